#include "glove_driver/degrade/calibration_error.hpp"

#include "glove_driver/degrade/seeded_random.hpp"

namespace vcockpit::degrade {

std::array<ChannelError, hand::kJointCount> draw_channel_errors(const CalibrationError& error,
                                                                uint64_t seed) {
  SeededRandom random(seed, "calibration_error");
  std::array<ChannelError, hand::kJointCount> out{};
  for (ChannelError& c : out) {
    c.offset_rad = random.uniform(-error.offset_rad, error.offset_rad);
    c.gain = random.uniform(1.0 - error.gain, 1.0 + error.gain);
  }
  return out;
}

void apply_calibration_error(std::vector<hand::GloveSample>& samples, const hand::HandModel& hand,
                             const CalibrationError& error, uint64_t seed) {
  const auto channels = draw_channel_errors(error, seed);
  for (hand::GloveSample& s : samples) {
    for (int j = 0; j < hand::kJointCount; ++j) {
      const double min_rad = hand.joints[j].min_rad;
      s.joints_rad[j] = min_rad + channels[j].gain * (s.joints_rad[j] - min_rad) +
                        channels[j].offset_rad;
    }
  }
}

}  // namespace vcockpit::degrade
