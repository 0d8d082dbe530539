// Rolling resistance against its closed form: a solid sphere rolling without slip on a level
// plane feels the couple mu_roll m g about its contact, so (I + m r^2) dw/dt = -mu_roll m g:
//   a = mu_roll g / (r (1 + 2/5)),   stopping distance v0^2 / (2 a)
// and it stops there: it neither rolls back nor rocks about where it stopped.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "physics_node/physics/world.hpp"
#include "tests/support/scene_builder.hpp"

namespace vcockpit::test {
namespace {

constexpr double kRadius_m = 0.03;
constexpr double kMass_kg = 0.06;
constexpr double kG_mps2 = 9.81;

struct Rolled {
  double distance_m = 0.0;  // from the start to where it ended
  double stop_s = -1.0;     // when it first stood still
  double least_vx_mps = 0.0;
  double moved_after_stop_m = 0.0;  // how far it went from where it first stood still
  Eigen::Vector3d v_end_G = Eigen::Vector3d::Zero();
  Eigen::Vector3d w_end_G = Eigen::Vector3d::Zero();
};

// The ball rolls along +x at v0 without slipping (w = v0 / r about +y) on a floor; both materials
// have the rolling resistance mu_roll_m (the pair's is then the same).
Rolled roll(double v0_mps, double mu_roll_m, double duration_s) {
  physics::Material m = material(1e5, 0.9, 0.8);
  m.mu_roll_m = mu_roll_m;
  physics::Scene scene;
  scene.step_s = 0.001;
  scene.objects.push_back(floor_box(m));
  // resting at its contact depth m g / k_pair (k_pair = 5e4 N/m): no drop, no bounce
  const double depth_m = kMass_kg * kG_mps2 / 5e4;
  physics::ObjectSpec ball = dynamic_object("ball", physics::Shape::sphere(kRadius_m), kMass_kg,
                                            at(0, 0, kRadius_m - depth_m), m);
  ball.v_G = Eigen::Vector3d(v0_mps, 0, 0);
  ball.w_G = Eigen::Vector3d(0, v0_mps / kRadius_m, 0);
  scene.objects.push_back(ball);
  physics::World world(scene);
  Rolled out;
  Eigen::Vector3d stopped_at = Eigen::Vector3d::Zero();
  const int steps = static_cast<int>(std::lround(duration_s / scene.step_s));
  for (int k = 1; k <= steps; ++k) {
    world.step();
    const physics::BodyState& b = world.bodies()[1];
    out.least_vx_mps = std::min(out.least_vx_mps, b.v_G.x());
    if (out.stop_s < 0 && b.v_G.norm() < 1e-4) {
      out.stop_s = k * scene.step_s;
      stopped_at = b.X_GO.translation();
    }
    if (out.stop_s >= 0)
      out.moved_after_stop_m =
          std::max(out.moved_after_stop_m, (b.X_GO.translation() - stopped_at).norm());
  }
  EXPECT_TRUE(world.body_faults().empty());
  const physics::BodyState& b = world.bodies()[1];
  out.distance_m = b.X_GO.translation().x();
  out.v_end_G = b.v_G;
  out.w_end_G = b.w_G;
  return out;
}

TEST(RollingResistance, SphereStopsAtTheClosedFormDistance) {
  const double v0_mps = 0.5, mu_roll_m = 1e-3;
  const double a_mps2 = mu_roll_m * kG_mps2 / (kRadius_m * (1.0 + 2.0 / 5.0));  // 0.234 m/s^2
  const double expected_m = v0_mps * v0_mps / (2.0 * a_mps2);                    // 0.535 m
  const Rolled r = roll(v0_mps, mu_roll_m, 4.0);
  std::printf("stopped at %.5f m after %.3f s (closed form %.5f m, %.3f s); least v_x %.2e m/s\n",
              r.distance_m, r.stop_s, expected_m, v0_mps / a_mps2, r.least_vx_mps);
  // 1 %: the soft constraints stop it 0.07 % short (0.5348 m); the explicit penalty springs
  // once did 0.26 % short at 1 ms, 0.5 ms and 0.25 ms substeps alike (the friction that keeps it
  // rolling acts through stick springs at a slightly penetrating contact). A couple off by a factor (the 1 + 2/5, or mu_roll N at each point
  // of a manifold) would miss by tens of percent, and stick springs anchored on the ball's
  // material points (dragged round as it rolls) by 1.2 %.
  EXPECT_NEAR(r.distance_m, expected_m, 0.01 * expected_m);
  EXPECT_NEAR(r.stop_s, v0_mps / a_mps2, 0.02 * v0_mps / a_mps2);
  EXPECT_GT(r.least_vx_mps, -1e-4) << "it never rolls back";
  EXPECT_LT(r.moved_after_stop_m, 1e-5) << "it stays where it stopped";
  EXPECT_LT(r.v_end_G.norm(), 1e-5);
  EXPECT_LT(r.w_end_G.norm(), 1e-3);
}

TEST(RollingResistance, WithoutItTheSphereRollsOn) {
  const Rolled r = roll(0.5, 0.0, 1.0);
  EXPECT_NEAR(r.distance_m, 0.5, 0.005) << "rolling without slip loses nothing";
  EXPECT_LT(r.stop_s, 0.0);
}

}  // namespace
}  // namespace vcockpit::test
