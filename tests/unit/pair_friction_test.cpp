// A touching pair's friction coefficients (friction_force.hpp): geometric means of the two
// materials' (Box2D, Jolt), the sliding one never above the static one.

#include "physics_node/physics/friction_force.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace vcockpit::physics {
namespace {

TEST(PairFriction, StaticAndSlidingAreTheGeometricMeansSlidingAtMostStatic) {
  Material rubber, steel;
  rubber.mu_s = 0.9;
  rubber.mu_d = 0.8;
  steel.mu_s = 0.4;
  steel.mu_d = 0.1;
  ContactBody A, B;
  A.material = &rubber;
  B.material = &steel;
  EXPECT_NEAR(pair_friction(A, B).mu_s, 0.6, 1e-15);
  EXPECT_NEAR(pair_friction(A, B).mu_d, std::sqrt(0.08), 1e-15);
  // a material whose sliding coefficient exceeds the pair's static one is capped there
  steel.mu_d = 0.9;
  EXPECT_EQ(pair_friction(A, B).mu_d, pair_friction(A, B).mu_s);
}

TEST(PairFriction, RollingAndSpinningAreTheGeometricMeansNoneWhenEitherHasNone) {
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
