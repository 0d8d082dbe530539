// calibration error: each channel off by its own offset and gain, within the bounds asked for,
// so readings go past the calibrated range.

#include <gtest/gtest.h>

#include "glove_driver/degrade/calibration_error.hpp"
#include "tests/unit/degrade_samples.hpp"

namespace vcockpit::degrade {
namespace {

TEST(CalibrationError, EachChannelIsAffineWithinTheBounds) {
  const auto hand = test::default_hand();
  const auto clean = test::grip_log(hand);
  auto off = clean;
  const CalibrationError error{deg_to_rad(5.0), 0.10};
  apply_calibration_error(off, hand, error, 5);
  const auto channels = draw_channel_errors(error, 5);
  double min_offset = 1, max_offset = -1;
  for (int j = 0; j < hand::kJointCount; ++j) {
    EXPECT_LE(std::abs(channels[j].offset_rad), error.offset_rad);
    EXPECT_LE(std::abs(channels[j].gain - 1.0), error.gain);
    min_offset = std::min(min_offset, channels[j].offset_rad);
    max_offset = std::max(max_offset, channels[j].offset_rad);
    const double lo = hand.joints[j].min_rad;
    for (std::size_t i = 0; i < clean.size(); i += 97) {
      EXPECT_NEAR(off[i].joints_rad[j],
                  lo + channels[j].gain * (clean[i].joints_rad[j] - lo) + channels[j].offset_rad,
                  1e-12);
    }
  }
  // 22 uniform draws spread over most of +-5 deg
  EXPECT_LT(min_offset, -0.5 * error.offset_rad);
  EXPECT_GT(max_offset, 0.5 * error.offset_rad);
  EXPECT_EQ(off[100].p_MT_m, clean[100].p_MT_m);
}

TEST(CalibrationError, StraightFingersReadBelowTheirRange) {
  const auto hand = test::default_hand();
  auto open = test::grip_log(hand);  // starts open: index and middle at 0 = their minimum
  apply_calibration_error(open, hand, {deg_to_rad(5.0), 0.10}, 5);
  const auto channels = draw_channel_errors({deg_to_rad(5.0), 0.10}, 5);
  for (hand::Joint joint : {hand::Joint::kIndexMcp, hand::Joint::kIndexPip,
                            hand::Joint::kMiddleMcp, hand::Joint::kMiddlePip}) {
    const int j = static_cast<int>(joint);
    const bool below = open.front().joints_rad[j] < hand.joints[j].min_rad;
    EXPECT_EQ(below, channels[j].offset_rad < 0) << hand::joint_name(joint);
  }
}

}  // namespace
}  // namespace vcockpit::degrade
