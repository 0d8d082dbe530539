// Scene files: the shipped cockpit loads as documented, and every bad value is an error naming
// file, line and key.

#include "physics_node/config/scene_config.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "common/pose.hpp"
#include "common/yaml_config.hpp"
#include "hand/config/hand_yaml.hpp"
#include "model/import/model_file.hpp"
#include "physics_node/physics/world.hpp"
#include "tests/support/process.hpp"
#include "tests/support/test_files.hpp"
#include "tests/unit/scene_error_cases.hpp"

namespace vcockpit {
namespace {

using test::read_text;
using test::source_dir;

using physics::ObjectSpec;
using physics::Scene;
using physics::ShapeKind;


// ---- world-frame boxes round objects: exact for boxes, spheres and cylinders ---------------

struct Aabb {
  Eigen::Vector3d lo;
  Eigen::Vector3d hi;
};

Eigen::Vector3d half_extents(const ObjectSpec& o) {
  const Eigen::Matrix3d R = o.X_GO.linear();
  const auto& s = o.shape;
  if (s.kind == ShapeKind::kBox) return R.cwiseAbs() * (0.5 * s.box_size_m);
  if (s.kind == ShapeKind::kSphere) return Eigen::Vector3d::Constant(s.radius_m);
  const Eigen::Vector3d axis = R.col(2);
  Eigen::Vector3d h;
  for (int i = 0; i < 3; ++i) {
    // a disk of radius r tilted to axis a reaches r sqrt(1 - a_i^2) along world axis i
    const double disk = s.kind == ShapeKind::kCapsule
                            ? s.radius_m
                            : s.radius_m * std::sqrt(std::max(0.0, 1.0 - axis[i] * axis[i]));
    h[i] = 0.5 * s.length_m * std::abs(axis[i]) + disk;
  }
  return h;
}

Aabb aabb(const ObjectSpec& o) {
  const Eigen::Vector3d c = o.X_GO.translation();
  const Eigen::Vector3d h = half_extents(o);
  return {c - h, c + h};
}

// Largest gap between two boxes along any axis (negative: they overlap on every axis).
double aabb_gap_m(const Aabb& a, const Aabb& b) {
  return (b.lo - a.hi).cwiseMax(a.lo - b.hi).maxCoeff();
}

// ---- the shipped cockpit --------------------------------------------------------------------

class ShippedCockpit : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { scene_ = new Scene(load_scene(path())); }
  static void TearDownTestSuite() {
    delete scene_;
    scene_ = nullptr;
  }
  static std::string path() { return source_dir() + "/config/cockpit.yaml"; }

  const ObjectSpec& object(const std::string& name) const {
    const int i = scene_->find_object(name);
    EXPECT_GE(i, 0) << name;
    return scene_->objects.at(static_cast<std::size_t>(std::max(i, 0)));
  }
  // the loose objects: dynamic, and not a control's moving part
  // the loose objects on the centre console (the heavy bar lies on the glareshield)
  std::vector<const ObjectSpec*> dynamic_objects() const {
    std::vector<const ObjectSpec*> out;
    for (const auto& o : scene_->objects) {
      if (o.dynamic && o.control < 0 && o.name != "heavy_bar") out.push_back(&o);
    }
    return out;
  }

  static Scene* scene_;
};
Scene* ShippedCockpit::scene_ = nullptr;

constexpr double kConsoleTop_m = 0.70;

TEST_F(ShippedCockpit, WorldAndHand) {
  EXPECT_EQ(scene_->gravity_mps2, Eigen::Vector3d(0.0, 0.0, -9.81));
  EXPECT_EQ(scene_->step_s, 0.001);
  // the pilot's two hands: hand.yaml's right hand and its mirror image on the left
  ASSERT_EQ(scene_->hands.size(), 2u);
  const hand::HandModel hand = load_hand_model(source_dir() + "/config/hand.yaml");
  EXPECT_EQ(scene_->hands[0].palm_size_m, hand.palm_size_m);
  EXPECT_FALSE(scene_->hands[0].left);
  EXPECT_EQ(scene_->hands[1].palm_size_m, hand.palm_size_m);
  EXPECT_TRUE(scene_->hands[1].left);
  EXPECT_EQ(physics::hand_id_of(scene_->hands[1]), 1);
  EXPECT_EQ(scene_->hand_material.stiffness_Npm, 2.0e4);
  EXPECT_EQ(scene_->hand_material.mu_s, 1.0);
}

TEST_F(ShippedCockpit, ObjectsKindsAndMasses) {
  const std::vector<std::string> statics = {
      "floor",     "instrument_panel", "glareshield",   "centre_console", "left_wall",
      "right_wall", "front_bulkhead",  "nose_bulkhead", "windscreen",     "back_wall",
      "left_window", "right_window",   "canopy",         "left_pedestal"};
  for (const auto& name : statics) {
    EXPECT_FALSE(object(name).dynamic) << name;
    EXPECT_EQ(object(name).shape.kind, ShapeKind::kBox) << name;
    EXPECT_EQ(object(name).mass_kg, 0.0) << name;
  }
  std::size_t lights = 0;
  for (const physics::ControlSpec& c : scene_->controls) lights += c.light_object >= 0 ? 1 : 0;
  EXPECT_EQ(lights, 4u) << "landing lights, fuel pump, engine start, gear down";
  EXPECT_EQ(scene_->objects.size(), statics.size() + 5 + scene_->controls.size() + lights);
  EXPECT_EQ(dynamic_objects().size(), 4u);
  EXPECT_EQ(object("cup").mass_kg, 0.2);
  EXPECT_EQ(object("checklist").mass_kg, 0.15);
  EXPECT_EQ(object("flashlight").mass_kg, 0.25);
  EXPECT_EQ(object("ball").mass_kg, 0.06);
  for (const ObjectSpec* o : dynamic_objects()) {
    // inertia from the shape at uniform density: I = m / V * unit-density inertia
    const Eigen::Matrix3d expected =
        o->mass_kg / o->shape.volume_m3() * o->shape.unit_density_inertia();
    EXPECT_TRUE(o->I_O.isApprox(expected, 1e-14)) << o->name;
    EXPECT_EQ(o->v_G, Eigen::Vector3d::Zero()) << o->name;
    EXPECT_LE(o->material.mu_d, o->material.mu_s) << o->name;
  }
}

// The cockpit's controls: what the issue asks of a default cockpit, each at rest where it starts.
TEST_F(ShippedCockpit, ControlsOfEveryKind) {
  using physics::ControlKind;
  std::map<ControlKind, int> kinds;
  int latching = 0, lit = 0, gated = 0, continuous = 0;
  for (const physics::ControlSpec& c : scene_->controls) {
    ++kinds[c.kind];
    latching += c.latching ? 1 : 0;
    lit += c.lit_when >= 0 ? 1 : 0;
    gated += c.gates.empty() ? 0 : 1;
    continuous += c.limited ? 0 : 1;
    EXPECT_EQ(scene_->objects[static_cast<std::size_t>(c.body)].name, c.name);
  }
  EXPECT_EQ(kinds[ControlKind::kPushButton], 2);
  EXPECT_EQ(kinds[ControlKind::kToggle], 3);
  EXPECT_EQ(kinds[ControlKind::kRotary], 2);
  EXPECT_EQ(kinds[ControlKind::kLever], 3);  // throttle, flaps, gear
  EXPECT_EQ(kinds[ControlKind::kGuard], 1);
  EXPECT_EQ(latching, 1);
  EXPECT_EQ(lit, 6);
  EXPECT_EQ(gated, 2);
  EXPECT_EQ(continuous, 1);
  // left alone for a second, no control moves off its position
  physics::World world(*scene_);
  for (int i = 0; i < 1000; ++i) {
    world.step();
    EXPECT_TRUE(world.control_events().empty()) << "at step " << i;
  }
}

TEST_F(ShippedCockpit, ConsoleAndFloorGeometry) {
  const ObjectSpec& console = object("centre_console");
  EXPECT_EQ(console.X_GO.translation(), Eigen::Vector3d(0.45, -0.35, 0.35));
  EXPECT_EQ(console.shape.box_size_m, Eigen::Vector3d(0.40, 0.30, 0.70));
  EXPECT_TRUE(console.X_GO.linear().isIdentity(0.0));
  EXPECT_EQ(aabb(console).hi.z(), kConsoleTop_m);
  EXPECT_EQ(aabb(object("floor")).hi.z(), 0.0);
  EXPECT_EQ(console.material.stiffness_Npm, 5.0e4);
  EXPECT_EQ(object("floor").material.stiffness_Npm, 5.0e4);
}

// The shell is drawn as config/models/cockpit/'s parts (looks) and collides as its boxes, so
// each look must keep to its box where hands and loose objects touch it: a console's top (what
// rests there would float or sink), the panel's face (a finger pressing a switch). And the model
// is the detailed cockpit the renderer is measured on.
TEST_F(ShippedCockpit, TheShellIsDrawnAsModelPartsThatKeepToTheTouchedFaces) {
  std::size_t triangles = 0;
  for (const char* name : {"floor", "instrument_panel", "glareshield", "centre_console",
                           "left_pedestal", "left_wall", "right_wall", "canopy"}) {
    const ObjectSpec& o = object(name);
    ASSERT_TRUE(o.look.has_value()) << name;
    EXPECT_EQ(o.look->kind, ShapeKind::kMesh) << name;
    EXPECT_EQ(o.shape.kind, ShapeKind::kBox) << name << " collides as its box";
    EXPECT_EQ(o.color_rgba, (std::array<float, 4>{1, 1, 1, 1})) << name << ": the model's colours";
    const model::TriangleMesh& mesh = *o.look->mesh;
    triangles += mesh.triangles.size();
    // wound counter-clockwise seen from outside, as its normals say: a triangle wound the other
    // way is lit as if it faced inward (the renderer turns a back face's normal round)
    ASSERT_EQ(mesh.normals.size(), mesh.vertices_m.size()) << name;
    std::size_t inward = 0;
    for (const auto& t : mesh.triangles) {
      const Eigen::Vector3d a = mesh.vertices_m[t[0]], b = mesh.vertices_m[t[1]], c = mesh.vertices_m[t[2]];
      const Eigen::Vector3d n = (b - a).cross(c - a);
      const Eigen::Vector3f shading = mesh.normals[t[0]] + mesh.normals[t[1]] + mesh.normals[t[2]];
      if (n.norm() > 1e-12 && n.dot(shading.cast<double>()) <= 0.0) ++inward;
    }
    EXPECT_EQ(inward, 0u) << name << ": of " << mesh.triangles.size() << " triangles";
  }
  EXPECT_GE(triangles, 100'000u);
  for (const char* name : {"centre_console", "left_pedestal"}) {
    const ObjectSpec& o = object(name);
    const Eigen::Vector3d half = 0.5 * o.shape.box_size_m;
    const model::Bounds& b = o.look->mesh_bounds;  // in the object's frame
    EXPECT_GE(b.max_m.z(), half.z()) << name;  // the top is there
    EXPECT_LE(b.max_m.z(), half.z() + 0.0005) << name << ": what rests on the top is drawn on it";
    for (int axis = 0; axis < 2; ++axis) {  // its sides, and a kick strip 3 mm proud
      EXPECT_LE(b.max_m[axis], half[axis] + 0.004) << name << " axis " << axis;
      EXPECT_GE(b.min_m[axis], -half[axis] - 0.004) << name << " axis " << axis;
    }
  }
  const ObjectSpec& panel = object("instrument_panel");  // its face is at x = -0.015
  EXPECT_GE(panel.look->mesh_bounds.min_m.x(), -0.015 - 0.005) << "a rim and screws at most";
  EXPECT_LE(panel.look->mesh_bounds.max_m.y(), 0.55 + 1e-6);
  EXPECT_LE(panel.look->mesh_bounds.max_m.z(), 0.175 + 1e-6);
}

TEST_F(ShippedCockpit, CupPose) {
  const ObjectSpec& cup = object("cup");
  EXPECT_TRUE(cup.dynamic);
  EXPECT_EQ(cup.shape.kind, ShapeKind::kCylinder);
  EXPECT_EQ(cup.shape.radius_m, 0.035);
  EXPECT_EQ(cup.shape.length_m, 0.10);
  EXPECT_EQ(cup.X_GO.translation(), Eigen::Vector3d(0.45, -0.35, 0.75));
  EXPECT_TRUE(cup.X_GO.linear().isIdentity(0.0));  // upright: axis along world z
}

TEST_F(ShippedCockpit, PanelTiltsBackFifteenDegrees) {
  const Eigen::Matrix3d R = object("instrument_panel").X_GO.linear();
  EXPECT_TRUE(R.isApprox(rotation_from_rpy(0.0, deg_to_rad(15.0), 0.0), 1e-15));
  // the panel's face (-x in its frame) looks back at the pilot and up toward the eyes
  const Eigen::Vector3d face = R * -Eigen::Vector3d::UnitX();
  EXPECT_LT(face.x(), 0.0);
  EXPECT_GT(face.z(), 0.0);
}

TEST_F(ShippedCockpit, LooseObjectsRestOnTheConsoleTop) {
  const Aabb top = aabb(object("centre_console"));
  for (const ObjectSpec* o : dynamic_objects()) {
    SCOPED_TRACE(o->name);
    // resting exactly: the lowest point on the top, no gap, no overlap
    EXPECT_NEAR(aabb(*o).lo.z(), kConsoleTop_m, 1e-12);
    // the centroid over the console, at least 2 cm inside its edges (the checklist overhangs)
    const Eigen::Vector3d c = o->X_GO.translation();
    EXPECT_GE(c.x() - top.lo.x(), 0.02);
    EXPECT_GE(top.hi.x() - c.x(), 0.02);
    EXPECT_GE(c.y() - top.lo.y(), 0.02);
    EXPECT_GE(top.hi.y() - c.y(), 0.02);
  }
  // all but the checklist lie wholly on the top
  for (const char* name : {"cup", "flashlight", "ball"}) {
    const Aabb box = aabb(object(name));
    EXPECT_GE(box.lo.x(), top.lo.x() - 1e-12) << name;
    EXPECT_LE(box.hi.x(), top.hi.x() + 1e-12) << name;
    EXPECT_GE(box.lo.y(), top.lo.y() - 1e-12) << name;
    EXPECT_LE(box.hi.y(), top.hi.y() + 1e-12) << name;
  }
  // the flashlight lies along x
  EXPECT_NEAR(object("flashlight").X_GO.linear().col(2).x(), 1.0, 1e-15);
}

// The two-handed lift's bar: 2.5 kg, lying along y exactly on the glareshield's top, touching no
// other static object and clear of every control's part.
TEST_F(ShippedCockpit, HeavyBarLiesAcrossTheGlareshield) {
  const ObjectSpec& bar = object("heavy_bar");
  EXPECT_TRUE(bar.dynamic);
  EXPECT_EQ(bar.mass_kg, 2.5);
  EXPECT_EQ(bar.shape.kind, ShapeKind::kCylinder);
  EXPECT_NEAR(std::abs(bar.X_GO.linear().col(2).y()), 1.0, 1e-12);
  const Aabb shield = aabb(object("glareshield"));
  EXPECT_NEAR(aabb(bar).lo.z(), shield.hi.z(), 1e-9);
  for (const ObjectSpec& o : scene_->objects) {
    if (&o == &bar || o.name == "glareshield") continue;
    EXPECT_GE(aabb_gap_m(aabb(bar), aabb(o)), 0.01) << o.name;
  }
}

// Bounding spheres cannot be used: a 22 x 15 cm board beside the cup on a 40 x 30 cm console
// always lies inside the cup's bounding sphere plus its own. World boxes are exact here (every
// object is axis-aligned or a cylinder) and a gap between boxes is a gap between the shapes.
TEST_F(ShippedCockpit, LooseObjectsAreAtLeastOneCentimetreApart) {
  const auto objects = dynamic_objects();
  for (std::size_t i = 0; i < objects.size(); ++i) {
    for (std::size_t j = i + 1; j < objects.size(); ++j) {
      EXPECT_GE(aabb_gap_m(aabb(*objects[i]), aabb(*objects[j])), 0.01 - 1e-12)
          << objects[i]->name << " vs " << objects[j]->name;
    }
  }
}

TEST_F(ShippedCockpit, LooseObjectsTouchNoStaticButTheConsole) {
  for (const ObjectSpec* o : dynamic_objects()) {
    for (const ObjectSpec& s : scene_->objects) {
      if (s.dynamic || s.name == "centre_console") continue;  // (a control's part is dynamic)
      EXPECT_GE(aabb_gap_m(aabb(*o), aabb(s)), 0.01) << o->name << " vs " << s.name;
    }
  }
}

TEST_F(ShippedCockpit, CockpitShellAroundThePilot) {
  EXPECT_NEAR(aabb(object("left_wall")).lo.y(), 0.60, 1e-12);
  EXPECT_NEAR(aabb(object("right_wall")).hi.y(), -0.60, 1e-12);
  const Aabb panel = aabb(object("instrument_panel"));
  EXPECT_NEAR(panel.lo.z(), 0.70, 0.01);
  EXPECT_NEAR(panel.hi.z(), 1.05, 0.01);
  EXPECT_NEAR(0.5 * (panel.lo.x() + panel.hi.x()), 0.80, 1e-12);
  EXPECT_NEAR(aabb(object("glareshield")).lo.z(), panel.hi.z(), 0.005);  // sits on the panel
}

TEST_F(ShippedCockpit, GraspAndContactBlocks) {
  EXPECT_EQ(scene_->grasp.xi_N, 3.0);
  EXPECT_EQ(scene_->grasp.eta_Nm, 0.3);
  EXPECT_EQ(scene_->grasp.alpha0_deg, 120.0);
  EXPECT_EQ(scene_->grasp.min_contacts, 3);
  EXPECT_EQ(scene_->grasp.exit_min_contacts, 2);
  EXPECT_EQ(scene_->grasp.gesture_rule, physics::GestureRule::kProject);
  EXPECT_EQ(scene_->grasp.hold_rule, physics::HoldRule::kTrackedGrip);
  EXPECT_DOUBLE_EQ(scene_->grasp.release_opening_share, 0.2);
  EXPECT_DOUBLE_EQ(scene_->grasp.release_gap_m, 0.005);
  EXPECT_EQ(scene_->contact.max_points_per_pair, 4);
}

// ---- a small valid scene, so each case can break one thing ----------------------------------

const char* const kValidScene = R"(gravity: [0, 0, -9.81]
step_s: 0.001
hand_material: {stiffness: 2.0e4, damping_ratio: 0.7, mu_s: 1.0, mu_d: 0.8}
objects:
  - name: table
    kind: static
    shape: {box: [1.0, 0.8, 0.1]}
    pose: {position: [0.5, 0.0, 0.65], rpy_deg: [0, 0, 0]}
    material: {stiffness: 5.0e4, damping_ratio: 0.9, mu_s: 0.6, mu_d: 0.5, mu_roll_m: 3.0e-4,
               mu_spin_m: 2.0e-3}
    color: [0.4, 0.4, 0.4]
  - name: mug
    kind: dynamic
    shape: {cylinder: [0.04, 0.1]}
    mass: 0.3
    pose: {position: [0.5, 0.0, 0.75], rpy_deg: [0, 0, 0]}
  - name: marble
    kind: dynamic
    shape: {sphere: 0.01}
    density: 2500
    pose: {position: [0.3, 0.1, 0.71]}
    velocity: {linear: [0.1, 0, 0], angular: [0, 0, 2]}
  - name: pen
    kind: dynamic
    shape: {capsule: [0.005, 0.12]}
    mass: 0.02
    inertia: [2.5e-5, 2.5e-5, 2.5e-7]
    pose: {position: [0.6, -0.2, 0.705], rpy_deg: [0, 90, 0]}
    material: {mu_s: 0.3, mu_d: 0.2}
    color: [0.1, 0.2, 0.9, 0.5]
grasp: {xi_N: 2.0, eta_Nm: 0.2, alpha0_deg: 110, min_contacts: 3}
contact: {slip_speed_mps: 0.002, max_substeps: 16}
)";

TEST(SceneConfig, ValidSceneParses) {
  const Scene scene = parse_scene(ConfigNode::load_string(kValidScene, "inline.yaml"), "");
  ASSERT_EQ(scene.objects.size(), 4u);
  EXPECT_FALSE(scene.has_hands());
  const ObjectSpec& table = scene.objects[0];
  EXPECT_FALSE(table.dynamic);
  EXPECT_EQ(table.material.damping_ratio, 0.9);
  EXPECT_EQ(table.material.mu_roll_m, 3.0e-4);
  EXPECT_EQ(table.material.mu_spin_m, 2.0e-3);
  EXPECT_EQ(table.color_rgba, (std::array<float, 4>{0.4f, 0.4f, 0.4f, 1.0f}));

  const ObjectSpec& mug = scene.objects[1];
  EXPECT_EQ(mug.mass_kg, 0.3);
  EXPECT_EQ(mug.material.stiffness_Npm, physics::Material{}.stiffness_Npm);  // defaults
  EXPECT_EQ(mug.material.mu_roll_m, physics::Material{}.mu_roll_m);
  EXPECT_EQ(mug.material.mu_spin_m, physics::Material{}.mu_spin_m);
  EXPECT_GT(physics::Material{}.mu_roll_m, 0.0) << "a little rolling resistance by default";
  EXPECT_GT(physics::Material{}.mu_spin_m, 0.0) << "and a little spinning resistance";
  EXPECT_EQ(mug.color_rgba, ObjectSpec{}.color_rgba);

  const ObjectSpec& marble = scene.objects[2];
  const double volume_m3 = 4.0 / 3.0 * std::numbers::pi * 1e-6;
  EXPECT_NEAR(marble.mass_kg, 2500.0 * volume_m3, 1e-15);
  EXPECT_NEAR(marble.I_O(0, 0), 0.4 * marble.mass_kg * 1e-4, 1e-18);
  EXPECT_TRUE(marble.X_GO.linear().isIdentity(0.0));  // rpy_deg omitted
  EXPECT_EQ(marble.v_G, Eigen::Vector3d(0.1, 0.0, 0.0));
  EXPECT_EQ(marble.w_G, Eigen::Vector3d(0.0, 0.0, 2.0));

  const ObjectSpec& pen = scene.objects[3];
  EXPECT_EQ(pen.shape.kind, ShapeKind::kCapsule);
  EXPECT_EQ(pen.I_O, Eigen::Vector3d(2.5e-5, 2.5e-5, 2.5e-7).asDiagonal().toDenseMatrix());
  EXPECT_EQ(pen.material.mu_s, 0.3);
  EXPECT_EQ(pen.material.stiffness_Npm, physics::Material{}.stiffness_Npm);
  EXPECT_EQ(pen.material.mu_roll_m, physics::Material{}.mu_roll_m);
  EXPECT_EQ(pen.color_rgba[3], 0.5f);
  EXPECT_NEAR(pen.X_GO.linear().col(2).x(), 1.0, 1e-15);

  EXPECT_EQ(scene.grasp.alpha0_deg, 110.0);
  EXPECT_EQ(scene.grasp.exit_scale, physics::GraspParams{}.exit_scale);  // not given: default
  EXPECT_EQ(scene.contact.slip_speed_mps, 0.002);  // (its max_substeps: 16 loads, and sets nothing)
  EXPECT_TRUE(scene.sleep.enabled);  // not given: resting objects sleep
  EXPECT_EQ(scene.sleep.time_s, physics::SleepParams{}.time_s);
}

// Scenes written when the contacts were stepped in substeps (recordings' scenes made by other
// sites carry contact.substep_safety and max_substeps) load, and those keys set nothing.
TEST(SceneConfig, ASceneWithTheOldSubstepSettingsLoadsAsOneWithout) {
  std::string without = kValidScene;
  const std::string old_line = "contact: {slip_speed_mps: 0.002, max_substeps: 16}";
  without.replace(without.find(old_line), old_line.size(), "contact: {slip_speed_mps: 0.002}");
  std::string with = kValidScene;
  with.replace(with.find(old_line), old_line.size(),
               "contact: {slip_speed_mps: 0.002, substep_safety: 0.05, max_substeps: 500, solver: soft}");
  const Scene a = parse_scene(ConfigNode::load_string(without, "without.yaml"), "");
  const Scene b = parse_scene(ConfigNode::load_string(with, "with.yaml"), "");
  EXPECT_EQ(a.contact.slip_speed_mps, b.contact.slip_speed_mps);
  EXPECT_EQ(a.contact.max_points_per_pair, b.contact.max_points_per_pair);
  EXPECT_EQ(a.contact.iterations, b.contact.iterations);
  EXPECT_EQ(a.contact.relax_iterations, b.contact.relax_iterations);
  EXPECT_EQ(a.contact.restitution_threshold_mps, b.contact.restitution_threshold_mps);
}

TEST(SceneConfig, SleepingIsReadAndCanBeTurnedOff) {
  const std::string text = std::string(kValidScene) + "sleep: {enabled: false, speed_mps: 0.02, time_s: 1.5}\n";
  const Scene scene = parse_scene(ConfigNode::load_string(text, "inline.yaml"), "");
  EXPECT_FALSE(scene.sleep.enabled);
  EXPECT_EQ(scene.sleep.speed_mps, 0.02);
  EXPECT_EQ(scene.sleep.time_s, 1.5);
}

// A cockpit whose parts are nodes of one model file (a static panel, a loose knob, a drawn
// bezel, a lever's moving part) has the file parsed once for the whole scene, not once a part.
TEST(SceneConfig, ThePartsOfOneModelFileAreReadInOneGo) {
  const std::string dir = test::make_temp_dir("vcockpit_one_file_cockpit");
  // a closed tetrahedron per moving part (its hull has a volume), a triangle for the panel
  const auto tetra = [](const char* name, int base, double x) {
    std::ostringstream o;
    o << "o " << name << "\n";
    for (const auto& v : {std::array<double, 3>{0, 0, 0}, {0.02, 0, 0}, {0, 0.02, 0}, {0, 0, 0.02}})
      o << "v " << v[0] + x << ' ' << v[1] << ' ' << v[2] << "\n";
    o << "f " << base << ' ' << base + 2 << ' ' << base + 1 << "\nf " << base << ' ' << base + 1
      << ' ' << base + 3 << "\nf " << base << ' ' << base + 3 << ' ' << base + 2 << "\nf "
      << base + 1 << ' ' << base + 2 << ' ' << base + 3 << "\n";
    return o.str();
  };
  std::ofstream(dir + "/cockpit.obj") << "o panel\nv -1 -1 0\nv 1 -1 0\nv 0 1 0\nf 1 2 3\n"
                                      << tetra("knob", 4, 0.0) << tetra("bezel", 8, 0.1)
                                      << tetra("handle", 12, 0.2);
  std::ofstream(dir + "/scene.yaml")
      << "gravity: [0, 0, -9.81]\nstep_s: 0.001\nobjects:\n"
         "  - {name: panel, kind: static, shape: {mesh: cockpit.obj, node: panel, up: z}, pose: {position: [0, 0, 0]}}\n"
         "  - {name: knob, kind: dynamic, mass: 0.05, shape: {mesh: cockpit.obj, node: knob, up: z},\n"
         "     pose: {position: [0, 0, 0.1]}}\n"
         "  - {name: rim, kind: static, shape: {box: [0.02, 0.02, 0.02]},\n"
         "     look: {mesh: cockpit.obj, node: bezel, up: z}, pose: {position: [0.3, 0, 0.1]}}\n"
         "controls:\n"
         "  - {name: lever, kind: lever, joint: revolute, pose: {position: [0.5, 0, 0.1]},\n"
         "     body: {shape: {mesh: cockpit.obj, node: handle, up: z}, mass: 0.1}, travel: [-10, 10],\n"
         "     positions: [{name: back, at: -10, enter: [-10, -8]}, {name: fore, at: 10, enter: [8, 10]}]}\n";
  const uint64_t reads = model::model_file_reads();
  const Scene scene = load_scene(dir + "/scene.yaml");
  EXPECT_EQ(model::model_file_reads(), reads + 1) << "the file parsed once for its four parts";
  ASSERT_EQ(scene.objects.size(), 4u);
  EXPECT_EQ(scene.objects[0].shape.mesh->triangles.size(), 1u);
  EXPECT_EQ(scene.objects[1].shape.hull->triangles.size(), 4u);
  EXPECT_EQ(scene.objects[2].look->mesh->triangles.size(), 4u);
  EXPECT_EQ(scene.objects[3].shape.hull->triangles.size(), 4u);
  // and a scene of one part a file reads it once, as ever
  std::ofstream(dir + "/one.yaml")
      << "gravity: [0, 0, -9.81]\nstep_s: 0.001\nobjects:\n"
         "  - {name: panel, kind: static, shape: {mesh: cockpit.obj, node: panel, up: z}, pose: {position: [0, 0, 0]}}\n";
  const uint64_t before = model::model_file_reads();
  load_scene(dir + "/one.yaml");
  EXPECT_EQ(model::model_file_reads(), before + 1);
}

TEST(SceneConfig, ZeroRollingAndSpinningResistanceAreAllowed) {
  std::string text = kValidScene;
  for (const auto& [from, to] : {std::pair<std::string, std::string>{"mu_roll_m: 3.0e-4", "mu_roll_m: 0"},
                                 {"mu_spin_m: 2.0e-3", "mu_spin_m: 0.0"}})
    text.replace(text.find(from), from.size(), to);
  const Scene scene = parse_scene(ConfigNode::load_string(text, "inline.yaml"), "");
  EXPECT_EQ(scene.objects[0].material.mu_roll_m, 0.0);
  EXPECT_EQ(scene.objects[0].material.mu_spin_m, 0.0);
}

TEST(SceneConfig, OptionalBlocksMayBeLeftOut) {
  const Scene scene = parse_scene(
      ConfigNode::load_string("gravity: [0, 0, -1.62]\nstep_s: 0.002\nobjects: []\n", "moon.yaml"),
      "");
  EXPECT_TRUE(scene.objects.empty());
  EXPECT_EQ(scene.gravity_mps2.z(), -1.62);
  EXPECT_EQ(scene.grasp.xi_N, physics::GraspParams{}.xi_N);
  EXPECT_EQ(scene.hand_material.stiffness_Npm, Scene{}.hand_material.stiffness_Npm);
}

// ---- bad input ------------------------------------------------------------------------------

TEST(SceneConfig, ValidSceneFileLoads) {
  EXPECT_EQ(load_error(write_file("valid.yaml", kValidScene)), "(no error)");
}

TEST(SceneConfig, EveryBadValueNamesFileLineAndKey) {
  const std::vector<BadCase> cases = {
      // sizes, masses, densities
      {"negative_mass", "mass: 0.3", "mass: -0.3", "mass: -0.3", "objects[1].mass",
       "mass must be positive, got -0.3"},
      {"zero_mass", "mass: 0.02", "mass: 0", "mass: 0\n", "objects[3].mass", "must be positive"},
      {"zero_density", "density: 2500", "density: 0", "density: 0", "objects[2].density",
       "density must be positive"},
      {"negative_density", "density: 2500", "density: -1", "density: -1", "objects[2].density",
       "must be positive"},
      {"not_a_number", "mass: 0.3", "mass: heavy", "mass: heavy", "objects[1].mass",
       "expected a number"},
      {"negative_box_size", "box: [1.0, 0.8, 0.1]", "box: [1.0, -0.8, 0.1]", "box: [1.0, -0.8",
       "objects[0].shape.box[1]", "size y must be positive"},
      {"box_two_numbers", "box: [1.0, 0.8, 0.1]", "box: [1.0, 0.8]", "box: [1.0, 0.8]",
       "objects[0].shape.box", "list of 3 numbers"},
      {"zero_sphere_radius", "sphere: 0.01", "sphere: 0", "sphere: 0", "objects[2].shape.sphere",
       "radius must be positive"},
      {"negative_capsule_length", "capsule: [0.005, 0.12]", "capsule: [0.005, -0.12]",
       "capsule:", "objects[3].shape.capsule[1]", "length must be positive"},
      {"zero_capsule_radius", "capsule: [0.005, 0.12]", "capsule: [0, 0.12]",
       "capsule:", "objects[3].shape.capsule[0]", "radius must be positive"},
      {"zero_cylinder_radius", "cylinder: [0.04, 0.1]", "cylinder: [0, 0.1]",
       "cylinder:", "objects[1].shape.cylinder[0]", "radius must be positive"},
      {"zero_cylinder_length", "cylinder: [0.04, 0.1]", "cylinder: [0.04, 0]",
       "cylinder:", "objects[1].shape.cylinder[1]", "length must be positive"},
      // materials
      {"zero_stiffness", "stiffness: 5.0e4", "stiffness: 0", "stiffness: 0",
       "objects[0].material.stiffness", "must be positive"},
      {"negative_stiffness", "stiffness: 5.0e4", "stiffness: -5", "stiffness: -5",
       "objects[0].material.stiffness", "must be positive"},
      {"mu_d_above_mu_s", "mu_s: 0.6, mu_d: 0.5", "mu_s: 0.6, mu_d: 0.7", "mu_d: 0.7",
       "objects[0].material.mu_d", "mu_d 0.7 is greater than mu_s 0.6"},
      {"mu_d_above_default_mu_s", "material: {mu_s: 0.3, mu_d: 0.2}", "material: {mu_d: 0.7}",
       "mu_d: 0.7", "objects[3].material.mu_d", "greater than mu_s 0.6"},
      {"mu_s_below_default_mu_d", "material: {mu_s: 0.3, mu_d: 0.2}", "material: {mu_s: 0.3}",
       "material: {mu_s: 0.3}", "objects[3].material.mu_s", "mu_d 0.4 is greater than mu_s 0.3"},
      {"negative_mu", "mu_s: 0.3, mu_d: 0.2", "mu_s: -0.3, mu_d: 0.2", "mu_s: -0.3",
       "objects[3].material.mu_s", "must be >= 0"},
      {"negative_mu_d", "mu_s: 0.3, mu_d: 0.2", "mu_s: 0.3, mu_d: -0.2", "mu_d: -0.2",
       "objects[3].material.mu_d", "must be >= 0"},
      {"negative_damping", "damping_ratio: 0.9", "damping_ratio: -0.9", "damping_ratio: -0.9",
       "objects[0].material.damping_ratio", "must be >= 0"},
      {"negative_mu_roll", "mu_roll_m: 3.0e-4", "mu_roll_m: -3.0e-4", "mu_roll_m: -3.0e-4",
       "objects[0].material.mu_roll_m", "must be >= 0, got -0.0003"},
      {"mu_roll_not_a_number", "mu_roll_m: 3.0e-4", "mu_roll_m: small", "mu_roll_m: small",
       "objects[0].material.mu_roll_m", "expected a number"},
      {"mu_roll_without_unit", "mu_roll_m: 3.0e-4", "mu_roll: 3.0e-4", "mu_roll: 3.0e-4",
       "objects[0].material.mu_roll", "unknown key 'mu_roll'"},
      {"negative_mu_spin", "mu_spin_m: 2.0e-3", "mu_spin_m: -2.0e-3", "mu_spin_m: -2.0e-3",
       "objects[0].material.mu_spin_m", "must be >= 0, got -0.002"},
      {"negative_hand_mu_roll", "mu_s: 1.0, mu_d: 0.8}", "mu_s: 1.0, mu_d: 0.8, mu_roll_m: -1}",
       "hand_material:", "hand_material.mu_roll_m", "must be >= 0"},
      {"unknown_material_key", "material: {mu_s: 0.3, mu_d: 0.2}",
       "material: {mu_s: 0.3, mu_d: 0.2, k: 5}", "k: 5", "objects[3].material.k",
       "unknown key 'k'"},
      {"hand_material", "mu_s: 1.0, mu_d: 0.8}", "mu_s: 0.5, mu_d: 0.8}",
       "hand_material:", "hand_material.mu_d", "greater than mu_s 0.5"},
      // shapes and kinds
      {"unknown_shape", "sphere: 0.01", "cube: 0.01", "cube: 0.01", "objects[2].shape.cube",
       "unknown key 'cube'"},
      {"two_shapes", "{sphere: 0.01}", "{sphere: 0.01, box: [1, 1, 1]}", "shape: {sphere",
       "objects[2].shape", "exactly one of box, sphere, capsule, cylinder, mesh, found 2"},
      {"empty_shape", "shape: {sphere: 0.01}", "shape: {}", "shape: {}", "objects[2].shape",
       "exactly one of box, sphere, capsule, cylinder, mesh, found 0"},
      {"mesh_missing", "shape: {sphere: 0.01}", "shape: {mesh: no_such.glb, node: cap}", "shape: {mesh",
       "objects[2].shape.mesh", "no_such.glb: no such file"},
      {"mesh_bad_up", "shape: {sphere: 0.01}", "shape: {mesh: no_such.glb, up: x}", "shape: {mesh",
       "objects[2].shape.up", "up must be y or z, not 'x'"},
      {"mesh_unknown_key", "shape: {sphere: 0.01}", "shape: {mesh: no_such.glb, units: mm}", "shape: {mesh",
       "objects[2].shape.units", "unknown key 'units'"},
      {"mesh_bad_scale", "shape: {sphere: 0.01}", "shape: {mesh: no_such.glb, scale: 0}", "shape: {mesh",
       "objects[2].shape.scale", "scale"},
      {"look_missing", "    color: [0.4, 0.4, 0.4]\n",
       "    color: [0.4, 0.4, 0.4]\n    look: {mesh: no_such.glb, node: Panel}\n", "look: {mesh",
       "objects[0].look.mesh", "no_such.glb: no such file"},
      {"look_unknown_key", "    color: [0.4, 0.4, 0.4]\n",
       "    color: [0.4, 0.4, 0.4]\n    look: {mesh: no_such.glb, units: mm}\n", "look: {mesh",
       "objects[0].look.units", "unknown key 'units'"},
      {"look_on_dynamic", "    mass: 0.3\n", "    mass: 0.3\n    look: {mesh: no_such.glb}\n",
       "look: {mesh", "objects[1].look", "a look is for a static object"},
      {"shape_not_a_map", "shape: {sphere: 0.01}", "shape: sphere", "shape: sphere",
       "objects[2].shape", "expected a map"},
      {"unknown_kind", "kind: static", "kind: fixed", "kind: fixed", "objects[0].kind",
       "unknown kind 'fixed'"},
      // names and fields
      {"duplicate_name", "name: marble", "name: mug",
       "name: mug\n    kind: dynamic\n    shape: {sph", "objects[2].name",
       "duplicate object name 'mug' (first used on line 12)"},
      {"empty_name", "name: marble", "name: ''", "name: ''", "objects[2].name",
       "must not be empty"},
      {"missing_pose", "    pose: {position: [0.3, 0.1, 0.71]}\n", "", "name: marble", "objects[2]",
       "missing required key 'pose'"},
      {"missing_position", "pose: {position: [0.3, 0.1, 0.71]}", "pose: {rpy_deg: [0, 0, 0]}",
       "pose: {rpy_deg", "objects[2].pose", "missing required key 'position'"},
      {"missing_kind", "    kind: static\n", "", "name: table", "objects[0]",
       "missing required key 'kind'"},
      {"unknown_key", "    color: [0.4, 0.4, 0.4]\n", "    colour: [0.4, 0.4, 0.4]\n",
       "colour:", "objects[0].colour", "unknown key 'colour'"},
      {"unknown_pose_key", "rpy_deg: [0, 90, 0]", "rpy: [0, 90, 0]", "rpy: [0, 90, 0]",
       "objects[3].pose.rpy", "unknown key 'rpy'"},
      {"unknown_top_key", "step_s: 0.001\n", "step_s: 0.001\nstep_ms: 1\n", "step_ms", "step_ms",
       "unknown key 'step_ms'"},
      {"missing_step", "step_s: 0.001\n", "", "gravity:", "(top level)",
       "missing required key 'step_s'"},
      // mass and density rules
      {"mass_and_density", "density: 2500", "density: 2500\n    mass: 0.1", "density: 2500",
       "objects[2].density", "either mass or density, not both"},
      {"dynamic_without_mass", "    mass: 0.3\n", "", "name: mug", "objects[1]",
       "needs 'mass' or 'density'"},
      {"static_with_mass", "    color: [0.4, 0.4, 0.4]\n",
       "    color: [0.4, 0.4, 0.4]\n    mass: 10\n", "mass: 10", "objects[0].mass",
       "a static object has no mass"},
      {"static_with_density", "    color: [0.4, 0.4, 0.4]\n",
       "    color: [0.4, 0.4, 0.4]\n    density: 700\n", "density: 700", "objects[0].density",
       "a static object has no density"},
      {"static_with_velocity", "    color: [0.4, 0.4, 0.4]\n",
       "    color: [0.4, 0.4, 0.4]\n    velocity: {linear: [1, 0, 0]}\n",
       "velocity:", "objects[0].velocity", "a static object has no velocity"},
      {"inertia_zero", "inertia: [2.5e-5, 2.5e-5, 2.5e-7]", "inertia: [2.5e-5, 2.5e-5, 0]",
       "inertia:", "objects[3].inertia[2]", "izz must be positive"},
      {"inertia_negative", "inertia: [2.5e-5, 2.5e-5, 2.5e-7]", "inertia: [-2.5e-5, 2.5e-5, 1]",
       "inertia:", "objects[3].inertia[0]", "ixx must be positive"},
      {"inertia_triangle", "inertia: [2.5e-5, 2.5e-5, 2.5e-7]", "inertia: [2.5e-5, 2.5e-5, 1e-4]",
       "inertia:", "objects[3].inertia", "triangle inequality"},
      {"unknown_velocity_key", "angular: [0, 0, 2]", "spin: [0, 0, 2]",
       "spin:", "objects[2].velocity.spin", "unknown key 'spin'"},
      // world
      {"step_zero", "step_s: 0.001", "step_s: 0", "step_s: 0", "step_s", "must be in (0, 0.1]"},
      {"step_too_long", "step_s: 0.001", "step_s: 0.5", "step_s: 0.5", "step_s",
       "must be in (0, 0.1], got 0.5"},
      {"gravity_two_numbers", "gravity: [0, 0, -9.81]", "gravity: [0, -9.81]",
       "gravity:", "gravity", "expected a list of 3 numbers"},
      {"gravity_word", "gravity: [0, 0, -9.81]", "gravity: down", "gravity:", "gravity",
       "expected a list of 3 numbers"},
      // colours
      {"color_component", "color: [0.4, 0.4, 0.4]", "color: [0.4, 1.5, 0.4]", "color: [0.4, 1.5",
       "objects[0].color[1]", "must be in [0, 1], got 1.5"},
      {"color_negative", "color: [0.1, 0.2, 0.9, 0.5]", "color: [0.1, 0.2, 0.9, -0.5]",
       "color: [0.1, 0.2, 0.9, -0.5]", "objects[3].color[3]", "must be in [0, 1]"},
      {"color_count", "color: [0.4, 0.4, 0.4]", "color: [0.4, 0.4]", "color: [0.4, 0.4]",
       "objects[0].color", "[r, g, b] or [r, g, b, a]"},
      // grasp and contact
      {"min_contacts_zero", "min_contacts: 3", "min_contacts: 0", "grasp:", "grasp.min_contacts",
       "must be an integer in [1, 16], got 0"},
      {"min_contacts_fraction", "min_contacts: 3", "min_contacts: 2.5",
       "grasp:", "grasp.min_contacts", "expected an integer"},
      {"alpha0_180", "alpha0_deg: 110", "alpha0_deg: 180", "grasp:", "grasp.alpha0_deg",
       "must be in (0, 180), got 180"},
      {"alpha0_zero", "alpha0_deg: 110", "alpha0_deg: 0", "grasp:", "grasp.alpha0_deg",
       "must be in (0, 180)"},
      {"xi_negative", "xi_N: 2.0", "xi_N: -2.0", "grasp:", "grasp.xi_N", "must be positive"},
      {"exit_scale_below_one", "min_contacts: 3}", "min_contacts: 3, exit_scale: 0.5}",
       "grasp:", "grasp.exit_scale", "must be >= 1"},
      {"exit_margin_above_alpha0", "min_contacts: 3}",
       "min_contacts: 3, exit_alpha_margin_deg: 120}", "grasp:", "grasp.exit_alpha_margin_deg",
       "must be below alpha0_deg 110"},
      {"exit_contacts_above_entry", "min_contacts: 3}", "min_contacts: 3, exit_min_contacts: 4}",
       "grasp:", "grasp.exit_min_contacts", "must not exceed min_contacts 3"},
      {"negative_hold", "min_contacts: 3}", "min_contacts: 3, min_hold_s: -1}",
       "grasp:", "grasp.min_hold_s", "must be >= 0"},
      {"unknown_grasp_key", "min_contacts: 3}", "min_contacts: 3, xi: 1}", "grasp:", "grasp.xi",
       "unknown key 'xi'"},
      {"gesture_rule_unknown", "min_contacts: 3}", "min_contacts: 3, gesture_rule: maybe}",
       "grasp:", "grasp.gesture_rule", "expected project, paper or none"},
      {"hold_rule_unknown", "min_contacts: 3}", "min_contacts: 3, hold_rule: forces}",
       "grasp:", "grasp.hold_rule", "expected grip"},
      {"opening_share_of_one", "min_contacts: 3}", "min_contacts: 3, release_opening_share: 1.0}",
       "grasp:", "grasp.release_opening_share", "must be in [0, 1)"},
      {"release_gap_zero", "min_contacts: 3}", "min_contacts: 3, release_gap_m: 0}",
       "grasp:", "grasp.release_gap_m", "must be positive"},
      {"max_substeps_zero", "max_substeps: 16", "max_substeps: 0",
       "contact:", "contact.max_substeps", "must be an integer in [1, 1000]"},
      {"substep_safety_above_one", "max_substeps: 16", "max_substeps: 16, substep_safety: 2",
       "contact:", "contact.substep_safety", "must be in (0, 1]"},
      {"slip_speed_zero", "slip_speed_mps: 0.002", "slip_speed_mps: 0",
       "contact:", "contact.slip_speed_mps", "must be positive"},
      {"unknown_contact_key", "max_substeps: 16", "max_substeps: 16, points: 4",
       "contact:", "contact.points", "unknown key 'points'"},
      // the proxy hand
      {"proxy_static_depth_above_1mm", "contact: {slip_speed_mps: 0.002, max_substeps: 16}", "contact: {slip_speed_mps: 0.002, max_substeps: 16}\nproxy: {static_depth_m: 0.002}",
       "proxy:", "proxy.static_depth_m", "must be in (0, 0.001]"},
      {"proxy_push_faster_than_max", "contact: {slip_speed_mps: 0.002, max_substeps: 16}",
       "contact: {slip_speed_mps: 0.002, max_substeps: 16}\nproxy: {max_speed_mps: 1, push_speed_mps: 2}", "proxy:",
       "proxy.push_speed_mps", "must not exceed max_speed_mps 1"},
      {"proxy_finger_pull_negative", "contact: {slip_speed_mps: 0.002, max_substeps: 16}", "contact: {slip_speed_mps: 0.002, max_substeps: 16}\nproxy: {finger_pull_ratio: -1}",
       "proxy:", "proxy.finger_pull_ratio", "must be in [0, 100]"},
      {"proxy_pass_through_negative", "contact: {slip_speed_mps: 0.002, max_substeps: 16}", "contact: {slip_speed_mps: 0.002, max_substeps: 16}\nproxy: {pass_through_depth_m: -0.001}",
       "proxy:", "proxy.pass_through_depth_m", "must be >= 0"},
      {"proxy_grip_force_zero", "contact: {slip_speed_mps: 0.002, max_substeps: 16}", "contact: {slip_speed_mps: 0.002, max_substeps: 16}\nproxy: {grip_force_N: 0}",
       "proxy:", "proxy.grip_force_N", "must be positive"},
      {"proxy_unknown_key", "contact: {slip_speed_mps: 0.002, max_substeps: 16}", "contact: {slip_speed_mps: 0.002, max_substeps: 16}\nproxy: {speed: 1}", "proxy:",
       "proxy.speed", "unknown key 'speed'"},
      {"contact_solver_unknown", "contact: {slip_speed_mps: 0.002, max_substeps: 16}",
       "contact: {slip_speed_mps: 0.002, max_substeps: 16, solver: implicit}", "contact:",
       "contact.solver", "the only value is soft"},
      // the explicit penalty path is gone: a scene asking for it is told so
      {"contact_solver_penalty", "contact: {slip_speed_mps: 0.002, max_substeps: 16}",
       "contact: {slip_speed_mps: 0.002, max_substeps: 16, solver: penalty}", "contact:",
       "contact.solver", "the explicit penalty path and its substeps were removed"},
      {"contact_iterations_zero", "contact: {slip_speed_mps: 0.002, max_substeps: 16}",
       "contact: {slip_speed_mps: 0.002, max_substeps: 16, iterations: 0}", "contact:",
       "contact.iterations", "1"},
      // sleeping
      {"sleep_speed_zero", "contact: {slip_speed_mps: 0.002, max_substeps: 16}",
       "contact: {slip_speed_mps: 0.002, max_substeps: 16}\nsleep: {speed_mps: 0}", "sleep:",
       "sleep.speed_mps", "must be positive"},
      {"sleep_time_negative", "contact: {slip_speed_mps: 0.002, max_substeps: 16}",
       "contact: {slip_speed_mps: 0.002, max_substeps: 16}\nsleep: {time_s: -1}", "sleep:",
       "sleep.time_s", "must be positive"},
      {"sleep_unknown_key", "contact: {slip_speed_mps: 0.002, max_substeps: 16}",
       "contact: {slip_speed_mps: 0.002, max_substeps: 16}\nsleep: {linear_mps: 0.01}", "sleep:",
       "sleep.linear_mps", "unknown key 'linear_mps'"},
      // the hand file
      {"hand_file_missing", "step_s: 0.001\n", "step_s: 0.001\nhand: no_such_hand.yaml\n",
       "hand: no_such", "hand", "cannot open hand file"},
      {"hands_not_a_list", "step_s: 0.001\n", "step_s: 0.001\nhands: hand.yaml\n", "hands: hand",
       "hands", "expected a list of one or two hands"},
      {"hands_three", "step_s: 0.001\n", "step_s: 0.001\nhands: [a.yaml, b.yaml, c.yaml]\n", "hands: [",
       "hands", "expected a list of one or two hands"},
      {"hands_file_missing", "step_s: 0.001\n", "step_s: 0.001\nhands: [{file: no_such_hand.yaml, side: left}]\n",
       "hands: [", "hands[0].file", "cannot open hand file"},
  };
  for (const BadCase& c : cases)
    expect_error(c, kValidScene);
}

std::string parse_error(const std::string& text, const std::string& name) {
  try {
    parse_scene(ConfigNode::load_string(text, name), "");
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(SceneConfig, ObjectsListIsRequiredAndMustBeAList) {
  const std::string head = "gravity: [0, 0, -9.81]\nstep_s: 0.001\n";
  expect_error_at(parse_error(head, "none.yaml"), "none.yaml", 1, "(top level)",
                  "missing required key 'objects'");
  expect_error_at(parse_error(head + "objects: {cup: 1}\n", "map.yaml"), "map.yaml", 3, "objects",
                  "expected a list, found a map");
  expect_error_at(parse_error(head + "objects:\n  - cup\n", "scalar.yaml"), "scalar.yaml", 4,
                  "objects[0]", "expected a map");
}

// The hand path is relative to the scene file's directory, wherever the program runs.
TEST(SceneConfig, HandIsLoadedRelativeToTheSceneFile) {
  write_file("relative/hands/my_hand.yaml", read_text(source_dir() + "/config/hand.yaml"));
  const std::string scene_path =
      write_file("relative/scene.yaml", std::string("hand: hands/my_hand.yaml\n") + kValidScene);
  const Scene scene = load_scene(scene_path);
  ASSERT_TRUE(scene.has_hands());
  EXPECT_EQ(scene.hands[0].palm_size_m,
            load_hand_model(source_dir() + "/config/hand.yaml").palm_size_m);
}

// Errors inside the hand file come from the hand loader and name the hand file, not the scene.
TEST(SceneConfig, HandFileErrorsNameTheHandFile) {
  std::string hand = read_text(source_dir() + "/config/hand.yaml");
  const auto at = hand.find("\nside: right");
  ASSERT_NE(at, std::string::npos);
  hand.replace(at, std::string("\nside: right").size(), "\nside: both");
  const std::string hand_path = write_file("bad_hand/bad_hand.yaml", hand);
  const std::string scene_path =
      write_file("bad_hand/scene.yaml", std::string("hand: bad_hand.yaml\n") + kValidScene);
  expect_error_at(load_error(scene_path), hand_path, line_of(hand, at + 1), "side",
                  "right or left");
}

TEST(SceneConfig, SyntaxErrorsAndMissingFilesAreConfigErrors) {
  const std::string bad = write_file("syntax.yaml", "objects: [\n  - name: a\n");
  EXPECT_NE(load_error(bad).find(bad + ":"), std::string::npos) << load_error(bad);
  EXPECT_THROW(load_scene("/nonexistent_vcockpit_dir/none.yaml"), ConfigError);
}

}  // namespace
}  // namespace vcockpit
