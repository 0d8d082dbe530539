#pragma once
// Readings past the calibrated range: the glove calibrated for another hand, or a calibration
// that has drifted. Each channel gets its own offset (uniform in +-offset_rad) and gain error
// (uniform in 1 +- gain) about the bottom of its range:
//   q' = min + gain_j (q - min) + offset_j
// so a straight finger reads a few degrees below its range and a tight fist past its top —
// values the log reader clamps and counts.

#include <array>
#include <cstdint>
#include <vector>

#include "hand/glove_sample.hpp"
#include "hand/hand_model.hpp"

namespace vcockpit::degrade {

struct CalibrationError {
  double offset_rad = 0.0;
  double gain = 0.0;
};

struct ChannelError {
  double offset_rad = 0.0;
  double gain = 1.0;
};

// The per-channel errors drawn for a seed (what apply_calibration_error applies).
std::array<ChannelError, hand::kJointCount> draw_channel_errors(const CalibrationError& error,
                                                                uint64_t seed);

void apply_calibration_error(std::vector<hand::GloveSample>& samples, const hand::HandModel& hand,
                             const CalibrationError& error, uint64_t seed);

}  // namespace vcockpit::degrade
