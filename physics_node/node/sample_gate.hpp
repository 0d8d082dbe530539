#pragma once
// Incoming hand samples are checked before the world sees them: a sample the source flagged
// invalid, non-finite values, a wrist position beyond the tracker's range, a quaternion far from
// unit length, or a stamp not after the last accepted one (stale or out of order) is rejected and
// counted; joint angles beyond their limits are clamped and counted. The same checks the glove
// driver makes, so a replay reaches the physics exactly as it left the log.

#include "cockpit.h"
#include "hand/sample_validator.hpp"

namespace vcockpit::physics_node {

class SampleGate {
 public:
  static constexpr double kTrackerRange_m = 10.0;

  explicit SampleGate(const hand::HandModel& hand) : validator_(hand) {}

  // True and `out` filled when the sample is accepted.
  bool accept(const cockpit::HandSample& sample, hand::GloveSample& out);
  const hand::InputCounts& counts() const { return validator_.counts(); }
  // A new source: its stamps are compared with its own from now on.
  void reset_time() { validator_.reset_time(); }
  uint64_t rejected_flagged_or_far() const { return rejected_flagged_or_far_; }
  uint64_t rejected() const { return validator_.counts().rejected() + rejected_flagged_or_far_; }

 private:
  hand::SampleValidator validator_;
  uint64_t rejected_flagged_or_far_ = 0;
};

}  // namespace vcockpit::physics_node
