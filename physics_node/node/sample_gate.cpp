#include "physics_node/node/sample_gate.hpp"

#include "idl/topics/hand_sample_convert.hpp"

namespace vcockpit::physics_node {

bool SampleGate::accept(const cockpit::HandSample& sample, hand::GloveSample& out) {
  out = from_hand_sample(sample);
  // NaN fails this comparison too, but is left to the validator so it is counted as non-finite
  if (!sample.valid() || out.p_MT_m.norm() > kTrackerRange_m) {
    if (out.p_MT_m.allFinite()) {
      ++rejected_flagged_or_far_;
      return false;
    }
  }
  return validator_.accept(out);
}

}  // namespace vcockpit::physics_node
