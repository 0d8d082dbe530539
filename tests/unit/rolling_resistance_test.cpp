// Rolling resistance at a pair (rolling_resistance.hpp): a couple against the relative rolling
// angular velocity, mu_roll N at most, and never more than stops the roll within the substep.

#include "physics_node/physics/rolling_resistance.hpp"

#include <gtest/gtest.h>

#include "physics_node/physics/friction_force.hpp"

namespace vcockpit::physics {
namespace {

constexpr double kDt_s = 1e-3;
constexpr double kMass_kg = 0.06;
constexpr double kRadius_m = 0.03;

// A 60 g, 3 cm solid sphere (I = 2/5 m r^2) at the origin, free to turn.
ContactBody ball(const Eigen::Vector3d& w_G) {
  ContactBody b;
  b.dynamic = true;
  b.inv_mass = 1.0 / kMass_kg;
  b.inv_I_O = Eigen::Matrix3d::Identity() / (0.4 * kMass_kg * kRadius_m * kRadius_m);
  b.w_G = w_G;
  return b;
}

ContactBody ground() { return ContactBody{}; }  // immovable: no inverse inertia

const Eigen::Vector3d kUp = Eigen::Vector3d::UnitZ();

TEST(RollingResistance, OpposesTheRollWithMuRollTimesTheLoad) {
  const Eigen::Vector3d w(3.0, -4.0, 0.0);  // rolling at 5 rad/s
  const Eigen::Vector3d M = rolling_torque_on_b_G(ground(), ball(w), kUp, 0.6, 1e-3, kDt_s);
  EXPECT_NEAR(M.norm(), 1e-3 * 0.6, 1e-15);
  EXPECT_NEAR(M.normalized().dot(-w.normalized()), 1.0, 1e-15);
}

TEST(RollingResistance, SpinAboutTheNormalIsNotRolling) {
  const Eigen::Vector3d w(0.0, 2.0, 7.0);  // rolling at 2 rad/s, spinning at 7 about the normal
  const Eigen::Vector3d M = rolling_torque_on_b_G(ground(), ball(w), kUp, 0.6, 1e-3, kDt_s);
  EXPECT_NEAR(M.z(), 0.0, 1e-18);
  EXPECT_LT(M.y(), 0.0);
  EXPECT_TRUE(rolling_torque_on_b_G(ground(), ball(7.0 * kUp), kUp, 0.6, 1e-3, kDt_s).isZero(0.0));
}

TEST(RollingResistance, ASlowRollIsStoppedWithinTheSubstepNotReversed) {
  // mu_roll N dt / I = 1e-3 * 0.6 * 1e-3 / 2.16e-5 = 0.028 rad/s: slower rolls stop in one substep
  for (const double rate_radps : {0.02, 1e-3, 1e-9}) {
    const ContactBody b = ball(Eigen::Vector3d(0.0, rate_radps, 0.0));
    const Eigen::Vector3d M = rolling_torque_on_b_G(ground(), b, kUp, 0.6, 1e-3, kDt_s);
    EXPECT_LT(M.norm(), 1e-3 * 0.6) << rate_radps;
    const Eigen::Vector3d w_after = b.w_G + b.inv_I_O * M * kDt_s;
    EXPECT_NEAR(w_after.y(), 0.0, 1e-12 * rate_radps) << rate_radps;
  }
}

TEST(RollingResistance, TwoTurningBodiesShareTheStopByTheirInertias) {
  // ball b rolls on ball a; the couple slows their relative roll, each by its own inertia, and
  // a slow relative roll ends at zero
  ContactBody a = ball(Eigen::Vector3d(0.0, 0.010, 0.0));
  ContactBody b = ball(Eigen::Vector3d(0.0, 0.015, 0.0));
  b.inv_I_O *= 2.0;  // b is half as hard to turn
  const Eigen::Vector3d M = rolling_torque_on_b_G(a, b, kUp, 0.6, 1e-3, kDt_s);
  const Eigen::Vector3d wa = a.w_G - a.inv_I_O * M * kDt_s;
  const Eigen::Vector3d wb = b.w_G + b.inv_I_O * M * kDt_s;
  EXPECT_NEAR((wb - wa).y(), 0.0, 1e-15);
  EXPECT_LT(M.y(), 0.0);
}

TEST(RollingResistance, NothingWithoutLoadCoefficientOrAMovableBody) {
  const ContactBody b = ball(Eigen::Vector3d(0.0, 5.0, 0.0));
  EXPECT_TRUE(rolling_torque_on_b_G(ground(), b, kUp, 0.0, 1e-3, kDt_s).isZero(0.0));
  EXPECT_TRUE(rolling_torque_on_b_G(ground(), b, kUp, 0.6, 0.0, kDt_s).isZero(0.0));
  ContactBody held = b;
  held.inv_I_O.setZero();  // held or kinematic: nothing to slow
  EXPECT_TRUE(rolling_torque_on_b_G(ground(), held, kUp, 0.6, 1e-3, kDt_s).isZero(0.0));
  EXPECT_TRUE(rolling_torque_on_b_G(ground(), ball(Eigen::Vector3d::Zero()), kUp, 0.6, 1e-3, kDt_s)
                  .isZero(0.0));
}

TEST(RollingResistance, PairCoefficientIsTheGeometricMean) {
  Material rubber, steel, none;
  rubber.mu_roll_m = 4e-4;
  steel.mu_roll_m = 1e-4;
  none.mu_roll_m = 0.0;
  ContactBody A, B;
  A.material = &rubber;
  B.material = &steel;
  EXPECT_NEAR(pair_friction(A, B).mu_roll_m, 2e-4, 1e-18);
  B.material = &none;
  EXPECT_EQ(pair_friction(A, B).mu_roll_m, 0.0);
}

}  // namespace
}  // namespace vcockpit::physics
