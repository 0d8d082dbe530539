#pragma once
// The checks every sample passes before it is published: finite numbers, a unit quaternion,
// time moving forward, joint angles inside their limits (clamped and counted when not).
// Rejected samples are never published; the counters (InputCounts: accepted, rejected by cause,
// clamped joint values) go to cockpit/node_status.

#include <cstdint>

#include "hand/glove_sample.hpp"
#include "hand/hand_model.hpp"
#include "hand/input_counts.hpp"

namespace vcockpit::hand {

class SampleValidator {
 public:
  explicit SampleValidator(const hand::HandModel& hand) : hand_(hand) {}

  // True if the sample may be published (its joints possibly clamped in place).
  bool accept(GloveSample& sample);
  const InputCounts& counts() const { return counts_; }
  // Forget the last stamp (a looping replay starts a new timeline).
  void reset_time() { have_last_ = false; }

 private:
  const hand::HandModel& hand_;
  InputCounts counts_;
  int64_t last_t_ns_ = 0;
  bool have_last_ = false;
};

}  // namespace vcockpit::hand
