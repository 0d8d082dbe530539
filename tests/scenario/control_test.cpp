// Cockpit controls in the world (control.hpp), against closed forms:
//   - a released momentary button returns as its mass-spring-damper does (to 2 % of its travel)
//     and reports out, caused by its mechanism;
//   - a detent holds a lever against gravity while its strength exceeds the gravity torque, and
//     not beyond;
//   - a command moves a control to the position asked for, reported as commanded; a command for
//     an unknown position is refused;
//   - a weight set on a spring button overshoots and settles as one mass on the button's spring
//     (the contact solver takes the cap as a body on its joint);
//   - the default cockpit's master caution button pressed by the proxy hand's fingertip, with its
//     own box cap and with a cap from a model file (glTF, OBJ, AC3D).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "hand/hand_model.hpp"
#include "physics_node/config/scene_config.hpp"
#include "physics_node/physics/world.hpp"
#include "tests/support/scene_builder.hpp"
#include "tests/support/test_files.hpp"

namespace vcockpit::test {
namespace {

constexpr double kPi = 3.14159265358979323846;

physics::ControlPosition position(const char* name, double q, double lo, double hi) {
  return {name, q, lo, hi};
}

// A 5 g push button on a panel, pressed along +x (the joint's z), 4 mm of travel, its spring
// preloaded against the out stop (rest 2 mm beyond it), damping ratio 0.5.
struct ButtonScene {
  static constexpr double kMass_kg = 0.005;
  static constexpr double kStiffness_Npm = 1500.0;
  static constexpr double kZeta = 0.5;
  static constexpr double kRest_m = -0.002;
  static constexpr double kTravel_m = 0.004;

  static physics::Scene make(double q_initial) {
    physics::Scene scene;
    scene.objects.push_back(static_box("panel", {0.02, 0.3, 0.3}, at(0.52, 0, 1.0), material(5e4)));
    physics::ObjectSpec cap = dynamic_object("button_cap", physics::Shape::box({0.008, 0.012, 0.012}),
                                             kMass_kg, at(0.5, 0, 1.0), material(5e4));
    cap.control = 0;
    scene.objects.push_back(cap);
    physics::ControlSpec c;
    c.name = "button";
    c.kind = physics::ControlKind::kPushButton;
    c.joint = physics::JointKind::kPrismatic;
    c.body = 1;
    c.X_GJ = at(0.5, 0, 1.0, 0, 90, 0);  // z along +x: into the panel
    c.q_min = 0.0;
    c.q_max = kTravel_m;
    c.q_initial = q_initial;
    c.q_rest = kRest_m;
    c.stiffness = kStiffness_Npm;
    c.damping = 2.0 * kZeta * std::sqrt(kStiffness_Npm * kMass_kg);
    c.positions = {position("out", 0.0, -1.0, 0.0015), position("pressed", kTravel_m, 0.003, 1.0)};
    scene.controls.push_back(c);
    return scene;
  }
};

TEST(Controls, AReleasedMomentaryButtonReturnsAsItsMassSpringDamper) {
  physics::World world(ButtonScene::make(ButtonScene::kTravel_m));
  ASSERT_EQ(world.state().controls[0].position, 1) << "starts pressed";
  const double w0 = std::sqrt(ButtonScene::kStiffness_Npm / ButtonScene::kMass_kg);
  const double zeta = ButtonScene::kZeta;
  const double wd = w0 * std::sqrt(1.0 - zeta * zeta);
  const double y0 = ButtonScene::kTravel_m - ButtonScene::kRest_m;
  // the free response from rest at y0 above the spring's rest, until the out stop holds it
  auto closed_form_q = [&](double t) {
    const double y = y0 * std::exp(-zeta * w0 * t) *
                     (std::cos(wd * t) + zeta / std::sqrt(1.0 - zeta * zeta) * std::sin(wd * t));
    return std::max(0.0, ButtonScene::kRest_m + y);
  };
  double worst_m = 0.0;
  int out_events = 0;
  for (int i = 1; i <= 50; ++i) {
    world.step();
    const double t = i * 1e-3;
    worst_m = std::max(worst_m, std::abs(world.state().controls[0].q - closed_form_q(t)));
    for (const physics::ControlEvent& e : world.control_events()) {
      EXPECT_EQ(e.from, 1);
      EXPECT_EQ(e.to, 0);
      EXPECT_EQ(e.cause, physics::ControlCause::kMechanism);
      ++out_events;
    }
  }
  EXPECT_LE(worst_m, 0.02 * ButtonScene::kTravel_m) << "worst " << worst_m * 1e3 << " mm";
  EXPECT_EQ(out_events, 1) << "one event, no chatter";
  EXPECT_EQ(world.state().controls[0].q, 0.0) << "on its out stop";
  // the cap's body follows its coordinate: at the out stop, where the joint frame is
  EXPECT_LT((world.bodies()[1].X_GO.translation() - Eigen::Vector3d(0.5, 0, 1.0)).norm(), 1e-12);
}

// A 100 g lever on a horizontal pivot (y), its centroid 5 cm out along x: gravity's torque about
// the pivot at q = 0 is m g r = 0.049 N m, turning it down (+q). A detent at 0 of 10 deg half
// width holds it while the detent's strength exceeds that torque (statically: the lever is
// damped enough to creep into its equilibrium rather than swing past it).
physics::Scene lever_scene(double detent_strength_Nm) {
  physics::Scene scene;
  physics::ObjectSpec arm = dynamic_object("lever_arm", physics::Shape::box({0.1, 0.01, 0.01}), 0.1,
                                           at(0.05, 0, 1.0), material(5e4));
  arm.control = 0;
  scene.objects.push_back(arm);
  physics::ControlSpec c;
  c.name = "lever";
  c.kind = physics::ControlKind::kLever;
  c.joint = physics::JointKind::kRevolute;
  c.body = 0;
  c.X_GJ = at(0, 0, 1.0, -90, 0, 0);  // z along +y
  c.X_JO = at(0.05, 0, 0);
  c.q_min = -kPi / 3;
  c.q_max = kPi / 3;
  c.damping = 0.05;  // overdamped in the detent (critical ~0.038 N m s): it creeps, no overshoot
  c.detents = {{0.0, detent_strength_Nm, 10.0 * kPi / 180.0}};
  c.positions = {position("up", 0.0, -0.1, 0.1), position("down", kPi / 3, 0.9, 1.1)};
  scene.controls.push_back(c);
  return scene;
}

TEST(Controls, ADetentHoldsALeverAgainstGravityUpToItsStrength) {
  const double gravity_Nm = 0.1 * 9.81 * 0.05;
  physics::World held(lever_scene(1.2 * gravity_Nm));
  physics::World falls(lever_scene(0.8 * gravity_Nm));
  // (3 s: the damper that lets the held lever creep makes the falling one slow)
  for (int i = 0; i < 3000; ++i) {
    held.step();
    falls.step();
  }
  // held: where the detent's restoring torque meets gravity's, A sin(pi q / w) = m g r cos q
  const double w = 10.0 * kPi / 180.0;
  const double q_eq = w / kPi * std::asin(1.0 / 1.2);  // (cos q ~ 1 this close to 0)
  EXPECT_NEAR(held.state().controls[0].q, q_eq, 0.02 * q_eq);
  EXPECT_EQ(held.state().controls[0].position, 0);
  EXPECT_EQ(falls.state().controls[0].q, kPi / 3) << "on its stop";
  EXPECT_EQ(falls.state().controls[0].position, 1);
}

TEST(Controls, ACommandSetsThePositionAndIsReportedAsCommanded) {
  physics::World world(lever_scene(1.0));
  world.step();
  EXPECT_FALSE(world.command_control(0, 2)) << "no such position";
  EXPECT_FALSE(world.command_control(1, 0)) << "no such control";
  ASSERT_TRUE(world.command_control(0, 1));
  world.step();
  ASSERT_EQ(world.control_events().size(), 1u);
  const physics::ControlEvent& e = world.control_events()[0];
  EXPECT_EQ(e.from, 0);
  EXPECT_EQ(e.to, 1);
  EXPECT_EQ(e.cause, physics::ControlCause::kCommanded);
  EXPECT_EQ(world.state().controls[0].q, kPi / 3);
}


// A 50 g box set on the cap of a vertical spring button (5 g, 50 N/m, rest at its top stop) and
// let go: box and cap go down together as one mass on the button's spring, so the button
// overshoots to q_eq (1 + exp(-zeta pi / sqrt(1 - zeta^2))) and settles at q_eq = (m_box +
// m_cap) g / k, zeta = c / (2 sqrt(k (m_box + m_cap))). The cap is a body on its joint in the
// contact solve (its rate's answer to the box's impulse).
struct WeightOnButton {
  static constexpr double kBox_kg = 0.05;
  static constexpr double kCap_kg = 0.005;
  static constexpr double kStiffness_Npm = 50.0;
  static constexpr double kZeta = 0.2;
  static double damping() { return 2.0 * kZeta * std::sqrt(kStiffness_Npm * (kBox_kg + kCap_kg)); }
  static double q_eq() { return (kBox_kg + kCap_kg) * 9.81 / kStiffness_Npm; }

  static physics::Scene make() {
    physics::Scene scene;
    scene.sleep.enabled = false;
    physics::ObjectSpec cap = dynamic_object("cap", physics::Shape::box({0.03, 0.03, 0.006}), kCap_kg,
                                             at(0, 0, 0.1), material(5e4));
    cap.control = 0;
    scene.objects.push_back(cap);
    scene.objects.push_back(dynamic_object("weight", physics::Shape::box({0.02, 0.02, 0.02}), kBox_kg,
                                           at(0, 0, 0.1 + 0.003 + 0.01), material(5e4)));
    physics::ControlSpec c;
    c.name = "button";
    c.kind = physics::ControlKind::kPushButton;
    c.joint = physics::JointKind::kPrismatic;
    c.body = 0;
    c.X_GJ = at(0, 0, 0.1, 180, 0, 0);  // z down: q is how far it is pressed
    c.q_min = 0.0;
    c.q_max = 0.03;
    c.q_rest = 0.0;
    c.stiffness = kStiffness_Npm;
    c.damping = damping();
    c.positions = {position("out", 0.0, -1.0, 0.005), position("pressed", 0.02, 0.015, 1.0)};
    scene.controls.push_back(c);
    return scene;
  }
};

TEST(WeightOnButtonTest, OvershootsAndSettlesAsTheWeightOnTheSpring) {
  physics::World world(WeightOnButton::make());
  const double q_eq = WeightOnButton::q_eq();
  const double zeta = WeightOnButton::kZeta;
  const double q_peak_closed = q_eq * (1.0 + std::exp(-zeta * kPi / std::sqrt(1.0 - zeta * zeta)));
  double q_peak = 0.0;
  for (int i = 0; i < 3000; ++i) {
    world.step();
    q_peak = std::max(q_peak, world.state().controls[0].q);
  }
  const double q_end = world.state().controls[0].q;
  std::printf("peak %.3f mm (closed form %.3f), rest %.3f mm (closed form %.3f)\n", q_peak * 1e3,
              q_peak_closed * 1e3, q_end * 1e3, q_eq * 1e3);
  EXPECT_NEAR(q_peak, q_peak_closed, 0.03 * q_peak_closed);
  EXPECT_NEAR(q_end, q_eq, 0.01 * q_eq);
  EXPECT_LT(std::abs(world.state().controls[0].qd), 1e-4);
  // the box rides on the cap: its centre 13 mm above the cap's, less the contact's give
  const double gap_m = world.bodies()[1].X_GO.translation().z() - world.bodies()[0].X_GO.translation().z();
  EXPECT_NEAR(gap_m, 0.013, 1e-4);
  EXPECT_LT(std::abs(world.bodies()[1].X_GO.translation().x()), 1e-4) << "slid off sideways";
}


// The default cockpit's master caution button, pressed by the proxy hand's index fingertip: the
// fingertip's contact force, projected onto the button's axis, pushes it past its actuation
// point ("pressed", caused by the index's distal link); withdrawn, the spring returns it ("out",
// by its mechanism). One event each, no chatter.
// The default cockpit's master caution pressed in to its detent by the index fingertip of a
// pointing hand and let go: one press, reported as pushed by that link, and one return by its
// spring. `cap_half_m`: how far the cap's front face stands out from the joint's origin.
void press_master_caution(const physics::Scene& loaded, double cap_half_m) {
  physics::World world(loaded);
  const physics::Scene& scene = world.scene();
  const int button = scene.find_control("master_caution");
  ASSERT_GE(button, 0);
  const physics::ControlSpec& c = scene.controls[static_cast<std::size_t>(button)];
  const hand::HandModel& model = scene.hands[0];
  // a pointing hand: index straight, the other fingers and the thumb curled in
  physics::HandInput input;
  input.q_rad = model.rest_pose();
  for (hand::Joint j : {hand::Joint::kMiddleMcp, hand::Joint::kMiddlePip, hand::Joint::kRingMcp,
                        hand::Joint::kRingPip, hand::Joint::kLittleMcp, hand::Joint::kLittlePip})
    input.q_rad[static_cast<std::size_t>(j)] = 80.0 * kPi / 180.0;
  input.q_rad[static_cast<std::size_t>(hand::Joint::kIndexMcp)] = 0.0;
  input.q_rad[static_cast<std::size_t>(hand::Joint::kIndexPip)] = 0.0;
  input.q_rad[static_cast<std::size_t>(hand::Joint::kIndexDip)] = 0.0;
  input.q_rad[static_cast<std::size_t>(hand::Joint::kThumbIp)] = 60.0 * kPi / 180.0;
  hand::HandLinkPoses links;
  hand::forward_kinematics(model, input.q_rad, links);
  const Eigen::Vector3d tip_H = links.p_H_tip[static_cast<std::size_t>(hand::Finger::kIndex)];
  // the index's tip along the button's axis, the back of the hand up
  const Eigen::Vector3d axis = physics::joint_axis_G(c);
  const Eigen::Vector3d x = axis;
  const Eigen::Vector3d z = (Eigen::Vector3d::UnitZ() - x.dot(Eigen::Vector3d::UnitZ()) * x).normalized();
  Eigen::Matrix3d R_GH;
  R_GH.col(0) = x;
  R_GH.col(1) = z.cross(x);
  R_GH.col(2) = z;
  const Eigen::Vector3d cap_face = c.X_GJ.translation() - cap_half_m * axis;  // its front face
  const double tip_radius =
      model.capsules[static_cast<std::size_t>(hand::Link::kIndexDistal)].radius_m;
  auto hand_at = [&](double depth_m) {  // the fingertip's surface depth_m past the cap's face
    input.X_GH.linear() = R_GH;
    input.X_GH.translation() = cap_face + (depth_m - tip_radius) * axis - R_GH * tip_H;
    return input;
  };
  std::vector<physics::ControlEvent> events;
  auto run = [&](double from_m, double to_m, double seconds) {
    const int steps = static_cast<int>(seconds * 1000);
    for (int i = 1; i <= steps; ++i) {
      world.set_hand_input(hand_at(from_m + (to_m - from_m) * i / steps));
      world.step();
      events.insert(events.end(), world.control_events().begin(), world.control_events().end());
    }
  };
  run(-0.03, -0.03, 0.05);
  run(-0.03, 0.006, 0.3);  // in, 2 mm past the bottom of its travel
  run(0.006, 0.006, 0.2);
  EXPECT_GE(world.state().controls[static_cast<std::size_t>(button)].q, 0.003) << "held down";
  run(0.006, -0.03, 0.3);
  run(-0.03, -0.03, 0.2);
  std::vector<physics::ControlEvent> mine;
  for (const auto& e : events)
    if (e.control == button) mine.push_back(e);
    else ADD_FAILURE() << scene.controls[static_cast<std::size_t>(e.control)].name << " moved";
  ASSERT_EQ(mine.size(), 2u);
  EXPECT_EQ(mine[0].to, 1);
  EXPECT_EQ(mine[0].cause, physics::ControlCause::kPushed);
  EXPECT_EQ(mine[0].link, static_cast<int>(hand::Link::kIndexDistal));
  EXPECT_EQ(mine[1].to, 0);
  EXPECT_EQ(mine[1].cause, physics::ControlCause::kMechanism);
  EXPECT_EQ(world.state().controls[static_cast<std::size_t>(button)].q, 0.0);
}

TEST(Controls, AFingertipPressesTheMasterCautionButtonAndItsSpringReturnsIt) {
  press_master_caution(load_scene(source_dir() + "/config/cockpit.yaml"), 0.004);
}

// The same button with a cap from a model file (the 24 x 24 x 12 mm chamfered cap of
// scripts/make_test_models.py, colliding as its convex hull), in each format.
class MeshCap : public ::testing::TestWithParam<const char*> {};

TEST_P(MeshCap, AFingertipPressesAMeshButtonToItsDetent) {
  std::string yaml = read_text(source_dir() + "/config/cockpit.yaml");
  const std::string box_cap = "body: {shape: {box: [0.022, 0.022, 0.008]}, mass: 0.005, color: [0.85, 0.55, 0.05]}";
  const auto at = yaml.find(box_cap);  // the master caution's, the first such body
  ASSERT_NE(at, std::string::npos);
  yaml.replace(at, box_cap.size(),
               "body: {shape: {mesh: " + source_dir() + "/tests/data/models/button." + GetParam() +
                   ", node: button}, mass: 0.005}");
  const std::string hands = "hands: [hand.yaml, {file: hand.yaml, side: left}]";
  const std::string hand = source_dir() + "/config/hand.yaml";
  yaml.replace(yaml.rfind(hands), hands.size(),  // (the header comment has it too)
               "hands: [" + hand + ", {file: " + hand + ", side: left}]");
  const physics::Scene scene =
      load_scene(write_test_file("mesh_cap", "cockpit.yaml", cockpit_yaml_models_absolute(yaml)));
  const physics::ObjectSpec& cap = scene.objects[static_cast<std::size_t>(
      scene.controls[static_cast<std::size_t>(scene.find_control("master_caution"))].body)];
  ASSERT_EQ(cap.shape.kind, physics::ShapeKind::kMesh);
  press_master_caution(scene, 0.006);
}

INSTANTIATE_TEST_SUITE_P(Controls, MeshCap, ::testing::Values("gltf", "obj", "ac"));

}  // namespace
}  // namespace vcockpit::test
