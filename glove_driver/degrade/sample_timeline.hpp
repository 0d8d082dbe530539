#pragma once
// A glove log as a continuous signal: the reading at any time between two rows, position and
// joints linear, orientation by slerp. Resampling and time-warping read the input through it.

#include <cstdint>
#include <vector>

#include "hand/glove_sample.hpp"

namespace vcockpit::degrade {

// Samples sorted by strictly increasing t_ns, at least one. Times before the first row give the
// first row, after the last the last. The result carries t_ns.
hand::GloveSample sample_at_time(const std::vector<hand::GloveSample>& samples, int64_t t_ns);

// a + u (b - a), slerp for the orientation; t_ns from a.
hand::GloveSample blend(const hand::GloveSample& a, const hand::GloveSample& b, double u);

}  // namespace vcockpit::degrade
