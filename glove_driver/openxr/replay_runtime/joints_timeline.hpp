#pragma once
// A hand-joints log served as a live tracker serves its hands: at any moment, each hand's newest
// frame, with the log's time running at `rate` from the session's start, looping or ending. What
// the replay runtime (replay_runtime.cpp) answers xrLocateHandJointsEXT with; pure, no OpenXR.

#include <array>
#include <cstdint>
#include <vector>

#include "hand/tracking/joints_log.hpp"

namespace vcockpit::glove::xr_replay {

class JointsTimeline {
 public:
  // A hand whose newest frame is older than this is lost (a gap in the recording).
  static constexpr int64_t kHandLost_ns = 100'000'000;

  // `frames`: a log's frames in file order (each hand's times increasing). `rate`: log seconds
  // per second (above 0). Throws std::invalid_argument when there is no frame.
  JointsTimeline(const std::vector<hand::tracking::JointsFrame>& frames, double rate, bool loop);

  // The log's time `elapsed_ns` after the start (looping: wrapped onto the log).
  int64_t log_time_ns(int64_t elapsed_ns) const;
  // Not looping, and past the last frame.
  bool ended(int64_t elapsed_ns) const;
  // This hand's newest frame at the elapsed time, or nullptr: before its first frame, in a gap
  // longer than kHandLost_ns, or after the end. A joint the tracker lost keeps `valid` false
  // and carries where it was last seen (the palm's place until it has been seen at all), as a
  // runtime reports an untracked joint's estimate.
  const hand::tracking::JointsFrame* at(bool left_hand, int64_t elapsed_ns) const;

  int64_t first_ns() const { return first_ns_; }
  int64_t period_ns() const { return period_ns_; }

 private:
  std::array<std::vector<hand::tracking::JointsFrame>, 2> hands_;  // right, left; lost filled in
  int64_t first_ns_ = 0;
  int64_t last_ns_ = 0;
  int64_t period_ns_ = 0;  // one pass of the log, with one frame interval to wrap around
  double rate_ = 1.0;
  bool loop_ = false;
};

}  // namespace vcockpit::glove::xr_replay
