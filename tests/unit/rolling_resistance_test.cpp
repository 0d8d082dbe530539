// Rolling and spinning resistance at a pair (rolling_resistance.hpp): couples against the
// relative rolling and the relative spin about the normal, mu N at most, and never more than
// stops that turning within the substep.

#include "physics_node/physics/rolling_resistance.hpp"

#include <gtest/gtest.h>

#include "physics_node/physics/friction_force.hpp"

namespace vcockpit::physics {
namespace {

constexpr double kDt_s = 1e-3;
constexpr double kMass_kg = 0.06;
constexpr double kRadius_m = 0.03;
constexpr double kLoad_N = 0.6;
constexpr double kRoll_m = 1e-3;
constexpr double kSpin_m = 4e-3;

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

Eigen::Vector3d couple(const ContactBody& A, const ContactBody& B, double N = kLoad_N,
                       double roll_m = kRoll_m, double spin_m = kSpin_m) {
  return resistance_couple_on_b_G(A, B, kUp, N, roll_m, spin_m, kDt_s);
}

TEST(RollingResistance, OpposesTheRollWithMuRollTimesTheLoad) {
  const Eigen::Vector3d w(3.0, -4.0, 0.0);  // rolling at 5 rad/s
  const Eigen::Vector3d M = couple(ground(), ball(w));
  EXPECT_NEAR(M.norm(), kRoll_m * kLoad_N, 1e-15);
  EXPECT_NEAR(M.normalized().dot(-w.normalized()), 1.0, 1e-15);
}

TEST(RollingResistance, OpposesTheSpinAboutTheNormalWithMuSpinTimesTheLoad) {
  const Eigen::Vector3d w(0.0, 2.0, 7.0);  // rolling at 2 rad/s, spinning at 7 about the normal
  const Eigen::Vector3d M = couple(ground(), ball(w));
  EXPECT_NEAR(M.z(), -kSpin_m * kLoad_N, 1e-15);
  EXPECT_NEAR(M.y(), -kRoll_m * kLoad_N, 1e-15);
  EXPECT_EQ(M.x(), 0.0);
  // each part has its own coefficient: no spin resistance, no couple about the normal
  EXPECT_EQ(couple(ground(), ball(w), kLoad_N, kRoll_m, 0.0).z(), 0.0);
  EXPECT_EQ(couple(ground(), ball(w), kLoad_N, 0.0, kSpin_m).y(), 0.0);
}

TEST(RollingResistance, ASlowTurnIsStoppedWithinTheSubstepNotReversed) {
  // mu N dt / I = 1e-3 * 0.6 * 1e-3 / 2.16e-5 = 0.028 rad/s: slower rolls stop in one substep
  // (spins below 0.11 rad/s)
  for (const double rate_radps : {0.02, 1e-3, 1e-9}) {
    for (const Eigen::Vector3d& axis : {Eigen::Vector3d(Eigen::Vector3d::UnitY()), kUp}) {
      const ContactBody b = ball(rate_radps * axis);
      const Eigen::Vector3d M = couple(ground(), b);
      EXPECT_GT(M.norm(), 0.0);
      const Eigen::Vector3d w_after = b.w_G + b.inv_I_O * M * kDt_s;
      EXPECT_NEAR(w_after.norm(), 0.0, 1e-12 * rate_radps) << rate_radps << " about " << axis.transpose();
    }
  }
}

TEST(RollingResistance, TwoTurningBodiesShareTheStopByTheirInertias) {
  // ball b rolls on ball a; the couple slows their relative roll, each by its own inertia, and
  // a slow relative roll ends at zero
  ContactBody a = ball(Eigen::Vector3d(0.0, 0.010, 0.0));
  ContactBody b = ball(Eigen::Vector3d(0.0, 0.015, 0.0));
  b.inv_I_O *= 2.0;  // b is half as hard to turn
  const Eigen::Vector3d M = couple(a, b);
  const Eigen::Vector3d wa = a.w_G - a.inv_I_O * M * kDt_s;
  const Eigen::Vector3d wb = b.w_G + b.inv_I_O * M * kDt_s;
  EXPECT_NEAR((wb - wa).y(), 0.0, 1e-15);
  EXPECT_LT(M.y(), 0.0);
  // turning together is no relative turning
  EXPECT_TRUE(couple(ball(Eigen::Vector3d(1, 2, 3)), ball(Eigen::Vector3d(1, 2, 3))).isZero(0.0));
}

TEST(RollingResistance, NothingWithoutLoadCoefficientOrAMovableBody) {
  const ContactBody b = ball(Eigen::Vector3d(0.0, 5.0, 5.0));
  EXPECT_TRUE(couple(ground(), b, 0.0).isZero(0.0));
  EXPECT_TRUE(couple(ground(), b, kLoad_N, 0.0, 0.0).isZero(0.0));
  ContactBody held = b;
  held.inv_I_O.setZero();  // held or kinematic: nothing to slow
  EXPECT_TRUE(couple(ground(), held).isZero(0.0));
  EXPECT_TRUE(couple(ground(), ball(Eigen::Vector3d::Zero())).isZero(0.0));
}

TEST(RollingResistance, PairCoefficientsAreTheGeometricMeans) {
  Material rubber, steel, none;
  rubber.mu_roll_m = 4e-4;
  rubber.mu_spin_m = 9e-4;
  steel.mu_roll_m = 1e-4;
  steel.mu_spin_m = 1e-4;
  none.mu_roll_m = 0.0;
  none.mu_spin_m = 0.0;
  ContactBody A, B;
  A.material = &rubber;
  B.material = &steel;
  EXPECT_NEAR(pair_friction(A, B).mu_roll_m, 2e-4, 1e-18);
  EXPECT_NEAR(pair_friction(A, B).mu_spin_m, 3e-4, 1e-18);
  B.material = &none;
  EXPECT_EQ(pair_friction(A, B).mu_roll_m, 0.0);
  EXPECT_EQ(pair_friction(A, B).mu_spin_m, 0.0);
}

}  // namespace
}  // namespace vcockpit::physics
