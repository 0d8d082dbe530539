#include <gtest/gtest.h>

#include "common/pose.hpp"

namespace vcockpit {
namespace {

constexpr double kTol = 1e-12;

TEST(Pose, RpyIsExtrinsicXyzSoYawIsAppliedLast) {
  // roll 90 deg maps y to z; then yaw 90 deg maps that z to z (unchanged) and x to y.
  const Eigen::Matrix3d R = rotation_from_rpy(M_PI / 2, 0, M_PI / 2);
  EXPECT_TRUE((R * Eigen::Vector3d::UnitY()).isApprox(Eigen::Vector3d::UnitZ(), kTol));
  EXPECT_TRUE((R * Eigen::Vector3d::UnitX()).isApprox(Eigen::Vector3d::UnitY(), kTol));
}

TEST(Pose, EulerZyxEqualsRpyWithReversedAngles) {
  const double a = 0.3, b = -0.7, c = 1.1;
  EXPECT_TRUE(rotation_from_euler("zyx", a, b, c).isApprox(rotation_from_rpy(c, b, a), kTol));
}

TEST(Pose, EulerRejectsBadConventions) {
  EXPECT_FALSE(is_valid_euler_axes("zzx"));
  EXPECT_FALSE(is_valid_euler_axes("xy"));
  EXPECT_FALSE(is_valid_euler_axes("abc"));
  EXPECT_TRUE(is_valid_euler_axes("zxz"));
  EXPECT_THROW(rotation_from_euler("xx", 0, 0, 0), std::invalid_argument);
}

TEST(Pose, ComposesInMonogramOrder) {
  const auto X_AB = pose_from_position_rpy_deg({1, 0, 0}, {0, 0, 90});
  const auto X_BC = pose_from_position_rpy_deg({1, 0, 0}, {0, 0, 0});
  const Eigen::Isometry3d X_AC = X_AB * X_BC;
  EXPECT_TRUE(X_AC.translation().isApprox(Eigen::Vector3d(1, 1, 0), kTol));
}

}  // namespace
}  // namespace vcockpit
