// joint noise and quantisation: the noise's sigma; every value on the grid of its range.

#include <gtest/gtest.h>

#include <set>

#include "glove_driver/degrade/joint_noise.hpp"
#include "tests/unit/degrade_samples.hpp"

namespace vcockpit::degrade {
namespace {

TEST(JointNoise, EveryChannelGetsItsSigma) {
  const auto hand = test::default_hand();
  const auto clean = test::smooth_log(hand, 10.0, 1000.0);
  auto noisy = clean;
  const double sigma_rad = deg_to_rad(0.5);
  add_joint_noise(noisy, sigma_rad, 3);
  const double n = static_cast<double>(clean.size());
  for (int j = 0; j < hand::kJointCount; ++j) {
    double sum = 0, sum2 = 0;
    for (std::size_t i = 0; i < clean.size(); ++i) {
      const double d = noisy[i].joints_rad[j] - clean[i].joints_rad[j];
      sum += d;
      sum2 += d * d;
    }
    const double mean = sum / n;
    const double sd = std::sqrt(sum2 / n - mean * mean);
    EXPECT_NEAR(sd, sigma_rad, 0.04 * sigma_rad) << hand::joint_name(static_cast<hand::Joint>(j));
    EXPECT_LT(std::abs(mean), 5 * sigma_rad / std::sqrt(n));
  }
  EXPECT_EQ(noisy[5].p_MT_m, clean[5].p_MT_m);
}

TEST(Quantize, EightBitsGive256LevelsOverTheCalibratedRange) {
  const auto hand = test::default_hand();
  auto sweep = test::smooth_log(hand, 2.0, 1000.0);
  // sweep every channel over its whole range
  for (std::size_t i = 0; i < sweep.size(); ++i) {
    const double u = static_cast<double>(i) / static_cast<double>(sweep.size() - 1);
    for (int j = 0; j < hand::kJointCount; ++j) {
      sweep[i].joints_rad[j] = hand.joints[j].min_rad + u * (hand.joints[j].max_rad - hand.joints[j].min_rad);
    }
  }
  auto q8 = sweep;
  quantize_joints(q8, hand, 8);
  for (int j = 0; j < hand::kJointCount; ++j) {
    const auto& range = hand.joints[j];
    const double step = (range.max_rad - range.min_rad) / 255.0;
    std::set<double> levels;
    for (std::size_t i = 0; i < sweep.size(); ++i) {
      const double v = q8[i].joints_rad[j];
      levels.insert(v);
      const double k = (v - range.min_rad) / step;
      EXPECT_NEAR(k, std::round(k), 1e-9);
      EXPECT_LE(std::abs(v - sweep[i].joints_rad[j]), 0.5 * step + 1e-12);
    }
    EXPECT_EQ(levels.size(), 256u) << hand::joint_name(static_cast<hand::Joint>(j));
  }
}

TEST(Quantize, ValuesPastTheRangeStayPastItOnTheGrid) {
  const auto hand = test::default_hand();
  auto s = test::smooth_log(hand, 0.0, 1000.0);
  const int j = static_cast<int>(hand::Joint::kIndexMcp);
  const auto& range = hand.joints[j];
  const double step = (range.max_rad - range.min_rad) / 255.0;
  s[0].joints_rad[j] = range.max_rad + 3.2 * step;
  quantize_joints(s, hand, 8);
  EXPECT_NEAR(s[0].joints_rad[j], range.max_rad + 3 * step, 1e-12);
}

}  // namespace
}  // namespace vcockpit::degrade
