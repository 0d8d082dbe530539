// Round shapes at rest on a flat face stay put. FCL 0.7 reports one contact point for a cylinder
// standing on a box, a cylinder lying on one and a capsule lying on one; with one point nothing
// resists rocking or twisting, and an upright cup spun at about 1.2 deg/s with no input.
// collision.cpp builds a manifold for these (rim points, the ends of the contact line), so:
//   - an upright cylinder (a cup on the console) keeps still: angular speed < 1e-4 rad/s after
//     5 s, displacement < 0.05 mm;
//   - a cylinder or capsule lying on its side does not yaw (< 0.01 deg over 5 s).
// Every body starts level at its resting depth m g / k_eff (k_eff = k1 k2 / (k1 + k2)); the
// "knocked" variants start with a small spin and tumble and must settle within 1 s and then stay.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "physics_node/physics/world.hpp"
#include "tests/support/scene_builder.hpp"

namespace vcockpit::test {
namespace {

constexpr double kConsoleK_Npm = 5e4;
constexpr double kObjectK_Npm = 3e4;
constexpr double kMass_kg = 0.2;
constexpr double kRadius_m = 0.035;
constexpr double kLength_m = 0.1;
constexpr int kSteps = 5000;  // 5 s at the default 1 ms

double resting_depth_m() {
  const double k_eff = kConsoleK_Npm * kObjectK_Npm / (kConsoleK_Npm + kObjectK_Npm);
  return kMass_kg * 9.81 / k_eff;
}

// A static console slab, its top face at z = 0, and one dynamic body.
physics::Scene console_with(const physics::Shape& shape, const Eigen::Isometry3d& X_GO,
                            const Eigen::Vector3d& w_G = Eigen::Vector3d::Zero()) {
  physics::Scene scene;
  scene.objects.push_back(
      static_box("console", {0.6, 0.4, 0.05}, at(0, 0, -0.025), material(kConsoleK_Npm)));
  scene.objects.push_back(dynamic_object("object", shape, kMass_kg, X_GO, material(kObjectK_Npm)));
  scene.objects.back().w_G = w_G;
  scene.sleep.enabled = false;  // what the contacts do at rest, which sleeping would end
  return scene;
}

// Heading of the body's z axis in the horizontal plane (rad).
double axis_yaw_rad(const Eigen::Isometry3d& X) {
  const Eigen::Vector3d a = X.linear().col(2);
  return std::atan2(a.y(), a.x());
}

double rad_to_deg(double rad) {
  return rad * 180.0 / M_PI;
}

std::string sci(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3e", x);
  return text;
}

TEST(RestingShapes, UprightCylinderOnConsoleNeitherSpinsNorDrifts) {
  const Eigen::Isometry3d X0 = at(0.05, -0.03, 0.5 * kLength_m - resting_depth_m());
  physics::World world(console_with(physics::Shape::cylinder(kRadius_m, kLength_m), X0));
  double max_w = 0.0;
  for (int i = 0; i < kSteps; ++i) {
    world.step();
    max_w = std::max(max_w, world.bodies()[1].w_G.norm());
  }
  const auto& body = world.bodies()[1];
  const double moved_m = (body.X_GO.translation() - X0.translation()).norm();
  // rotation about the vertical since the start, from the body's x axis
  const Eigen::Vector3d x_axis = body.X_GO.linear().col(0);
  const double twist_deg = rad_to_deg(std::atan2(x_axis.y(), x_axis.x()));
  EXPECT_LT(body.w_G.norm(), 1e-4) << "angular speed " << body.w_G.transpose() << " rad/s";
  EXPECT_LT(moved_m, 5e-5) << "moved " << moved_m * 1e3 << " mm";
  EXPECT_LT(std::abs(twist_deg), 0.01) << "turned " << twist_deg << " deg about the vertical";
  EXPECT_GT(body.X_GO.linear()(2, 2), 1.0 - 1e-8) << "tipped";
  // four rim points carry it (collision.cpp's manifold), not FCL's single point
  EXPECT_EQ(world.contacts().size(), 4u);
  RecordProperty("max_angular_speed_radps", sci(max_w));
  RecordProperty("final_angular_speed_radps", sci(body.w_G.norm()));
  RecordProperty("moved_m", sci(moved_m));
}

void expect_lying_shape_keeps_its_heading(const physics::Shape& shape, double centre_height_m) {
  // lying along y (roll 90 deg), then turned 30 deg about the vertical
  const Eigen::Isometry3d X0 = at(-0.05, 0.02, centre_height_m - resting_depth_m(), 90, 0, 30);
  physics::World world(console_with(shape, X0));
  for (int i = 0; i < kSteps; ++i)
    world.step();
  const auto& body = world.bodies()[1];
  const double yaw_deg = rad_to_deg(axis_yaw_rad(body.X_GO) - axis_yaw_rad(X0));
  const double moved_m = (body.X_GO.translation() - X0.translation()).norm();
  EXPECT_LT(std::abs(yaw_deg), 0.01) << "yawed " << yaw_deg << " deg";
  EXPECT_LT(moved_m, 5e-5) << "moved " << moved_m * 1e3 << " mm";
  EXPECT_LT(body.w_G.norm(), 1e-4) << "angular speed " << body.w_G.transpose() << " rad/s";
  EXPECT_EQ(world.contacts().size(), 2u);  // the two ends of the contact line
  ::testing::Test::RecordProperty("yaw_deg", sci(yaw_deg));
  ::testing::Test::RecordProperty("moved_m", sci(moved_m));
}

// Knocked: spinning at 3 deg/s about the vertical and rocking; after 1 s it must have stopped,
// and over the next 4 s it must not turn or creep.
TEST(RestingShapes, KnockedUprightCylinderSettlesAndStaysPut) {
  const Eigen::Isometry3d X0 = at(0.05, -0.03, 0.5 * kLength_m - resting_depth_m());
  physics::World world(console_with(physics::Shape::cylinder(kRadius_m, kLength_m), X0,
                                    Eigen::Vector3d(0.02, -0.01, 0.05)));
  for (int i = 0; i < 1000; ++i)
    world.step();
  const Eigen::Isometry3d X1 = world.bodies()[1].X_GO;
  for (int i = 1000; i < kSteps; ++i)
    world.step();
  const auto& body = world.bodies()[1];
  const double moved_m = (body.X_GO.translation() - X1.translation()).norm();
  const Eigen::Vector3d x0 = X1.linear().col(0), x1 = body.X_GO.linear().col(0);
  const double twist_deg = rad_to_deg(std::atan2(x1.y(), x1.x()) - std::atan2(x0.y(), x0.x()));
  EXPECT_LT(body.w_G.norm(), 1e-4) << "angular speed " << body.w_G.transpose() << " rad/s";
  EXPECT_LT(moved_m, 5e-5) << "moved " << moved_m * 1e3 << " mm";
  EXPECT_LT(std::abs(twist_deg), 0.01) << "turned " << twist_deg << " deg about the vertical";
  EXPECT_GT(body.X_GO.linear()(2, 2), 1.0 - 1e-6) << "left tilted";
  RecordProperty("final_angular_speed_radps", sci(body.w_G.norm()));
  RecordProperty("twist_deg_last_4s", sci(twist_deg));
  RecordProperty("moved_m_last_4s", sci(moved_m));
}

TEST(RestingShapes, KnockedLyingCylinderSettlesAndKeepsItsHeading) {
  const Eigen::Isometry3d X0 = at(-0.05, 0.02, kRadius_m - resting_depth_m(), 90, 0, 30);
  physics::World world(console_with(physics::Shape::cylinder(kRadius_m, kLength_m), X0,
                                    Eigen::Vector3d(0.0, 0.0, 0.05)));
  for (int i = 0; i < 1000; ++i)
    world.step();
  const Eigen::Isometry3d X1 = world.bodies()[1].X_GO;
  for (int i = 1000; i < kSteps; ++i)
    world.step();
  const auto& body = world.bodies()[1];
  const double yaw_deg = rad_to_deg(axis_yaw_rad(body.X_GO) - axis_yaw_rad(X1));
  const double moved_m = (body.X_GO.translation() - X1.translation()).norm();
  EXPECT_LT(std::abs(yaw_deg), 0.01) << "yawed " << yaw_deg << " deg";
  EXPECT_LT(moved_m, 5e-5) << "moved " << moved_m * 1e3 << " mm";
  EXPECT_LT(body.w_G.norm(), 1e-4) << "angular speed " << body.w_G.transpose() << " rad/s";
  RecordProperty("yaw_deg_last_4s", sci(yaw_deg));
  RecordProperty("moved_m_last_4s", sci(moved_m));
}

TEST(RestingShapes, CylinderLyingOnItsSideDoesNotYaw) {
  expect_lying_shape_keeps_its_heading(physics::Shape::cylinder(kRadius_m, kLength_m), kRadius_m);
}

TEST(RestingShapes, CapsuleLyingOnTheConsoleDoesNotYaw) {
  expect_lying_shape_keeps_its_heading(physics::Shape::capsule(0.015, kLength_m), 0.015);
}

}  // namespace
}  // namespace vcockpit::test
