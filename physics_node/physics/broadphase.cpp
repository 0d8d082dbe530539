#include "physics_node/physics/broadphase.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace vcockpit::physics {

Aabb shape_aabb(const Shape& shape, const Eigen::Isometry3d& X_GS) {
  const Eigen::Matrix3d& R = X_GS.linear();
  Eigen::Vector3d c = X_GS.translation();
  Eigen::Vector3d half = Eigen::Vector3d::Zero();
  switch (shape.kind) {
    case ShapeKind::kBox:
      half = R.cwiseAbs() * (0.5 * shape.box_size_m);
      break;
    case ShapeKind::kSphere:
      half.setConstant(shape.radius_m);
      break;
    case ShapeKind::kCapsule:  // the axis segment, swept by the radius
      half = (0.5 * shape.length_m) * R.col(2).cwiseAbs() + Eigen::Vector3d::Constant(shape.radius_m);
      break;
    case ShapeKind::kCylinder: {  // the axis segment plus the caps' disks: r sqrt(1 - a_i^2)
      const Eigen::Vector3d a = R.col(2);
      for (int i = 0; i < 3; ++i)
        half[i] = 0.5 * shape.length_m * std::abs(a[i]) +
                  shape.radius_m * std::sqrt(std::max(0.0, 1.0 - a[i] * a[i]));
      break;
    }
    case ShapeKind::kMesh: {  // the box round the vertices, turned
      const model::Bounds& b = shape.mesh_bounds;
      c = X_GS * (0.5 * (b.min_m + b.max_m));
      half = R.cwiseAbs() * (0.5 * (b.max_m - b.min_m));
      break;
    }
  }
  return {c - half, c + half};
}

SweepAndPrune::SweepAndPrune(std::vector<BroadphaseBody> kinds)
    : kinds_(std::move(kinds)), boxes_(kinds_.size()), enabled_(kinds_.size(), 1) {
  for (std::size_t i = 0; i < kinds_.size(); ++i)
    if (kinds_[i] == BroadphaseBody::kHand) enabled_[i] = 0;  // until its hand is active
  for (std::size_t i = 0; i < kinds_.size(); ++i)
    (kinds_[i] == BroadphaseBody::kStatic ? statics_ : order_).push_back(static_cast<int>(i));
}

bool SweepAndPrune::can_act(int a, int b) const {
  const BroadphaseBody ka = kinds_[static_cast<std::size_t>(a)];
  const BroadphaseBody kb = kinds_[static_cast<std::size_t>(b)];
  const bool hand = ka == BroadphaseBody::kHand || kb == BroadphaseBody::kHand;
  if (enabled_[static_cast<std::size_t>(a)] == 0 || enabled_[static_cast<std::size_t>(b)] == 0)
    return false;
  if (ka == BroadphaseBody::kDynamic || kb == BroadphaseBody::kDynamic) return true;
  // a control acts with the hand only (and with free objects, above): its joint holds it in its
  // panel, and a cockpit's controls are laid out not to touch one another
  if (ka == BroadphaseBody::kControl || kb == BroadphaseBody::kControl)
    return ka == BroadphaseBody::kHand || kb == BroadphaseBody::kHand;
  // neither is dynamic: static-static and hand-hand never act; hand-static when asked for
  return report_hand_static_ && hand && (ka == BroadphaseBody::kStatic || kb == BroadphaseBody::kStatic);
}

void SweepAndPrune::find_pairs(std::vector<BodyPair>& out) {
  out.clear();
  if (axis_ < 0) {
    // the axis along which the box centres spread the most separates the most pairs
    Eigen::Vector3d mean = Eigen::Vector3d::Zero(), sq = Eigen::Vector3d::Zero();
    for (const Aabb& b : boxes_) {
      const Eigen::Vector3d c = 0.5 * (b.lo + b.hi);
      mean += c;
      sq += c.cwiseProduct(c);
    }
    const double n = std::max<double>(1.0, static_cast<double>(boxes_.size()));
    const Eigen::Vector3d variance = sq / n - (mean / n).cwiseProduct(mean / n);
    variance.maxCoeff(&axis_);
  }
  const int axis = axis_;
  // the moving bodies by sweep and prune: insertion sort by the lower end (stable: ties keep
  // their order, so the sweep is a function of the poses' history only, and the output is
  // sorted anyway)
  for (std::size_t i = 1; i < order_.size(); ++i) {
    const int body = order_[i];
    const double key = boxes_[static_cast<std::size_t>(body)].lo[axis];
    std::size_t j = i;
    while (j > 0 && boxes_[static_cast<std::size_t>(order_[j - 1])].lo[axis] > key) {
      order_[j] = order_[j - 1];
      --j;
    }
    order_[j] = body;
  }
  for (std::size_t i = 0; i < order_.size(); ++i) {
    const int a = order_[i];
    if (enabled_[static_cast<std::size_t>(a)] == 0) continue;
    const Aabb& box_a = boxes_[static_cast<std::size_t>(a)];
    for (std::size_t j = i + 1; j < order_.size(); ++j) {
      const int b = order_[j];
      const Aabb& box_b = boxes_[static_cast<std::size_t>(b)];
      if (box_b.lo[axis] > box_a.hi[axis]) break;  // no later box reaches back to a
      if (!can_act(a, b) || !box_a.overlaps(box_b)) continue;
      out.push_back({std::min(a, b), std::max(a, b)});
    }
  }
  // the static bodies never move and never pair with each other: each moving body that can act
  // with them against each of them (the floor and the walls span the sweep axis, so in the sweep
  // they met every body)
  for (const int a : order_) {
    const BroadphaseBody ka = kinds_[static_cast<std::size_t>(a)];
    const bool acts = ka == BroadphaseBody::kDynamic ||
                      (ka == BroadphaseBody::kHand && enabled_[static_cast<std::size_t>(a)] != 0 &&
                       report_hand_static_);
    if (!acts) continue;
    const Aabb& box_a = boxes_[static_cast<std::size_t>(a)];
    for (const int b : statics_)
      if (box_a.overlaps(boxes_[static_cast<std::size_t>(b)])) out.push_back({std::min(a, b), std::max(a, b)});
  }
  std::sort(out.begin(), out.end());
}

}  // namespace vcockpit::physics
