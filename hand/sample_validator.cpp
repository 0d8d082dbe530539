#include "hand/sample_validator.hpp"

#include <cmath>

namespace vcockpit::hand {
namespace {

bool all_finite(const GloveSample& s) {
  if (!s.p_MT_m.allFinite() || !s.q_MT.coeffs().allFinite()) return false;
  for (double q : s.joints_rad) {
    if (!std::isfinite(q)) return false;
  }
  return true;
}

}  // namespace

bool SampleValidator::accept(GloveSample& sample) {
  if (!all_finite(sample)) {
    ++counts_.rejected_nonfinite;
    return false;
  }
  if (std::abs(sample.q_MT.norm() - 1.0) > 1e-3) {
    ++counts_.rejected_out_of_range;
    return false;
  }
  if (have_last_ && sample.t_ns <= last_t_ns_) {
    ++counts_.rejected_stale;
    return false;
  }
  hand::JointAngles clamped = sample.joints_rad;
  const int clamped_values = hand::clamp_to_limits(hand_, clamped);
  if (clamped_values > 0) {
    sample.joints_rad = clamped;
    counts_.clamped += static_cast<uint64_t>(clamped_values);
  }
  last_t_ns_ = sample.t_ns;
  have_last_ = true;
  ++counts_.accepted;
  return true;
}

}  // namespace vcockpit::hand
