#pragma once
// How the physics node follows its hand samples in time, in every mode (offline, lockstep, real
// time): gaps up to `max_gap_ns` are bridged (the hand moves across them), longer ones are not
// (the hand holds its last sample), and after `glove_timeout_ns` without a sample the glove is
// lost (the hand stays, held objects are let go) until samples resume.

#include <cstdint>
#include <stdexcept>
#include <string>

#include "hand/sample_intervals.hpp"

namespace vcockpit::physics_io {

constexpr int64_t kDefaultGloveTimeout_ns = 1'000'000'000;

struct InputTiming {
  int64_t max_gap_ns = hand::kDefaultMaxGap_ns;  // 0: never interpolate (hold each sample)
  int64_t glove_timeout_ns = kDefaultGloveTimeout_ns;
};

// Throws std::invalid_argument naming the flag: a negative max gap, a timeout that is not
// positive, or a max gap longer than the timeout (a bridged gap cannot also lose the glove).
inline void check_input_timing(const InputTiming& t) {
  if (t.max_gap_ns < 0) throw std::invalid_argument("--max-gap must be 0 or positive");
  if (t.glove_timeout_ns <= 0) throw std::invalid_argument("--glove-timeout must be positive");
  if (t.max_gap_ns > t.glove_timeout_ns) {
    throw std::invalid_argument("--max-gap (" + std::to_string(t.max_gap_ns * 1e-9) +
                                " s) must not exceed --glove-timeout (" +
                                std::to_string(t.glove_timeout_ns * 1e-9) + " s)");
  }
}

}  // namespace vcockpit::physics_io
