#pragma once
// Samples lost between the device and the log, the two ways it happens:
//   dropouts  single rows the device sent without valid data (written as all-`nan` rows, which
//             the log reader skips and counts, as the physics node's sample gate would): exactly
//             round(rate (n - 1)) of the rows after the first, chosen at random;
//   gaps      stretches of 0.1-0.7 s with no rows at all (a wireless glove out of range, a USB
//             hiccup): every row with t in [start, start + length) removed.
// The first and last rows always stay: the replay starts with a known hand and keeps its span.

#include <cstdint>
#include <vector>

#include "hand/glove_sample.hpp"

namespace vcockpit::degrade {

struct DegradedRow {
  hand::GloveSample sample;
  bool valid = true;  // false: a dropout row
};

struct Gaps {
  int count = 0;             // gaps at random places (when at_s is empty)
  double min_s = 0.1;        // each gap's length uniform in [min_s, max_s]
  double max_s = 0.7;
  std::vector<double> at_s;  // or gaps starting at these times (s after the first row)
};

struct PlacedGap {
  int64_t start_ns = 0;  // on the log's own timeline
  int64_t length_ns = 0;
};

// Throws DegradeError when the gaps do not fit strictly inside the log without overlapping.
std::vector<PlacedGap> cut_gaps(std::vector<hand::GloveSample>& samples, const Gaps& gaps,
                                uint64_t seed);

// rate in [0, 1).
std::vector<DegradedRow> mark_dropouts(const std::vector<hand::GloveSample>& samples, double rate,
                                       uint64_t seed);

}  // namespace vcockpit::degrade
