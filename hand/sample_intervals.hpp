#pragma once
// The time between consecutive hand samples, classified the same way by the glove driver and the
// physics node: regular, a gap (more than twice the usual interval) the hand is moved across, or
// longer than the max gap (the hand holds the earlier sample; the gap is not bridged).
//
// "Usual" is the median of the last 15 intervals within the max gap, so it follows a source at
// any rate from 30 Hz to 1 kHz, a rate that wanders (a Leap's), and a change of rate after about
// eight intervals, while a lone dropped sample does not move it.

#include <array>
#include <cstdint>

#include "hand/input_counts.hpp"

namespace vcockpit::hand {

// Longer intervals than this are not bridged by default: real recordings have gaps up to 0.66 s,
// and moving a hand in a straight line across a quarter of a second of missing motion is already
// a guess (a hand moves 10-50 cm in that time).
constexpr int64_t kDefaultMaxGap_ns = 250'000'000;

enum class IntervalKind { kRegular, kGap, kBeyondMaxGap };

class IntervalTracker {
 public:
  static constexpr int kWindow = 15;
  static constexpr int kMinHistory = 3;  // fewer known intervals: nothing counts as a gap yet

  // Classifies the interval, then remembers it (unless beyond the max gap).
  IntervalKind add(int64_t interval_ns, int64_t max_gap_ns);
  // The median of the remembered intervals; 0 before the first.
  int64_t typical_ns() const;
  void reset() {
    size_ = 0;
    next_ = 0;
  }

 private:
  std::array<int64_t, kWindow> window_{};
  int size_ = 0;
  int next_ = 0;
};

// Adds one interval to `counts`: `moved` says whether the counting node moves a hand across the
// intervals it bridges (the physics node) or only looks at them (the glove driver); `late` that
// the real-time hand reached the earlier sample before the later one arrived.
void count_interval(InputCounts& counts, IntervalKind kind, int64_t interval_ns, bool moved,
                    bool late = false);

}  // namespace vcockpit::hand
