// The rigid fit (Kabsch) that places the retargeted palm and that grip_drift uses: closed forms.

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "hand/tracking/rigid_fit.hpp"

namespace vcockpit::hand::tracking {
namespace {

Eigen::Isometry3d some_pose() {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = Eigen::AngleAxisd(2.1, Eigen::Vector3d(1, -2, 0.5).normalized()).toRotationMatrix();
  X.translation() = Eigen::Vector3d(0.3, -0.45, 0.9);
  return X;
}

std::vector<Eigen::Vector3d> palm_like_points() {
  return {{0, 0, 0}, {0.09, 0.03, 0}, {0.095, 0.01, 0}, {0.09, -0.01, 0.002},
          {0.08, -0.03, 0.004}, {0.03, 0.04, -0.01}, {-0.03, 0, 0}};
}

TEST(RigidFit, RecoversTheTransformOfExactPoints) {
  const Eigen::Isometry3d X_BA = some_pose();
  const std::vector<Eigen::Vector3d> a = palm_like_points();
  std::vector<Eigen::Vector3d> b;
  for (const auto& p : a) b.push_back(X_BA * p);
  const Eigen::Isometry3d fit = rigid_fit(a, b);
  EXPECT_LT((fit.linear() - X_BA.linear()).norm(), 1e-12);
  EXPECT_LT((fit.translation() - X_BA.translation()).norm(), 1e-12);
}

TEST(RigidFit, AMirroredSetGivesARotationNotAReflection) {
  // b is a mirrored copy of a: the best proper rotation, never a reflection (det +1)
  const std::vector<Eigen::Vector3d> a = palm_like_points();
  std::vector<Eigen::Vector3d> b;
  for (const auto& p : a) b.push_back({p.x(), p.y(), -p.z() * 50.0});
  const Eigen::Isometry3d fit = rigid_fit(a, b);
  EXPECT_NEAR(fit.linear().determinant(), 1.0, 1e-12);
  EXPECT_LT((fit.linear().transpose() * fit.linear() - Eigen::Matrix3d::Identity()).norm(), 1e-12);
}

TEST(RigidFit, PointsOfTinyWeightDoNotMoveTheFit) {
  // two points pulled 1 cm off: with weight 1 they move the fit, with weight 1e-9 they do not
  const Eigen::Isometry3d X_BA = some_pose();
  const std::vector<Eigen::Vector3d> a = palm_like_points();
  std::vector<Eigen::Vector3d> b;
  for (const auto& p : a) b.push_back(X_BA * p);
  b[0] += Eigen::Vector3d(0.01, 0, 0);
  b[6] += Eigen::Vector3d(0, 0.01, 0);
  std::vector<double> w(a.size(), 1.0);
  const Eigen::Isometry3d even = rigid_fit(a, b, w);
  w[0] = w[6] = 1e-9;
  const Eigen::Isometry3d weighted = rigid_fit(a, b, w);
  EXPECT_GT((even.translation() - X_BA.translation()).norm(), 1e-3);
  EXPECT_LT((weighted.translation() - X_BA.translation()).norm(), 1e-9);
  EXPECT_LT((weighted.linear() - X_BA.linear()).norm(), 1e-8);
}

TEST(RigidFit, NoisyPointsGiveTheCentroidsMatched) {
  // the fit maps the weighted centroid of a onto that of b, whatever the noise
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, 0.002);
  const Eigen::Isometry3d X_BA = some_pose();
  const std::vector<Eigen::Vector3d> a = palm_like_points();
  std::vector<Eigen::Vector3d> b;
  const std::array<double, 7> w = {1.0, 1.0, 1.0, 1.0, 1.0, 0.5, 0.5};
  Eigen::Vector3d ca = Eigen::Vector3d::Zero(), cb = Eigen::Vector3d::Zero();
  double total = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    b.push_back(X_BA * a[i] + Eigen::Vector3d(noise(rng), noise(rng), noise(rng)));
    ca += w[i] * a[i];
    cb += w[i] * b[i];
    total += w[i];
  }
  const Eigen::Isometry3d fit = rigid_fit(a, b, w);
  EXPECT_LT((fit * (ca / total) - cb / total).norm(), 1e-12);
  EXPECT_LT(Eigen::AngleAxisd(fit.linear().transpose() * X_BA.linear()).angle(), 0.1);
}

}  // namespace
}  // namespace vcockpit::hand::tracking
