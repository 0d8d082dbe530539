#include "glove_driver/degrade/resample.hpp"

#include <cmath>

#include "common/assert.hpp"
#include "glove_driver/degrade/sample_timeline.hpp"

namespace vcockpit::degrade {

std::vector<hand::GloveSample> resample(const std::vector<hand::GloveSample>& samples,
                                        double rate_hz) {
  VCOCKPIT_ASSERT(rate_hz > 0 && !samples.empty(), "resample: positive rate, some samples");
  const int64_t t0_ns = samples.front().t_ns;
  const int64_t span_ns = samples.back().t_ns - t0_ns;
  std::vector<hand::GloveSample> out;
  // each stamp from k directly (no accumulated rounding): t0 + round(k 1e9 / rate)
  for (int64_t k = 0;; ++k) {
    const int64_t dt_ns = std::llround(static_cast<double>(k) * 1e9 / rate_hz);
    if (dt_ns > span_ns) break;
    out.push_back(sample_at_time(samples, t0_ns + dt_ns));
  }
  return out;
}

}  // namespace vcockpit::degrade
