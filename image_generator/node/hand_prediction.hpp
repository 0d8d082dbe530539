#pragma once
// Where a hand will be when its frame is shown (OpenXR renders for a predicted display time):
// each link extrapolated from the hand's last two states, its position at its linear velocity and
// its orientation at its angular velocity, over the horizon from the glove's moment the newest
// state shows (its source_stamp_ns) to the display time. The velocity is over the states' source
// times; with no usable pair (the first state, a repeat, a gap over kMaxPairGap) nothing is
// extrapolated, and never further than kMaxHorizon.

#include <Eigen/Geometry>

#include <array>
#include <cstdint>

#include "dds/dds_participant.hpp"

namespace vcockpit::image_generator {

using LinkPoses = std::array<Eigen::Isometry3d, 16>;

class HandPredictor {
 public:
  static constexpr int64_t kMaxHorizon_ns = 50'000'000;
  static constexpr int64_t kMaxPairGap_ns = 100'000'000;

  // A new state of the hand (a state with the same source time as the newest is ignored).
  void on_state(const cockpit::HandState& state);
  // The drawn (proxy) or tracked links at display_ns (monotonic), into out; false (and out the
  // newest state's links) when there is nothing to extrapolate from.
  bool predict(int64_t display_ns, bool tracked, LinkPoses& out) const;
  // display_ns - the newest state's source stamp, clamped to [0, kMaxHorizon] (0: no state).
  int64_t horizon_ns(int64_t display_ns) const;

 private:
  bool have_newest_ = false;
  bool have_previous_ = false;
  cockpit::HandState newest_;
  cockpit::HandState previous_;
};

// `now` moved on from `previous` (dt_s before it) for another h_s at the same velocities.
Eigen::Isometry3d extrapolate_pose(const Eigen::Isometry3d& previous, const Eigen::Isometry3d& now,
                                   double dt_s, double h_s);

}  // namespace vcockpit::image_generator
