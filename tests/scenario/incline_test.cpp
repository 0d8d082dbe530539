// A box on a plane tilted below atan(mu_s) stays put (under 1 mm in 2 s); tilted above it, it
// slides with acceleration g (sin theta - mu_d cos theta) within 5 %.

#include <gtest/gtest.h>

#include <cmath>

#include "physics_node/physics/world.hpp"
#include "tests/support/scene_builder.hpp"

namespace vcockpit::test {
namespace {

constexpr double kMuS = 0.6, kMuD = 0.4, kG = 9.81;

// A 4 m plane tilted by theta about y (its surface through the origin), and a box resting on it.
physics::World incline_world(double theta_deg) {
  physics::Scene scene;
  const auto m = material(1e5, kMuS, kMuD);
  const double theta = deg_to_rad(theta_deg);
  // the plane's top surface passes through the origin; "downhill" is +x along the plane
  const Eigen::Isometry3d X_GP = at(0, 0, 0, 0, theta_deg, 0);
  scene.objects.push_back(static_box("plane", {4.0, 1.0, 0.2}, X_GP * at(0, 0, -0.1), m));
  const double half_m = 0.05, mass_kg = 1.0;
  const double depth_m = mass_kg * kG * std::cos(theta) / 5e4;  // settle near the rest depth
  scene.objects.push_back(dynamic_object("box", physics::Shape::box({0.1, 0.1, 0.1}), mass_kg,
                                         X_GP * at(-1.0, 0, half_m - depth_m), m));
  return physics::World(scene);
}

// Position along the plane's downhill direction.
double along_plane_m(const physics::World& world, double theta_deg) {
  const Eigen::Matrix3d R = rotation_from_rpy(0, deg_to_rad(theta_deg), 0);
  return (R.transpose() * world.bodies()[1].X_GO.translation()).x();
}

TEST(Incline, BelowTheFrictionAngleTheBoxStaysPut) {
  const double theta_deg = rad_to_deg(std::atan(kMuS)) - 5.0;  // 26 deg
  physics::World world = incline_world(theta_deg);
  for (int i = 0; i < 100; ++i) world.step();  // let the contact settle
  const Eigen::Vector3d p0 = world.bodies()[1].X_GO.translation();
  for (int i = 0; i < 2000; ++i) world.step();
  const double moved_m = (world.bodies()[1].X_GO.translation() - p0).norm();
  EXPECT_LT(moved_m, 1e-3) << "moved " << moved_m * 1e3 << " mm in 2 s at " << theta_deg << " deg";
}

TEST(Incline, AboveTheFrictionAngleTheBoxSlidesAtTheCoulombAcceleration) {
  const double theta_deg = rad_to_deg(std::atan(kMuS)) + 5.0;  // 36 deg
  const double theta = deg_to_rad(theta_deg);
  const double expected_mps2 = kG * (std::sin(theta) - kMuD * std::cos(theta));
  physics::World world = incline_world(theta_deg);
  for (int i = 0; i < 200; ++i) world.step();  // past the stick-slip transition
  const double s1 = along_plane_m(world, theta_deg);
  for (int i = 0; i < 300; ++i) world.step();
  const double s2 = along_plane_m(world, theta_deg);
  for (int i = 0; i < 300; ++i) world.step();
  const double s3 = along_plane_m(world, theta_deg);
  // equal intervals T: s3 - 2 s2 + s1 = a T^2
  const double T = 0.3;
  const double a = (s3 - 2 * s2 + s1) / (T * T);
  EXPECT_NEAR(a, expected_mps2, 0.05 * expected_mps2)
      << "a = " << a << " m/s^2, expected " << expected_mps2 << " at " << theta_deg << " deg";
  EXPECT_GT(s3 - s1, 0.1);  // it really slid downhill
}

}  // namespace
}  // namespace vcockpit::test
