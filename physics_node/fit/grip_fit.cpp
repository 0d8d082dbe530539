#include "physics_node/fit/grip_fit.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "physics_node/fit/nelder_mead.hpp"
#include "physics_node/fit/rest_orientation.hpp"
#include "physics_node/fit/shape_distance.hpp"

namespace vcockpit::fit {
namespace {

using hand::Finger;
using hand::Link;
using physics::Shape;
using physics::ShapeKind;

constexpr double kMm = 1e-3;
// One search unit of yaw (rad): 1 mm at a 5 cm lever, so a unit moves the object's far parts
// about as far as a unit of position (1 mm) does.
constexpr double kYawUnit_rad = 0.02;
// Yaws tried per resting orientation whose yaw is free (every 30 deg).
constexpr int kStartYaws = 6;
constexpr double kNudge_m = 0.008;
constexpr double kDepthWeight = 10.0;
constexpr double kRestWeight = 1e-3;
// The opposing finger's normal short of opposing the thumb's by (cos) x costs kOppositionWeight
// x^2 (mm^2): one pressing the same way as the thumb (x ~ 1.3) as much as a 6 mm gap. The target is
// kOppositionMargin_deg beyond the limit, as the distances' are inside theirs.
constexpr double kOppositionWeight = 25.0;
constexpr double kOppositionMargin_deg = 15.0;

// The continuation's stages (fit_object_in_grip): share of the object's size, the simplex's
// first step (search units: mm, kYawUnit_rad) and its evaluations. The last stage is the
// object itself, twice: a simplex can collapse short of the minimum, so once more from there.
struct Stage {
  double size_share;
  double step;
  int evaluations;
};
constexpr Stage kStages[] = {{0.6, 4.0, 800}, {0.8, 2.0, 600}, {1.0, 2.0, 1200}, {1.0, 1.0, 600}};
constexpr int kTightEvaluations = 600;

Shape scaled(const Shape& shape, double share) {
  Shape out = shape;
  out.box_size_m *= share;
  out.radius_m *= share;
  out.length_m *= share;
  return out;
}

double hinge(double x) {
  return x > 0.0 ? x : 0.0;
}

// How far inside the limits the cost aims: the search aims at half of each (contact within
// 0.5 mm, no link over 1 mm in) and an opposing finger 15 deg beyond the limit, so what it finds
// passes with room to spare; where the grip is too tight for those margins the same search is
// polished once more at 98 % of the distance limits (the figures that pass then pass narrowly).
// The opposition keeps its 15 deg: a polish aimed at the limit itself would take a finger just
// past it, which says little about a grip.
struct Margins {
  double limit_share;
  double opposition_deg;
};
constexpr Margins kRoomy{0.5, kOppositionMargin_deg};
constexpr Margins kTight{0.98, kOppositionMargin_deg};

// The search cost of a placement's figures (grip_fit.hpp), in mm^2.
double placement_cost(const Placement& p, const FitLimits& limits, const Margins& margins) {
  const double c_mm = margins.limit_share * limits.contact_m / kMm;
  const double e_mm = margins.limit_share * limits.max_depth_m / kMm;
  const double cos_target =
      std::cos((limits.opposition_deg + margins.opposition_deg) * M_PI / 180.0);
  std::array<double, hand::kFingerCount - 1> gaps{};
  double opposing = INFINITY;  // the finger best placed to oppose the thumb
  for (int f = 1; f < hand::kFingerCount; ++f) {
    const auto fk = static_cast<std::size_t>(f);
    const double gap = hinge(p.finger_distance_m[fk] / kMm - c_mm);
    const double along = hinge(p.finger_normal_G[0].dot(p.finger_normal_G[fk]) - cos_target);
    gaps[fk - 1] = gap * gap;
    opposing = std::min(opposing, gap * gap + kOppositionWeight * along * along);
  }
  std::sort(gaps.begin(), gaps.end());
  const double thumb = hinge(p.finger_distance_m[0] / kMm - c_mm);
  double cost = thumb * thumb + (limits.opposing_fingers > 0 ? opposing : 0.0);
  for (std::size_t i = 0; i < gaps.size(); ++i)
    cost += (static_cast<int>(i) < limits.other_fingers ? 1.0 : kRestWeight) * gaps[i];
  for (double d_m : p.link_distance_m) {
    const double deep = hinge(-d_m / kMm - e_mm);
    cost += kDepthWeight * deep * deep;
  }
  return cost;
}

Eigen::Vector3d midpoint(const GripHand& hand, Link link) {
  const auto k = static_cast<std::size_t>(link);
  return 0.5 * (hand.a_G[k] + hand.b_G[k]);
}

// Positions p_G to start from (grip_fit.hpp).
std::vector<Eigen::Vector3d> start_positions(const GripHand& hand, const Shape& shape) {
  std::vector<Eigen::Vector3d> out;
  Eigen::Vector3d phalanges = Eigen::Vector3d::Zero(), tips = Eigen::Vector3d::Zero();
  for (int l = 1; l < hand::kLinkCount; ++l)
    phalanges += midpoint(hand, static_cast<Link>(l));
  for (int f = 0; f < hand::kFingerCount; ++f)
    tips += hand.b_G[static_cast<std::size_t>(hand::finger_links(static_cast<Finger>(f))[2])];
  out.push_back(phalanges / (hand::kLinkCount - 1));
  out.push_back(tips / hand::kFingerCount);
  const Eigen::Vector3d thumb_tip_side = midpoint(hand, Link::kThumbDistal);
  for (int f = 1; f < hand::kFingerCount; ++f)
    out.push_back(0.5 *
                  (thumb_tip_side + midpoint(hand, hand::finger_links(static_cast<Finger>(f))[1])));
  // the palm's face (it faces -z of the palm box) pushed out by the object's least half size
  const double half_m =
      shape.kind == ShapeKind::kBox ? 0.5 * shape.box_size_m.minCoeff() : shape.radius_m;
  out.push_back(hand.X_GP * Eigen::Vector3d(0.0, 0.0, -(0.5 * hand.palm_size_m.z() + half_m)));
  return out;
}

struct Start {
  Eigen::Vector3d p_G;
  RestOrientation rest;
  double yaw_rad;
  int rest_index;
};

// Two accepted results the same pose (FitResult::accepted): centres within 1 mm, turned less than
// 2 deg apart.
constexpr double kSamePosition_m = 1e-3;
constexpr double kSameTurn_deg = 2.0;
bool same_pose(const Placement& a, const Placement& b) {
  if ((a.X_GO.translation() - b.X_GO.translation()).norm() > kSamePosition_m) return false;
  const double turn_rad = Eigen::AngleAxisd(a.X_GO.linear().transpose() * b.X_GO.linear()).angle();
  return turn_rad <= kSameTurn_deg * M_PI / 180.0;
}

// Search coordinates: position in mm from the start's, then (a free yaw only) yaw in kYawUnit_rad.
Eigen::Isometry3d pose_from(const Start& start, const Eigen::VectorXd& x) {
  Eigen::Isometry3d X_GO = Eigen::Isometry3d::Identity();
  X_GO.translation() = start.p_G + kMm * x.head<3>();
  const double yaw_rad = start.yaw_rad + (start.rest.yaw_free ? kYawUnit_rad * x[3] : 0.0);
  X_GO.linear() = rest_rotation(start.rest, yaw_rad);
  return X_GO;
}

// Of two results, the better (grip_fit.hpp): an accepted one, more fingers gripping, more
// touching, one the hand does not pass through before the moment, cheaper; on a full tie the
// earlier (`a`) stays.
bool better(const Placement& b, const Placement& a, const FitLimits& limits) {
  if (b.accepted != a.accepted) return b.accepted;
  if (b.accepted) {
    if (b.gripping_fingers != a.gripping_fingers) return b.gripping_fingers > a.gripping_fingers;
    if (b.touching_fingers != a.touching_fingers) return b.touching_fingers > a.touching_fingers;
    const bool b_clear = b.approach_m >= -limits.max_depth_m;
    const bool a_clear = a.approach_m >= -limits.max_depth_m;
    if (b_clear != a_clear) return b_clear;
  }
  return b.cost < a.cost;
}

// Every start (grip_fit.hpp), in a fixed order: positions, then resting orientations, then yaws
// (or, where the yaw is not free, the position nudged kNudge_m along each of H's axes either way).
std::vector<Start> starts_for(const GripHand& hand, const Shape& shape) {
  std::vector<Start> out;
  const std::vector<RestOrientation> rests = rest_orientations(shape);
  for (const Eigen::Vector3d& p_G : start_positions(hand, shape)) {
    for (std::size_t r = 0; r < rests.size(); ++r) {
      const RestOrientation& rest = rests[r];
      const int index = static_cast<int>(r);
      const std::vector<double> yaws = start_yaws_rad(hand.X_GH.linear(), rest, kStartYaws);
      for (double yaw_rad : yaws)
        out.push_back({p_G, rest, yaw_rad, index});
      for (int k = 0; !rest.yaw_free && k < kStartYaws; ++k) {
        const Eigen::Vector3d axis_G = hand.X_GH.linear().col(k / 2);
        out.push_back({p_G + (k % 2 ? -kNudge_m : kNudge_m) * axis_G, rest, yaws.front(), index});
      }
    }
  }
  return out;
}

// Which resting orientation and yaw a search result has.
void label(Placement& p, const Start& start, const Eigen::VectorXd& x) {
  p.rest_index = start.rest_index;
  p.rest_name = start.rest.name;
  p.yaw_free = start.rest.yaw_free;
  const double yaw_rad = start.yaw_rad + (start.rest.yaw_free ? kYawUnit_rad * x[3] : 0.0);
  p.yaw_rad = std::remainder(yaw_rad, 2.0 * M_PI);
}

// One start's search; adds its cost evaluations to `evaluations`.
Placement search_from(const GripHand& hand, const Shape& shape, const FitLimits& limits,
                      const Start& start, int& evaluations) {
  // Continuation: the object grown from 60 % of its size to all of it, each stage starting where
  // the last stopped. A small object settles inside the grip; growing it pushes it to where the
  // whole fits, rather than jamming it among the fingers from the start.
  Eigen::VectorXd x = Eigen::VectorXd::Zero(start.rest.yaw_free ? 4 : 3);
  for (const Stage& stage : kStages) {
    const Shape sized = scaled(shape, stage.size_share);
    const auto cost = [&](const Eigen::VectorXd& y) {
      return evaluate_placement(hand, sized, pose_from(start, y), limits).cost;
    };
    const SimplexResult r = minimise_simplex(cost, x, {stage.evaluations, stage.step, 1e-3});
    evaluations += r.evaluations;
    x = r.x;
  }
  Placement p = evaluate_placement(hand, shape, pose_from(start, x), limits);
  label(p, start, x);
  if (p.accepted) return p;
  // too tight for the margins: polished once more near the limits (Margins)
  const auto tight = [&](const Eigen::VectorXd& y) {
    return placement_cost(evaluate_placement(hand, shape, pose_from(start, y), limits), limits,
                          kTight);
  };
  const SimplexResult r = minimise_simplex(tight, x, {kTightEvaluations, 0.5, 1e-3});
  evaluations += r.evaluations;
  Placement polished = evaluate_placement(hand, shape, pose_from(start, r.x), limits);
  label(polished, start, r.x);
  return polished.accepted ? polished : p;
}

// A bound must clear the nearest by this much to leave a link out (far above the rounding of
// either; the skipped link's exact distance is then surely not the least).
constexpr double kBoundMargin_m = 1e-9;

}  // namespace

Placement evaluate_placement(const GripHand& hand, const Shape& shape,
                             const Eigen::Isometry3d& X_GO, const FitLimits& limits) {
  Placement p;
  p.X_GO = X_GO;
  p.link_distance_m[0] = box_signed_distance(shape, X_GO, hand.palm_size_m, hand.X_GP);
  std::array<Eigen::Vector3d, hand::kLinkCount> n_G{};
  // Each finger's phalanges nearest first by a cheap lower bound; one whose bound lies beyond the
  // finger's nearest so far (and outside the object) cannot be its nearest nor the deepest, nor
  // add to the cost: its exact distance is left out and the bound stands for it.
  const ShapeCore core = shape_core(shape, X_GO);
  for (int f = 0; f < hand::kFingerCount; ++f) {
    const auto links = hand::finger_links(static_cast<Finger>(f));
    std::array<std::pair<double, std::size_t>, 3> order{};
    for (std::size_t i = 0; i < links.size(); ++i) {
      const auto k = static_cast<std::size_t>(links[i]);
      order[i] = {capsule_distance_lower_bound(core, hand.a_G[k], hand.b_G[k], hand.radius_m[k]),
                  k};
    }
    std::sort(order.begin(), order.end());
    double nearest_m = INFINITY;
    for (const auto& [bound_m, k] : order) {
      if (bound_m > kBoundMargin_m && bound_m > nearest_m + kBoundMargin_m) {
        p.link_distance_m[k] = bound_m;
        continue;
      }
      const LinkContact c =
          capsule_contact(shape, X_GO, hand.a_G[k], hand.b_G[k], hand.radius_m[k]);
      p.link_distance_m[k] = c.distance_m;
      n_G[k] = c.n_G;
      nearest_m = std::min(nearest_m, c.distance_m);
    }
  }
  for (int f = 0; f < hand::kFingerCount; ++f) {
    const auto fk = static_cast<std::size_t>(f);
    p.finger_distance_m[fk] = INFINITY;
    for (Link link : hand::finger_links(static_cast<Finger>(f))) {
      const double d_m = p.link_distance_m[static_cast<std::size_t>(link)];
      if (d_m < p.finger_distance_m[fk]) {
        p.finger_distance_m[fk] = d_m;
        p.finger_link[fk] = link;
      }
    }
    p.finger_normal_G[fk] = n_G[static_cast<std::size_t>(p.finger_link[fk])];
  }
  const double cos_opposed = std::cos(limits.opposition_deg * M_PI / 180.0);
  p.thumb_touches = p.finger_distance_m[0] <= limits.contact_m;
  for (int f = 0; f < hand::kFingerCount; ++f) {
    const auto fk = static_cast<std::size_t>(f);
    const double cos_angle = std::clamp(p.finger_normal_G[0].dot(p.finger_normal_G[fk]), -1.0, 1.0);
    p.finger_opposition_deg[fk] = f == 0 ? 0.0 : std::acos(cos_angle) * 180.0 / M_PI;
    if (p.finger_distance_m[fk] > limits.contact_m) continue;
    ++p.touching_fingers;
    if (f > 0 && cos_angle < cos_opposed) ++p.gripping_fingers;
  }
  const auto deepest = std::min_element(p.link_distance_m.begin(), p.link_distance_m.end());
  p.deepest_link = static_cast<Link>(deepest - p.link_distance_m.begin());
  p.deepest_m = -*deepest;
  p.accepted = p.thumb_touches && p.touching_fingers - 1 >= limits.other_fingers &&
               p.gripping_fingers >= limits.opposing_fingers && p.deepest_m <= limits.max_depth_m;
  p.cost = placement_cost(p, limits, kRoomy);
  return p;
}

FitResult fit_object_in_grip(const GripHand& hand, const Shape& shape, const FitLimits& limits,
                             const std::vector<RecordedHand>& before) {
  FitResult result;
  for (const Start& start : starts_for(hand, shape)) {
    Placement p = search_from(hand, shape, limits, start, result.evaluations);
    if (p.accepted && !before.empty())
      p.approach_m = hand_approach(before, shape, p.X_GO).nearest_m;
    if (result.starts == 0 || better(p, result.best, limits)) result.best = p;
    if (p.accepted) result.accepted.push_back(p);
    ++result.starts;
  }
  // best first (a stable sort: on a full tie the earlier start), then the same poses left out
  std::stable_sort(result.accepted.begin(), result.accepted.end(),
                   [&](const Placement& a, const Placement& b) { return better(a, b, limits); });
  std::vector<Placement> distinct;
  for (const Placement& p : result.accepted) {
    const bool seen = std::any_of(distinct.begin(), distinct.end(),
                                  [&](const Placement& q) { return same_pose(p, q); });
    if (!seen) distinct.push_back(p);
  }
  result.accepted = std::move(distinct);
  return result;
}

}  // namespace vcockpit::fit
