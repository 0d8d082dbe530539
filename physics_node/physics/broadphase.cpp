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
    : kinds_(std::move(kinds)),
      boxes_(kinds_.size()),
      enabled_(kinds_.size(), 1),
      asleep_(kinds_.size(), 0) {
  for (std::size_t i = 0; i < kinds_.size(); ++i)
    if (kinds_[i] == BroadphaseBody::kHand) enabled_[i] = 0;  // until its hand is active
  for (std::size_t i = 0; i < kinds_.size(); ++i)
    (kinds_[i] == BroadphaseBody::kStatic ? statics_ : order_).push_back(static_cast<int>(i));
  awake_.reserve(order_.size());
  sleeping_.reserve(order_.size());
  static_movers_.reserve(order_.size());
}

bool SweepAndPrune::can_act(int a, int b) const {
  const BroadphaseBody ka = kinds_[static_cast<std::size_t>(a)];
  const BroadphaseBody kb = kinds_[static_cast<std::size_t>(b)];
  const bool hand = ka == BroadphaseBody::kHand || kb == BroadphaseBody::kHand;
  if (enabled_[static_cast<std::size_t>(a)] == 0 || enabled_[static_cast<std::size_t>(b)] == 0)
    return false;
  const bool a_asleep = asleep_[static_cast<std::size_t>(a)] != 0;
  const bool b_asleep = asleep_[static_cast<std::size_t>(b)] != 0;
  if (a_asleep || b_asleep)  // only something that moves wakes a sleeping body
    return !(a_asleep && b_asleep) && ka != BroadphaseBody::kStatic && kb != BroadphaseBody::kStatic;
  if (ka == BroadphaseBody::kDynamic || kb == BroadphaseBody::kDynamic) return true;
  // a control acts with the hand only (and with free objects, above): its joint holds it in its
  // panel, and a cockpit's controls are laid out not to touch one another
  if (ka == BroadphaseBody::kControl || kb == BroadphaseBody::kControl)
    return ka == BroadphaseBody::kHand || kb == BroadphaseBody::kHand;
  // neither is dynamic: static-static and hand-hand never act; hand-static when asked for
  return report_hand_static_ && hand && (ka == BroadphaseBody::kStatic || kb == BroadphaseBody::kStatic);
}

void SweepAndPrune::sweep_across(const std::vector<int>& firsts, const std::vector<int>& seconds,
                                 bool after_ties, bool all_act, std::vector<BodyPair>& out) const {
  const int axis = axis_;
  std::size_t start = 0;  // the first of `seconds` starting at or after (after_ties: after) a
  for (const int a : firsts) {
    const Aabb& box_a = boxes_[static_cast<std::size_t>(a)];
    const auto before_a = [&](int b) {
      const double lo = boxes_[static_cast<std::size_t>(b)].lo[axis];
      return after_ties ? lo <= box_a.lo[axis] : lo < box_a.lo[axis];
    };
    while (start < seconds.size() && before_a(seconds[start])) ++start;
    for (std::size_t j = start; j < seconds.size(); ++j) {
      const int b = seconds[j];
      const Aabb& box_b = boxes_[static_cast<std::size_t>(b)];
      if (box_b.lo[axis] > box_a.hi[axis]) break;
      if (!box_a.overlaps(box_b) || (!all_act && !can_act(a, b))) continue;
      out.push_back({std::min(a, b), std::max(a, b)});
    }
  }
}

void SweepAndPrune::sort_by_lower_end(std::vector<int>& bodies) const {
  const int axis = axis_;
  for (std::size_t i = 1; i < bodies.size(); ++i) {
    const int body = bodies[i];
    const double key = boxes_[static_cast<std::size_t>(body)].lo[axis];
    std::size_t j = i;
    while (j > 0 && boxes_[static_cast<std::size_t>(bodies[j - 1])].lo[axis] > key) {
      bodies[j] = bodies[j - 1];
      --j;
    }
    bodies[j] = body;
  }
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
  sort_by_lower_end(order_);
  // the moving bodies split, each list still sorted: a sleeping body pairs only with awake ones,
  // so two sleepers are never even looked at (a heap of sleepers costs what its size does, not
  // what its crowding does)
  // (a disabled body, a link of an inactive hand, acts with nothing: left out here)
  awake_.clear();
  sleeping_.clear();
  static_movers_.clear();
  for (const int body : order_) {
    const auto b = static_cast<std::size_t>(body);
    if (enabled_[b] == 0) continue;
    if (asleep_[b] != 0) {
      sleeping_.push_back(body);
      continue;
    }
    awake_.push_back(body);
    // the awake bodies that act with static ones: free objects, and hand links when asked for
    // (a control sits in its panel's cut-out)
    if (kinds_[b] == BroadphaseBody::kDynamic || (kinds_[b] == BroadphaseBody::kHand && report_hand_static_))
      static_movers_.push_back(body);
  }
  // two awake bodies (enabled, neither static) act when either is a free object, or when one is
  // a control and the other a hand link (can_act's rules for such bodies, by kind alone: a
  // hand's links crowd each other on every axis, so this is asked before the boxes)
  const auto awake_pair_acts = [](BroadphaseBody ka, BroadphaseBody kb) {
    if (ka == BroadphaseBody::kDynamic || kb == BroadphaseBody::kDynamic) return true;
    return (ka == BroadphaseBody::kControl && kb == BroadphaseBody::kHand) ||
           (ka == BroadphaseBody::kHand && kb == BroadphaseBody::kControl);
  };
  for (std::size_t i = 0; i < awake_.size(); ++i) {
    const int a = awake_[i];
    const BroadphaseBody ka = kinds_[static_cast<std::size_t>(a)];
    const Aabb& box_a = boxes_[static_cast<std::size_t>(a)];
    for (std::size_t j = i + 1; j < awake_.size(); ++j) {
      const int b = awake_[j];
      const Aabb& box_b = boxes_[static_cast<std::size_t>(b)];
      if (box_b.lo[axis] > box_a.hi[axis]) break;  // no later box reaches back to a
      if (!awake_pair_acts(ka, kinds_[static_cast<std::size_t>(b)]) || !box_a.overlaps(box_b)) continue;
      out.push_back({std::min(a, b), std::max(a, b)});
    }
  }
  if (!sleeping_.empty()) {
    // each awake-sleeping pair once, from the box that starts first (ties: the awake one's)
    sweep_across(awake_, sleeping_, /*after_ties=*/false, /*all_act=*/false, out);
    sweep_across(sleeping_, awake_, /*after_ties=*/true, /*all_act=*/false, out);
  }
  // the static bodies never move and never pair with each other: the same two-list sweep between
  // them and the awake bodies that act with them (the floor and the walls span the sweep axis
  // and meet every body; a panel meets only what reaches its span)
  sort_by_lower_end(statics_);
  sweep_across(static_movers_, statics_, /*after_ties=*/false, /*all_act=*/true, out);
  sweep_across(statics_, static_movers_, /*after_ties=*/true, /*all_act=*/true, out);
  std::sort(out.begin(), out.end());
}

}  // namespace vcockpit::physics
