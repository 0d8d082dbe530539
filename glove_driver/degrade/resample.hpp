#pragma once
// A device with another sample rate: the recorded motion read at t0 + k / rate_hz (t0 the first
// row, up to the last row), as a slower or faster glove and tracker would have sampled it.

#include <vector>

#include "hand/glove_sample.hpp"

namespace vcockpit::degrade {

// rate_hz > 0; input sorted by time, at least one row.
std::vector<hand::GloveSample> resample(const std::vector<hand::GloveSample>& samples,
                                        double rate_hz);

}  // namespace vcockpit::degrade
