#pragma once
// What happened to a stream of hand samples on its way to the hand, counted the same way by every
// node that handles one: the glove log reader (clamped values, missing columns), the sample
// validator (accepted, rejected, clamped), the glove driver (the intervals it publishes), and the
// physics node live and offline (the intervals it interpolates, holds or waits for, glove lost).
// The glove driver's and physics node's node_status carry these fields, and the offline
// summary.json their JSON form (input_counts_json), so a count means one thing everywhere.
//
// Intervals: the time between two consecutive accepted samples. Each is exactly one of
//   interpolated      the hand moved across it (a regular interval)
//   gap bridged       longer than twice the usual interval (IntervalTracker), within the max gap,
//                     and the hand moved across it
//   gap not bridged   longer than the max gap: the hand held the earlier sample, then took the
//                     later one in one step (and the glove was lost if it lasted past the timeout)
//   late              real time only: the later sample arrived after the hand had reached the
//                     earlier one; the hand waited there, then caught up in one step
// A node that does not move a hand (the glove driver) counts the interval kinds it sees against
// the same max gap: its "bridged" gaps are those a physics node with that max gap would bridge.

#include <cstdint>
#include <nlohmann/json_fwd.hpp>
#include <string>

namespace vcockpit::hand {

struct InputCounts {
  uint64_t accepted = 0;
  uint64_t rejected_nonfinite = 0;     // NaN/Inf anywhere
  uint64_t rejected_out_of_range = 0;  // quaternion far from unit length
  uint64_t rejected_stale = 0;         // time not after the previous accepted sample
  uint64_t clamped = 0;                // joint values moved into their limits (samples kept)
  uint64_t missing_columns = 0;        // joint channels the source lacks: the rest pose is used
  uint64_t intervals = 0;              // between consecutive accepted samples (the sum below)
  uint64_t intervals_interpolated = 0;
  uint64_t gaps_bridged = 0;
  uint64_t gaps_not_bridged = 0;
  uint64_t intervals_late = 0;
  int64_t longest_interval_ns = 0;
  uint64_t glove_lost = 0;  // times the glove was declared lost (no sample for the timeout)

  uint64_t rejected() const { return rejected_nonfinite + rejected_out_of_range + rejected_stale; }
  // Sums the counts (the longest interval: the longer one).
  InputCounts& operator+=(const InputCounts& other);
};

// One line for logs: "accepted 12, rejected 0 (...), clamped 3, missing columns 1, intervals 11
// (interpolated 9, gaps bridged 1, not bridged 1, late 0), longest 0.400 s, glove lost 0".
std::string input_counts_text(const InputCounts& counts);
nlohmann::ordered_json input_counts_json(const InputCounts& counts);

}  // namespace vcockpit::hand
