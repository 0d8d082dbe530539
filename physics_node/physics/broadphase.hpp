#pragma once
// Broadphase: the body pairs whose axis-aligned boxes overlap and that can act on each other, by
// sweep and prune along one axis (Baraff's, as in Bullet's and PhysX's SAP) over the moving
// bodies, and a sweep of the moving bodies across the static ones (which never pair with each
// other). Both lists keep their sorted order from step to step, so re-sorting after a small
// motion is an insertion sort of a nearly sorted list: O(n) plus the few swaps.
//
// Pairs that cannot act are never reported: static-static, asleep-static, asleep-asleep (a
// sleeping body moves for nothing but a moving one), hand-hand (a hand's own links, and
// two hands' links), a hand while it is disabled, and hand-static unless asked for (the proxy hand needs them to stay out of panels;
// no force acts on such a pair). The output is sorted by (lo, hi), whatever the sweep order.

#include <Eigen/Geometry>

#include <cstdint>
#include <vector>

#include "physics_node/physics/scene.hpp"

namespace vcockpit::physics {

struct Aabb {
  Eigen::Vector3d lo = Eigen::Vector3d::Zero();
  Eigen::Vector3d hi = Eigen::Vector3d::Zero();

  bool overlaps(const Aabb& o) const {
    return lo.x() <= o.hi.x() && o.lo.x() <= hi.x() && lo.y() <= o.hi.y() && o.lo.y() <= hi.y() &&
           lo.z() <= o.hi.z() && o.lo.z() <= hi.z();
  }
};

// The tight box of a shape (centred on its frame, axis along z) posed at X_GS.
Aabb shape_aabb(const Shape& shape, const Eigen::Isometry3d& X_GS);

// kControl: a control's moving part, dynamic but held by its joint, so never in contact with a
// static object (it sits in a panel's cut-out) or another control; the hand and free objects
// push it.
enum class BroadphaseBody : uint8_t { kStatic, kDynamic, kHand, kControl };

struct BodyPair {
  int lo = -1;
  int hi = -1;
  friend bool operator<(const BodyPair& x, const BodyPair& y) {
    return x.lo != y.lo ? x.lo < y.lo : x.hi < y.hi;
  }
  friend bool operator==(const BodyPair& x, const BodyPair& y) {
    return x.lo == y.lo && x.hi == y.hi;
  }
};

class SweepAndPrune {
 public:
  // One entry per body, in body order. Every box starts empty at the origin.
  explicit SweepAndPrune(std::vector<BroadphaseBody> kinds);

  void set_box(int body, const Aabb& box) { boxes_[static_cast<std::size_t>(body)] = box; }
  const Aabb& box(int body) const { return boxes_[static_cast<std::size_t>(body)]; }
  // A hand link takes part only while enabled (its hand is active); hand links start disabled,
  // every other body enabled.
  void set_enabled(int body, bool enabled) { enabled_[static_cast<std::size_t>(body)] = enabled ? 1 : 0; }
  void set_report_hand_static(bool report) { report_hand_static_ = report; }
  // A sleeping dynamic body (sleep.hpp) pairs only with bodies that move; every body starts awake.
  void set_asleep(int body, bool asleep) { asleep_[static_cast<std::size_t>(body)] = asleep ? 1 : 0; }

  // The overlapping pairs that can act, into `out` (cleared first). No allocation once `out`
  // has grown to the largest pair count.
  void find_pairs(std::vector<BodyPair>& out);

 private:
  bool can_act(int a, int b) const;
  // Insertion sort by the lower end of the box on the sweep axis: stable, and O(n) for a list
  // sorted the last time (the boxes moved little since).
  void sort_by_lower_end(std::vector<int>& bodies) const;
  // The pairs of a body of `firsts` and one of `seconds` (each sorted by the lower end of its box)
  // whose second starts within the first's span on the sweep axis, at or after its start
  // (after_ties: strictly after). all_act: every such pair can act (not asked again).
  void sweep_across(const std::vector<int>& firsts, const std::vector<int>& seconds, bool after_ties,
                    bool all_act, std::vector<BodyPair>& out) const;

  std::vector<BroadphaseBody> kinds_;
  std::vector<Aabb> boxes_;
  std::vector<int> order_;    // the moving bodies by the lower end of their box on the sweep axis
  std::vector<int> statics_;  // the static bodies, by the lower end of their box (find_pairs)
  std::vector<int> awake_;     // order_'s enabled bodies, awake and asleep (find_pairs)
  std::vector<int> sleeping_;
  std::vector<int> static_movers_;  // awake_'s bodies that act with static ones
  std::vector<uint8_t> enabled_;  // per body
  std::vector<uint8_t> asleep_;   // per body
  int axis_ = -1;           // chosen on the first sweep: where the boxes are spread the most
  bool report_hand_static_ = false;
};

}  // namespace vcockpit::physics
