#pragma once
// Real time: which hand to show now, from samples arriving at 30-1000 Hz with jitter.
//
// The choice: a small, rate-adaptive interpolation delay (what networked games call entity
// interpolation). The hand shown at local time `now` is the source's hand at
//     t* = now - offset - delay
// on the source's timeline, interpolated between the two received samples around t* exactly as
// offline (sample_interpolation.hpp). `offset` maps the source's timeline to the local clock: the
// smallest (arrival - sample time) seen, creeping up by 1 ms per second so that it follows a
// path that got slower; a sample therefore arrives at t + offset or a little later. `delay`
// waits for the next sample: the usual interval (IntervalTracker's median) plus a margin for
// arrival jitter, so the hand always has a sample ahead of it. It changes by at most 10 % of the
// time that passes (the shown motion runs at 0.9x-1.1x while it adapts, never jumps).
//
// Why not extrapolate (e.g. the 1-euro filter, Casiez et al., CHI 2012): a filter trades jitter
// for a lag that depends on speed, and extrapolation overshoots every stop and reversal (a grasp
// is all stops). Interpolation is exact for a constant velocity (the lag is exactly the delay),
// never leaves the recorded motion, and treats every rate alike; the price is the delay:
// about one sample interval plus the margin (33 Hz: ~32 ms, 1 kHz: ~3 ms).
//
// A gap longer than the max gap is not bridged: the hand holds the earlier sample until t*
// reaches the later one. A gap the delay does not cover cannot be bridged in real time either:
// the hand reaches the earlier sample before the later one has arrived, waits there, and catches
// up in one step when it comes; such an interval is counted late. --input-delay 0 shows the
// newest sample at once (no interpolation: the behaviour before this follower existed).
//
// Pure (no clock, no DDS): the caller passes the local times. No allocation after construction.

#include <cstdint>
#include <optional>
#include <vector>

#include "hand/glove_sample.hpp"
#include "hand/input_counts.hpp"
#include "hand/sample_intervals.hpp"

namespace vcockpit::physics_io {

struct FollowerOptions {
  int64_t max_gap_ns = hand::kDefaultMaxGap_ns;
  std::optional<int64_t> fixed_delay_ns;  // none: adaptive (usual interval + margin)
  int64_t margin_ns = 2'000'000;          // arrival jitter + one 1 ms step of slot phase
};

struct FollowedInput {
  hand::GloveSample sample;     // t_ns: the source time shown
  int64_t source_stamp_ns = 0;  // the source stamp at that time (interpolated like the sample)
};

class InputFollower {
 public:
  static constexpr int kCapacity = 1024;  // samples kept: a quarter second at 4 kHz
  static constexpr int64_t kOffsetCreepPerSecond_ns = 1'000'000;

  explicit InputFollower(const FollowerOptions& options);

  // An accepted sample (newer than the last), the local time it arrived and its source stamp.
  void push(const hand::GloveSample& sample, int64_t arrival_ns, int64_t source_stamp_ns);
  // The hand to show at local time now_ns (non-decreasing from call to call). False before the
  // first sample.
  bool at(int64_t now_ns, FollowedInput& out);
  // A new source: forget its predecessor's samples and timeline.
  void reset();

  int64_t delay_ns() const { return delay_ns_; }
  int64_t offset_ns() const { return offset_ns_; }
  // intervals interpolated, gaps bridged and not, late (glove lost is the caller's: wall clock)
  const hand::InputCounts& counts() const { return counts_; }

 private:
  struct Entry {
    hand::GloveSample sample;
    int64_t arrival_ns = 0;
    int64_t source_stamp_ns = 0;
    bool bridged_from_previous = false;  // the interval ending here is interpolated
  };
  const Entry& entry(int i) const {
    return ring_[static_cast<std::size_t>((head_ + i) % kCapacity)];
  }
  int64_t target_delay_ns() const;
  int64_t shown_time_ns(int64_t now_ns) const { return now_ns - offset_ns_ - delay_ns_; }

  FollowerOptions options_;
  std::vector<Entry> ring_;
  int head_ = 0;
  int size_ = 0;
  int64_t offset_ns_ = 0;
  int64_t last_arrival_ns_ = 0;
  int64_t delay_ns_ = 0;
  int64_t last_at_ns_ = 0;
  bool have_at_ = false;
  int64_t reached_t_ns_ = 0;  // the latest source time shown so far
  hand::IntervalTracker intervals_;
  hand::InputCounts counts_;
};

}  // namespace vcockpit::physics_io
