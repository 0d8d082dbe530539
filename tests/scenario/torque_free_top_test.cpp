// A free cylinder spun about a tilted axis, no gravity, nothing to touch: the axisymmetric top's
// torque-free motion (Landau & Lifshitz §33). In the body frame w3 stays constant and w's part
// across the axis turns about it at Omega = (I3 - I1) / I1 * w3; |L| and the kinetic energy are
// constants of the motion. Stepped by the world at the scene's 1 ms step for 60 s.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "physics_node/physics/world.hpp"
#include "tests/support/scene_builder.hpp"

namespace vcockpit::test {
namespace {

struct Invariants {
  Eigen::Vector3d L_G;  // angular momentum about the centroid, world frame (kg m^2/s)
  double E_J;           // rotational kinetic energy
};

Invariants invariants(const physics::BodyState& b, const Eigen::Matrix3d& I_O) {
  const Eigen::Matrix3d R = b.X_GO.linear();
  const Eigen::Vector3d L_G = R * (I_O * (R.transpose() * b.w_G));
  return {L_G, 0.5 * b.w_G.dot(L_G)};
}

physics::Scene free_cylinder(double r_m, double length_m, double mass_kg,
                             const Eigen::Isometry3d& X_GO, const Eigen::Vector3d& w_O) {
  physics::Scene scene;
  scene.gravity_mps2.setZero();
  scene.step_s = 0.001;
  physics::ObjectSpec o = dynamic_object("top", physics::Shape::cylinder(r_m, length_m), mass_kg,
                                         X_GO, material(1e5));
  o.w_G = X_GO.linear() * w_O;
  scene.objects.push_back(o);
  return scene;
}

TEST(TorqueFreeTop, KeepsLAndEnergyAndPrecessesAtTheClosedFormRate) {
  // the cockpit's cup (0.2 kg, r 3.5 cm, 10 cm long), tilted in the world so that body and
  // world axes differ, spun at 31.6 rad/s about an axis 18 deg off its own
  const Eigen::Vector3d w0_O(10.0, 0.0, 30.0);
  physics::World world(free_cylinder(0.035, 0.10, 0.2, at(0, 0, 1, 20, -35, 10), w0_O));
  const Eigen::Matrix3d& I_O = world.scene().objects[0].I_O;
  const double I1 = I_O(0, 0), I3 = I_O(2, 2);
  const double Omega_radps = (I3 - I1) / I1 * w0_O.z();  // -13.9 rad/s: the cup is prolate
  const Invariants start = invariants(world.bodies()[0], I_O);

  const double h_s = world.scene().step_s;
  const int steps = 60'000;
  double phase_rad = 0.0;  // of w's part across the axis, in the body frame, unwrapped
  double last_angle_rad = std::atan2(w0_O.y(), w0_O.x());
  double worst_L = 0.0, worst_E = 0.0, worst_w3 = 0.0;
  for (int k = 0; k < steps; ++k) {
    world.step();
    const physics::BodyState& b = world.bodies()[0];
    const Invariants now = invariants(b, I_O);
    worst_L = std::max(worst_L, std::abs(now.L_G.norm() / start.L_G.norm() - 1.0));
    worst_E = std::max(worst_E, std::abs(now.E_J / start.E_J - 1.0));
    const Eigen::Vector3d w_O = b.X_GO.linear().transpose() * b.w_G;
    worst_w3 = std::max(worst_w3, std::abs(w_O.z() - w0_O.z()));
    const double angle_rad = std::atan2(w_O.y(), w_O.x());
    double turn_rad = angle_rad - last_angle_rad;  // |Omega| h = 0.014 rad a step: no ambiguity
    if (turn_rad > std::numbers::pi) turn_rad -= 2.0 * std::numbers::pi;
    if (turn_rad < -std::numbers::pi) turn_rad += 2.0 * std::numbers::pi;
    phase_rad += turn_rad;
    last_angle_rad = angle_rad;
  }
  ASSERT_TRUE(world.body_faults().empty());
  EXPECT_LT(worst_L, 1e-3) << "|L| within 0.1 % over 60 s";
  EXPECT_LT(worst_E, 1e-2) << "kinetic energy within 1 % over 60 s";
  EXPECT_LT(worst_w3, 1e-6) << "w3 is a constant of the axisymmetric top";

  // The precession: Omega T = -834 rad over 60 s. The implicit midpoint rule turns w by
  // 2 atan(Omega h / 2) a step instead of Omega h, a lag of T |Omega| (Omega h)^2 / 12 = 0.013 rad
  // in all; 0.05 rad allows nearly four times that, and still pins Omega to 6e-5 of itself.
  const double T_s = steps * h_s;
  const double expected_rad = Omega_radps * T_s;
  const double midpoint_lag_rad = T_s * std::abs(Omega_radps) * std::pow(Omega_radps * h_s, 2) / 12;
  EXPECT_LT(3.5 * midpoint_lag_rad, 0.05);
  EXPECT_NEAR(phase_rad, expected_rad, 0.05) << "Omega = " << Omega_radps << " rad/s";
  EXPECT_LT(std::abs(phase_rad), std::abs(expected_rad)) << "the midpoint rule lags, never leads";

  // L is constant in the world as well (the rotation turns by the midpoint w): only the
  // exponential map's third-order difference from the midpoint rule's Cayley turn moves it
  const Invariants end = invariants(world.bodies()[0], I_O);
  EXPECT_LT(std::acos(std::min(1.0, end.L_G.normalized().dot(start.L_G.normalized()))), 1e-3);
}

TEST(TorqueFreeTop, AFastTiltedSpinStaysBounded) {
  // 60 g, r 2 cm, 16 cm long, 70.7 rad/s about an axis 45 deg off its own. The explicit
  // gyroscopic term took it to 149 rad/s after 1 s and 24,896 rad/s after 6 s.
  const Eigen::Vector3d w0_O(50.0, 0.0, 50.0);
  physics::World world(free_cylinder(0.02, 0.16, 0.06, at(0, 0, 1), w0_O));
  const Eigen::Matrix3d& I_O = world.scene().objects[0].I_O;
  const Invariants start = invariants(world.bodies()[0], I_O);
  double fastest_radps = 0.0, most_E_J = 0.0;
  for (int k = 1; k <= 6000; ++k) {
    world.step();
    const physics::BodyState& b = world.bodies()[0];
    fastest_radps = std::max(fastest_radps, b.w_G.norm());
    most_E_J = std::max(most_E_J, invariants(b, I_O).E_J);
    if (k == 1000 || k == 6000) {
      // the axisymmetric top keeps w3 and |w across| and so |w| itself
      EXPECT_NEAR(b.w_G.norm(), w0_O.norm(), 1e-9 * w0_O.norm()) << k << " ms";
    }
  }
  EXPECT_TRUE(world.body_faults().empty()) << "the body check found it spinning too fast";
  EXPECT_LE(fastest_radps, w0_O.norm() * (1.0 + 1e-9));
  EXPECT_LE(most_E_J, start.E_J * (1.0 + 1e-9)) << "the kinetic energy never grows";
}

}  // namespace
}  // namespace vcockpit::test
