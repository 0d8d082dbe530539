#include "hand/tracking/rigid_fit.hpp"

#include <Eigen/SVD>

#include <cassert>

namespace vcockpit::hand::tracking {

Eigen::Isometry3d rigid_fit(std::span<const Eigen::Vector3d> a, std::span<const Eigen::Vector3d> b,
                            std::span<const double> weights) {
  assert(a.size() == b.size() && !a.empty());
  assert(weights.empty() || weights.size() == a.size());
  const auto w = [&](std::size_t i) { return weights.empty() ? 1.0 : weights[i]; };
  double total = 0.0;
  Eigen::Vector3d ca = Eigen::Vector3d::Zero(), cb = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < a.size(); ++i) {
    total += w(i);
    ca += w(i) * a[i];
    cb += w(i) * b[i];
  }
  ca /= total;
  cb /= total;
  Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
  for (std::size_t i = 0; i < a.size(); ++i) H += w(i) * (a[i] - ca) * (b[i] - cb).transpose();
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(H, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d D = Eigen::Matrix3d::Identity();
  if ((svd.matrixV() * svd.matrixU().transpose()).determinant() < 0.0) D(2, 2) = -1.0;
  Eigen::Isometry3d X_BA = Eigen::Isometry3d::Identity();
  X_BA.linear() = svd.matrixV() * D * svd.matrixU().transpose();
  X_BA.translation() = cb - X_BA.linear() * ca;
  return X_BA;
}

}  // namespace vcockpit::hand::tracking
