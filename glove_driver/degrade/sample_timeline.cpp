#include "glove_driver/degrade/sample_timeline.hpp"

#include <algorithm>

#include "common/assert.hpp"

namespace vcockpit::degrade {

hand::GloveSample blend(const hand::GloveSample& a, const hand::GloveSample& b, double u) {
  hand::GloveSample out = a;
  out.p_MT_m = a.p_MT_m + u * (b.p_MT_m - a.p_MT_m);
  out.q_MT = a.q_MT.slerp(u, b.q_MT).normalized();
  for (int j = 0; j < hand::kJointCount; ++j) {
    out.joints_rad[j] = a.joints_rad[j] + u * (b.joints_rad[j] - a.joints_rad[j]);
  }
  return out;
}

hand::GloveSample sample_at_time(const std::vector<hand::GloveSample>& samples, int64_t t_ns) {
  VCOCKPIT_ASSERT(!samples.empty(), "sample_at_time needs samples");
  auto next = std::upper_bound(samples.begin(), samples.end(), t_ns,
                               [](int64_t t, const hand::GloveSample& s) { return t < s.t_ns; });
  hand::GloveSample out;
  if (next == samples.begin()) {
    out = samples.front();
  } else if (next == samples.end()) {
    out = samples.back();
  } else {
    const hand::GloveSample& a = *(next - 1);
    const hand::GloveSample& b = *next;
    out = blend(a, b, static_cast<double>(t_ns - a.t_ns) / static_cast<double>(b.t_ns - a.t_ns));
  }
  out.t_ns = t_ns;
  return out;
}

}  // namespace vcockpit::degrade
