// The integrator (eqs. 20-25) against closed forms: a constant force gives v = F t / m and the
// semi-implicit Euler positions; a torque-free tumble keeps |L| and the kinetic energy (the
// implicit midpoint rule for the gyroscopic term); a torque adds M dt to the angular momentum;
// the rotation increment is the exact exponential map at any angle; finite differences of poses
// give back the velocities that made them.

#include "physics_node/physics/integrator.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace vcockpit::physics {
namespace {

constexpr double kMass_kg = 2.0;

// A 0.1 x 0.2 x 0.3 m box of kMass_kg: three different principal moments (kg m^2).
Eigen::Matrix3d box_inertia() {
  const double a = 0.1, b = 0.2, c = 0.3;
  return Eigen::Vector3d(b * b + c * c, a * a + c * c, a * a + b * b).asDiagonal() *
         (kMass_kg / 12.0);
}

TEST(Integrator, ConstantForceGivesFtOverMAndSemiImplicitPositions) {
  const Eigen::Matrix3d I_O = box_inertia();
  BodyState body;
  body.X_GO.translation() = Eigen::Vector3d(0.1, -0.2, 0.3);
  const Eigen::Vector3d x0 = body.X_GO.translation();
  const Eigen::Vector3d F_N(3.0, -1.0, 0.5);
  const double dt_s = 1e-3;
  const int n = 1000;
  for (int k = 0; k < n; ++k)
    integrate_body(body, F_N, Eigen::Vector3d::Zero(), kMass_kg, I_O, I_O.inverse(), dt_s);
  const Eigen::Vector3d a_mps2 = F_N / kMass_kg;
  const double t_s = n * dt_s;
  EXPECT_LT((body.v_G - a_mps2 * t_s).norm(), 1e-12) << "v = F t / m";
  // x_n = x_0 + sum_k v_k dt = x_0 + a dt^2 n (n + 1) / 2: the new velocity moves the body
  // (eq. 24), half a step's a dt t ahead of the continuous a t^2 / 2
  const Eigen::Vector3d x_expected = x0 + a_mps2 * (dt_s * dt_s * n * (n + 1) / 2.0);
  EXPECT_LT((body.X_GO.translation() - x_expected).norm(), 1e-12);
  EXPECT_NEAR((body.X_GO.translation() - x0 - 0.5 * a_mps2 * t_s * t_s).norm(),
              (0.5 * a_mps2 * dt_s * t_s).norm(), 1e-12);
  EXPECT_LT(body.w_G.norm(), 1e-15);
  EXPECT_TRUE(body.X_GO.linear().isApprox(Eigen::Matrix3d::Identity(), 1e-15));
}

// World inertia R I_O R^T.
Eigen::Matrix3d world_inertia(const BodyState& body, const Eigen::Matrix3d& I_O) {
  const Eigen::Matrix3d R = body.X_GO.linear();
  return R * I_O * R.transpose();
}

TEST(Integrator, TorqueFreeSpinKeepsAngularMomentumAndEnergy) {
  // spun about an axis off the principal ones: the body tumbles (w moves in the body), but
  // L = I_G w and E = w . I_G w / 2 are constants of the motion
  const Eigen::Matrix3d I_O = box_inertia();
  BodyState body;
  body.w_G = Eigen::Vector3d(2.0, 0.3, 1.0);  // rad/s, near the stable largest axis
  const Eigen::Vector3d L0 = world_inertia(body, I_O) * body.w_G;
  const double E0 = 0.5 * body.w_G.dot(L0);
  const double dt_s = 1e-4;
  for (int k = 0; k < 20000; ++k) {  // 2 s: several turns
    integrate_body(body, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), kMass_kg, I_O,
                   I_O.inverse(), dt_s);
  }
  const Eigen::Vector3d L = world_inertia(body, I_O) * body.w_G;
  const double E = 0.5 * body.w_G.dot(L);
  // the midpoint rule keeps both exactly: what is left is rounding (the explicit gyroscopic term
  // drifted 2e-5 of |L| and 6e-5 of E here)
  EXPECT_NEAR(L.norm(), L0.norm(), 1e-11 * L0.norm());
  EXPECT_NEAR(E, E0, 1e-11 * E0);
  // and L stays put in the world: the rotation's exponential map differs from the midpoint
  // rule's Cayley turn by (|w| dt)^3 / 12 a step
  EXPECT_LT((L - L0).norm(), 1e-6 * L0.norm());
  EXPECT_GT((body.w_G - Eigen::Vector3d(2.0, 0.3, 1.0)).norm(), 1e-3) << "it does tumble";
  // the rotation stays proper
  const Eigen::Matrix3d R = body.X_GO.linear();
  EXPECT_TRUE((R.transpose() * R).isApprox(Eigen::Matrix3d::Identity(), 1e-12));
  EXPECT_NEAR(R.determinant(), 1.0, 1e-12);
  EXPECT_LT(body.v_G.norm(), 1e-15);
}

TEST(Integrator, TumbleAboutTheIntermediateAxisNeverGainsEnergy) {
  // the unstable middle axis (Dzhanibekov's wing nut) at a coarse step: w swings far through
  // the body, and the energy and |L| hold at every step
  const Eigen::Matrix3d I_O = box_inertia();
  BodyState body;
  body.w_G = Eigen::Vector3d(0.05, 20.0, 0.05);
  const Eigen::Vector3d L0 = world_inertia(body, I_O) * body.w_G;
  const double E0 = 0.5 * body.w_G.dot(L0);
  double most_E = 0.0, worst_L = 0.0, least_wy = body.w_G.y();
  for (int k = 0; k < 10000; ++k) {  // 10 s at 1 ms: several flips
    integrate_body(body, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), kMass_kg, I_O,
                   I_O.inverse(), 1e-3);
    const Eigen::Vector3d L = world_inertia(body, I_O) * body.w_G;
    most_E = std::max(most_E, 0.5 * body.w_G.dot(L));
    worst_L = std::max(worst_L, std::abs(L.norm() - L0.norm()));
    least_wy = std::min(least_wy, (body.X_GO.linear().transpose() * body.w_G).y());
  }
  EXPECT_LT(least_wy, -10.0) << "it flips";
  EXPECT_LE(most_E, E0 * (1.0 + 1e-11));
  EXPECT_LT(worst_L, 1e-11 * L0.norm());
}

TEST(Integrator, GyroscopicMidpointSolvesItsEquation) {
  // I (2 w_m - 2 w0) + dt w_m x I w_m = 0, and the step's change of L is perpendicular to both
  // the midpoint L and w (what keeps |L| and E)
  const Eigen::Matrix3d I_O = box_inertia();
  const Eigen::Vector3d w0(3.0, -40.0, 25.0);
  const double dt_s = 2e-3;  // |w| dt = 0.1
  const Eigen::Vector3d w_m = gyroscopic_midpoint_O(w0, I_O, dt_s);
  const Eigen::Vector3d residual = 2.0 * I_O * (w_m - w0) + dt_s * w_m.cross(I_O * w_m);
  EXPECT_LT(residual.norm(), 1e-14 * (I_O * w0).norm());
  const Eigen::Vector3d dL = I_O * (2.0 * (w_m - w0));
  EXPECT_NEAR(dL.dot(I_O * w_m), 0.0, 1e-14 * dL.norm() * (I_O * w_m).norm());
  EXPECT_NEAR(dL.dot(w_m), 0.0, 1e-14 * dL.norm() * w_m.norm());
  EXPECT_GT(dL.norm(), 1e-3 * (I_O * w0).norm()) << "the step does turn L in the body";
}

TEST(Integrator, TorqueAddsItsImpulseToTheAngularMomentum) {
  // dL/dt = M in the world frame, tumbling or not
  const Eigen::Matrix3d I_O = box_inertia();
  BodyState body;
  body.X_GO.linear() = Eigen::AngleAxisd(0.8, Eigen::Vector3d(1, 2, -1).normalized()).toRotationMatrix();
  body.w_G = Eigen::Vector3d(4.0, -1.0, 2.0);
  const Eigen::Vector3d L0 = world_inertia(body, I_O) * body.w_G;
  const Eigen::Vector3d M_Nm(0.02, 0.01, -0.03);
  const double dt_s = 1e-3;
  const int n = 500;
  for (int k = 0; k < n; ++k)
    integrate_body(body, Eigen::Vector3d::Zero(), M_Nm, kMass_kg, I_O, I_O.inverse(), dt_s);
  const Eigen::Vector3d L = world_inertia(body, I_O) * body.w_G;
  // exact but for the exponential map's turn, (|w| dt)^3 / 12 a step off the midpoint rule's
  const double turn_error = n * std::pow(body.w_G.norm() * dt_s, 3) / 12.0 * L.norm();
  EXPECT_LT(turn_error, 1e-2 * (M_Nm * (n * dt_s)).norm());
  EXPECT_LT((L - L0 - M_Nm * (n * dt_s)).norm(), 2.0 * turn_error);
}

TEST(Integrator, SpinAboutAPrincipalAxisIsExact) {
  // no gyroscopic torque: w stays, and the pose is the exponential map of w t
  const Eigen::Matrix3d I_O = box_inertia();
  BodyState body;
  body.w_G = Eigen::Vector3d(0.0, 0.0, 3.0);
  const double dt_s = 1e-3;
  for (int k = 0; k < 1000; ++k)
    integrate_body(body, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), kMass_kg, I_O,
                   I_O.inverse(), dt_s);
  EXPECT_EQ(body.w_G, Eigen::Vector3d(0.0, 0.0, 3.0));
  const Eigen::Matrix3d expected =
      Eigen::AngleAxisd(3.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  EXPECT_TRUE(body.X_GO.linear().isApprox(expected, 1e-12));
}

TEST(Integrator, RotationIncrementIsExactForLargeAngles) {
  for (const double angle_rad : {0.5, 3.0, M_PI - 1e-9, 5.0, 40.0}) {
    const Eigen::Vector3d axis = Eigen::Vector3d(1.0, -2.0, 0.5).normalized();
    const double dt_s = 0.25;
    const Eigen::Quaterniond q = rotation_increment(axis * (angle_rad / dt_s), dt_s);
    const Eigen::Matrix3d expected = Eigen::AngleAxisd(angle_rad, axis).toRotationMatrix();
    EXPECT_TRUE(q.toRotationMatrix().isApprox(expected, 1e-14)) << angle_rad << " rad";
    EXPECT_NEAR(q.norm(), 1.0, 1e-15);
  }
}

TEST(Integrator, RotationIncrementOfATinyAngleIsNearlyIdentity) {
  const Eigen::Vector3d w(1e-13, -2e-13, 0.0);
  const Eigen::Quaterniond q = rotation_increment(w, 1.0);
  EXPECT_NEAR(q.w(), 1.0, 1e-20);
  EXPECT_NEAR(q.x(), 0.5e-13, 1e-26);
  EXPECT_NEAR(q.y(), -1e-13, 1e-26);
}

TEST(Integrator, FiniteDifferenceGivesBackTheVelocities) {
  const Eigen::Vector3d v_G(0.3, -0.1, 0.2), w_G(0.0, 1.5, -0.5);
  const double dt_s = 0.01;
  Eigen::Isometry3d before = Eigen::Isometry3d::Identity();
  before.linear() = Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitX()).toRotationMatrix();
  before.translation() = Eigen::Vector3d(1.0, 2.0, 3.0);
  Eigen::Isometry3d now = before;
  now.translation() += v_G * dt_s;
  now.linear() = rotation_increment(w_G, dt_s).toRotationMatrix() * before.linear();
  Eigen::Vector3d v, w;
  finite_difference_velocity(before, now, dt_s, v, w);
  EXPECT_LT((v - v_G).norm(), 1e-12);
  EXPECT_LT((w - w_G).norm(), 1e-10);
}

}  // namespace
}  // namespace vcockpit::physics
