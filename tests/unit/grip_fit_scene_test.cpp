// grip_fit's scene (physics_node/fit/grip_scene_layout.hpp,
// physics_node/config/grip_scene_yaml.hpp): the pedestal and table under a placed object, and the
// file the project's scene loader reads back with the object's pose, the hand of the log's side and
// the cockpit's settings; a bad cockpit file is named and leaves no file.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/pose.hpp"
#include "physics_node/config/grip_scene_yaml.hpp"
#include "physics_node/config/scene_config.hpp"
#include "physics_node/fit/grip_hand.hpp"
#include "tests/support/process.hpp"
#include "tests/unit/grip_fit_samples.hpp"

namespace vcockpit {
namespace {

namespace fs = std::filesystem;
using physics::Shape;

// A 3 cm bar lying along world y 4 cm under the fist's palm, turned 20 deg.
Eigen::Isometry3d bar_pose(const fit::GripHand& hand) {
  Eigen::Isometry3d X_GO = Eigen::Isometry3d::Identity();
  X_GO.translation() = hand.X_GP.translation() - Eigen::Vector3d(0.0, 0.0, 0.04);
  X_GO.linear() = (Eigen::AngleAxisd(deg_to_rad(110.0), Eigen::Vector3d::UnitZ()) *
                   Eigen::AngleAxisd(0.5 * M_PI, Eigen::Vector3d::UnitY()))
                      .toRotationMatrix();
  return X_GO;
}

GripSceneSpec bar_spec(const fit::GripHand& hand) {
  GripSceneSpec spec;
  spec.object_name = "bar";
  spec.shape = Shape::cylinder(0.015, 0.12);
  spec.X_GO = bar_pose(hand);
  spec.mass_kg = 0.07;
  spec.layout = fit::lay_out_supports(hand, spec.shape, spec.X_GO);
  spec.hand_path = test::source_dir() + "/config/hand.yaml";
  spec.cockpit_path = test::source_dir() + "/config/cockpit.yaml";
  spec.comments = {"a test scene", "second line"};
  return spec;
}

const physics::ObjectSpec& object(const physics::Scene& scene, const std::string& name) {
  const int i = scene.find_object(name);
  EXPECT_GE(i, 0) << name;
  return scene.objects.at(static_cast<std::size_t>(std::max(i, 0)));
}

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

double top_z(const physics::ObjectSpec& box) {
  return box.X_GO.translation().z() + 0.5 * box.shape.box_size_m.z();
}
double bottom_z(const physics::ObjectSpec& box) {
  return box.X_GO.translation().z() - 0.5 * box.shape.box_size_m.z();
}

TEST(GripFitScene, PedestalTouchesTheObjectFromBelowOnATableUnderTheHand) {
  const fit::GripHand hand = fit::grip_hand_at(test::grip_fit_hand(), test::fist_sample());
  const Shape bar = Shape::cylinder(0.015, 0.12);
  fit::LayoutRule core_rule;
  core_rule.extend_m = 0.0;  // the core alone: its sides not pushed out
  const fit::GripSceneLayout core = fit::lay_out_supports(hand, bar, bar_pose(hand), core_rule);
  const double lowest_z = bar_pose(hand).translation().z() - 0.015;
  EXPECT_NEAR(core.object_lowest_z_m, lowest_z, 1e-12);
  EXPECT_NEAR(core.pedestal.p_G.z() + 0.5 * core.pedestal.size_m.z(), lowest_z, 1e-12);
  // along the bar's axis (yaw 110 deg), 60 % of its length and width, unless the hand is in the way
  EXPECT_NEAR(core.pedestal.yaw_rad, deg_to_rad(110.0), 1e-9);
  EXPECT_NEAR(core.pedestal.size_m.x(), core.footprint_share * 0.12, 1e-9);
  EXPECT_NEAR(core.pedestal.size_m.y(), core.footprint_share * 0.03, 1e-9);
  EXPECT_TRUE(core.pedestal_clearance_m >= 1e-3 || core.footprint_share < 0.21);
  EXPECT_NEAR((core.pedestal.p_G - bar_pose(hand).translation()).head<2>().norm(), 0.0, 1e-12);

  // by default its sides are then pushed out as far as the hand leaves room, up to 6 cm beyond
  // the bar: the core within it, the same top, still clear of the hand
  const fit::GripSceneLayout layout = fit::lay_out_supports(hand, bar, bar_pose(hand));
  EXPECT_DOUBLE_EQ(layout.footprint_share, core.footprint_share);
  EXPECT_NEAR(layout.pedestal.p_G.z(), core.pedestal.p_G.z(), 1e-12);
  EXPECT_NEAR(layout.pedestal.size_m.z(), core.pedestal.size_m.z(), 1e-12);
  EXPECT_NEAR(layout.pedestal.yaw_rad, core.pedestal.yaw_rad, 1e-12);
  const Eigen::Matrix2d R_GS = Eigen::Rotation2Dd(layout.pedestal.yaw_rad).toRotationMatrix();
  const Eigen::Vector2d centre_S =
      R_GS.transpose() * (layout.pedestal.p_G - core.pedestal.p_G).head<2>();
  for (int a = 0; a < 2; ++a) {
    const double half = 0.5 * layout.pedestal.size_m[a];
    EXPECT_LE(centre_S[a] - half, -0.5 * core.pedestal.size_m[a] + 1e-12) << a;
    EXPECT_GE(centre_S[a] + half, 0.5 * core.pedestal.size_m[a] - 1e-12) << a;
    const double object_half = a == 0 ? 0.06 : 0.015;
    EXPECT_GE(centre_S[a] - half, -object_half - 0.06 - 1e-9) << a;
    EXPECT_LE(centre_S[a] + half, object_half + 0.06 + 1e-9) << a;
  }
  EXPECT_GT(layout.pedestal.size_m.x() * layout.pedestal.size_m.y(),
            core.pedestal.size_m.x() * core.pedestal.size_m.y());
  if (core.pedestal_clearance_m >= 1e-3) {
    EXPECT_GE(layout.pedestal_clearance_m, 1e-3);
  }
  ASSERT_TRUE(layout.table);
  const double table_top_z = layout.table->p_G.z() + 0.5 * layout.table->size_m.z();
  EXPECT_NEAR(table_top_z, layout.pedestal.p_G.z() - 0.5 * layout.pedestal.size_m.z(), 1e-12);
  EXPECT_LE(table_top_z, fit::hand_lowest_z_m(hand) - 0.01 + 1e-12);
  EXPECT_LE(table_top_z, lowest_z - 0.02 + 1e-12);
  // an object at the floor has nowhere to stand
  Eigen::Isometry3d low = bar_pose(hand);
  low.translation().z() = 0.01;
  EXPECT_THROW(fit::lay_out_supports(hand, bar, low), std::invalid_argument);
}

TEST(GripFitScene, TheWrittenSceneLoadsWithThePoseTheHandAndTheCockpitsSettings) {
  const hand::HandModel model = test::grip_fit_hand();
  const fit::GripHand hand = fit::grip_hand_at(model, test::fist_sample());
  const GripSceneSpec spec = bar_spec(hand);
  const std::string dir = test::make_temp_dir("grip_fit_scene");
  const std::string path = dir + "/scene.yaml";
  write_grip_scene(spec, path);
  EXPECT_FALSE(fs::exists(path + ".partial"));

  const physics::Scene scene = load_scene(path);
  const physics::Scene cockpit = load_scene(spec.cockpit_path);
  const physics::ObjectSpec& bar = object(scene, "bar");
  EXPECT_TRUE(bar.dynamic);
  EXPECT_EQ(bar.shape.kind, physics::ShapeKind::kCylinder);
  EXPECT_DOUBLE_EQ(bar.shape.radius_m, 0.015);
  EXPECT_DOUBLE_EQ(bar.mass_kg, 0.07);
  EXPECT_LT((bar.X_GO.translation() - spec.X_GO.translation()).norm(), 1e-6);
  EXPECT_NEAR(std::abs(bar.X_GO.linear().col(2).dot(spec.X_GO.linear().col(2))), 1.0, 1e-10);
  const physics::Material& cup = object(cockpit, "cup").material;
  EXPECT_EQ(bar.material.stiffness_Npm, cup.stiffness_Npm);
  EXPECT_EQ(bar.material.mu_s, cup.mu_s);
  EXPECT_EQ(bar.material.mu_d, cup.mu_d);
  EXPECT_EQ(bar.material.damping_ratio, cup.damping_ratio);

  const physics::ObjectSpec& pedestal = object(scene, "pedestal");
  const physics::ObjectSpec& table = object(scene, "table");
  EXPECT_FALSE(pedestal.dynamic);
  EXPECT_FALSE(table.dynamic);
  EXPECT_NEAR(top_z(pedestal), bar.X_GO.translation().z() - 0.015, 2e-6);
  EXPECT_NEAR(top_z(table), bottom_z(pedestal), 2e-6);
  EXPECT_NEAR(top_z(object(scene, "floor")), 0.0, 1e-12);

  ASSERT_EQ(scene.hands.size(), 1u);
  EXPECT_FALSE(scene.hands[0].left);
  EXPECT_EQ(scene.hands[0].capsules[5].radius_m, model.capsules[5].radius_m);
  EXPECT_EQ(scene.gravity_mps2, cockpit.gravity_mps2);
  EXPECT_EQ(scene.step_s, cockpit.step_s);
  EXPECT_EQ(scene.hand_material.mu_s, cockpit.hand_material.mu_s);
  EXPECT_EQ(scene.grasp.xi_N, cockpit.grasp.xi_N);
  EXPECT_EQ(scene.grasp.alpha0_deg, cockpit.grasp.alpha0_deg);
  EXPECT_EQ(scene.grasp.gesture_rule, cockpit.grasp.gesture_rule);
  EXPECT_EQ(scene.grasp.min_hold_s, cockpit.grasp.min_hold_s);
  EXPECT_EQ(scene.contact.iterations, cockpit.contact.iterations);
  EXPECT_EQ(scene.contact.slip_speed_mps, cockpit.contact.slip_speed_mps);

  // the header says what made it
  EXPECT_EQ(read_text(path).rfind("# a test scene\n# second line\n", 0), 0u);
}

TEST(GripFitScene, TheHandIsReferencedRelativeToTheScene) {
  const fit::GripHand hand = fit::grip_hand_at(test::grip_fit_hand(), test::fist_sample());
  const std::string dir = test::make_temp_dir("grip_fit_scene");
  fs::create_directories(dir + "/hands");
  fs::create_directories(dir + "/scenes");
  fs::copy_file(test::source_dir() + "/config/hand.yaml", dir + "/hands/my hand.yaml");
  GripSceneSpec spec = bar_spec(hand);
  spec.hand_path = dir + "/hands/my hand.yaml";
  write_grip_scene(spec, dir + "/scenes/scene.yaml");
  EXPECT_NE(read_text(dir + "/scenes/scene.yaml")
                .find("hands: [{file: '../hands/my hand.yaml', side: right}]"),
            std::string::npos)
      << read_text(dir + "/scenes/scene.yaml");
  // moved together, the scene still finds its hand
  fs::rename(dir + "/hands", dir + "/moved_hands");
  fs::create_directories(dir + "/elsewhere");
  fs::rename(dir + "/moved_hands", dir + "/elsewhere/hands");
  fs::rename(dir + "/scenes", dir + "/elsewhere/scenes");
  EXPECT_EQ(load_scene(dir + "/elsewhere/scenes/scene.yaml").hands.size(), 1u);
}

TEST(GripFitScene, ALeftHandLogGetsALeftHand) {
  const fit::GripHand hand = fit::grip_hand_at(test::grip_fit_hand(), test::fist_sample());
  GripSceneSpec spec = bar_spec(hand);
  spec.left_hand = true;
  const std::string path = test::make_temp_dir("grip_fit_scene") + "/left.yaml";
  write_grip_scene(spec, path);
  const physics::Scene scene = load_scene(path);
  ASSERT_EQ(scene.hands.size(), 1u);
  EXPECT_TRUE(scene.hands[0].left);
}

TEST(GripFitScene, ABadCockpitFileIsNamedAndNothingIsWritten) {
  const fit::GripHand hand = fit::grip_hand_at(test::grip_fit_hand(), test::fist_sample());
  const std::string dir = test::make_temp_dir("grip_fit_scene");
  const std::string path = dir + "/scene.yaml";
  {
    // a grasp section the loader rejects: the written text would not load
    const std::string cockpit = dir + "/cockpit.yaml";
    std::ofstream(cockpit) << "gravity: [0, 0, -9.81]\nstep_s: 0.001\nobjects:\n"
                              "  - {name: cup, kind: static, shape: {sphere: 0.1}, "
                              "pose: {position: [0, 0, 1]}, material: {mu_s: 0.5, mu_d: 0.4}}\n"
                              "grasp: {xi_N: -3}\n";
    GripSceneSpec spec = bar_spec(hand);
    spec.cockpit_path = cockpit;
    try {
      write_grip_scene(spec, path);
      ADD_FAILURE() << "no error";
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find("cockpit.yaml:5:"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("xi_N"), std::string::npos) << e.what();
    }
    EXPECT_FALSE(fs::exists(path));
    EXPECT_FALSE(fs::exists(path + ".partial"));
  }
  {
    // no object to take the material of: named with the cockpit file's line
    GripSceneSpec spec = bar_spec(hand);
    spec.material_of = "teapot";
    try {
      write_grip_scene(spec, path);
      ADD_FAILURE() << "no error";
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find("cockpit.yaml:"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("teapot"), std::string::npos) << e.what();
    }
    EXPECT_FALSE(fs::exists(path));
  }
}

TEST(GripFitScene, RpyDegreesGiveTheRotationBack) {
  for (const Eigen::Vector3d& rpy :
       {Eigen::Vector3d(10, 20, 30), Eigen::Vector3d(-170, 45, 100), Eigen::Vector3d(0, 90, 105),
        Eigen::Vector3d(30, -90, -20), Eigen::Vector3d(179, -5, -179)}) {
    const Eigen::Matrix3d R =
        pose_from_position_rpy_deg({0, 0, 0}, {rpy.x(), rpy.y(), rpy.z()}).linear();
    const Eigen::Vector3d back = rpy_deg_from_rotation(R);
    const Eigen::Matrix3d R_back =
        pose_from_position_rpy_deg({0, 0, 0}, {back.x(), back.y(), back.z()}).linear();
    EXPECT_LT((R - R_back).norm(), 1e-12) << rpy.transpose();
  }
  // a lying bar is written as (0, 90, yaw), a sphere as 0
  const Eigen::Matrix3d lying =
      (Eigen::AngleAxisd(deg_to_rad(105.0), Eigen::Vector3d::UnitZ()) *
       Eigen::AngleAxisd(0.5 * M_PI, Eigen::Vector3d::UnitY()) *
       Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()))  // about its axis
          .toRotationMatrix();
  EXPECT_LT(
      (object_rpy_deg(Shape::cylinder(0.01, 0.1), lying) - Eigen::Vector3d(0, 90, 105)).norm(),
      1e-9);
  EXPECT_EQ(object_rpy_deg(Shape::sphere(0.01), lying), Eigen::Vector3d::Zero());
}

}  // namespace
}  // namespace vcockpit
