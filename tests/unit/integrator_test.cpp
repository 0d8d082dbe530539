// The integrator (eqs. 20-25) against closed forms: a constant force gives v = F t / m and the
// semi-implicit Euler positions; a torque-free spin keeps |L| and the kinetic energy; the
// rotation increment is the exact exponential map at any angle; finite differences of poses
// give back the velocities that made them.

#include "physics_node/physics/integrator.hpp"

#include <gtest/gtest.h>

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
  // explicit gyroscopic term: a first-order drift, 2e-5 of |L| and 6e-5 of E here
  EXPECT_NEAR(L.norm(), L0.norm(), 1e-4 * L0.norm()) << "|L| within 0.01 % over 2 s";
  EXPECT_NEAR(E, E0, 2e-4 * E0) << "E within 0.02 % over 2 s";
  EXPECT_GT((body.w_G - Eigen::Vector3d(2.0, 0.3, 1.0)).norm(), 1e-3) << "it does tumble";
  // the rotation stays proper
  const Eigen::Matrix3d R = body.X_GO.linear();
  EXPECT_TRUE((R.transpose() * R).isApprox(Eigen::Matrix3d::Identity(), 1e-12));
  EXPECT_NEAR(R.determinant(), 1.0, 1e-12);
  EXPECT_LT(body.v_G.norm(), 1e-15);
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
