#pragma once
// Wrist tracker jitter: independent Gaussian noise on every reading, sigma_m on each position
// axis and sigma_rad on each component of a small rotation applied in the tracker's own frame.
// Magnetic and optical trackers of the kind used with data gloves jitter by about 0.5 mm and
// 0.2 deg at arm's length (static accuracy of the Polhemus Liberty: 0.76 mm RMS, 0.15 deg RMS).

#include <cstdint>
#include <vector>

#include "hand/glove_sample.hpp"

namespace vcockpit::degrade {

struct TrackerJitter {
  double sigma_m = 0.0;
  double sigma_rad = 0.0;
};

void add_tracker_jitter(std::vector<hand::GloveSample>& samples, const TrackerJitter& jitter,
                        uint64_t seed);

}  // namespace vcockpit::degrade
