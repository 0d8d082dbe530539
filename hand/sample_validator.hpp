#pragma once
// The checks every sample passes before it is published: finite numbers, a unit quaternion,
// time moving forward, joint angles inside their limits (clamped and counted when not).
// Rejected samples are never published; the counters go to cockpit/node_status.

#include <cstdint>

#include "hand/glove_sample.hpp"
#include "hand/hand_model.hpp"

namespace vcockpit::hand {

struct ValidationCounts {
  uint64_t accepted = 0;
  uint64_t rejected_nonfinite = 0;     // NaN/Inf anywhere
  uint64_t rejected_out_of_range = 0;  // quaternion far from unit length
  uint64_t rejected_stale = 0;         // time not after the previous accepted sample
  uint64_t clamped = 0;                // accepted with joints clamped into their limits
  uint64_t rejected() const { return rejected_nonfinite + rejected_out_of_range + rejected_stale; }
};

class SampleValidator {
 public:
  explicit SampleValidator(const hand::HandModel& hand) : hand_(hand) {}

  // True if the sample may be published (its joints possibly clamped in place).
  bool accept(GloveSample& sample);
  const ValidationCounts& counts() const { return counts_; }
  // Forget the last stamp (a looping replay starts a new timeline).
  void reset_time() { have_last_ = false; }

 private:
  const hand::HandModel& hand_;
  ValidationCounts counts_;
  int64_t last_t_ns_ = 0;
  bool have_last_ = false;
};

}  // namespace vcockpit::hand
