// resample: exact stamps at the new rate, the motion read between rows.

#include <gtest/gtest.h>

#include "glove_driver/degrade/resample.hpp"
#include "tests/unit/degrade_samples.hpp"

namespace vcockpit::degrade {
namespace {

TEST(Resample, StampsAreExactlyTheNewRate) {
  const auto hand = test::default_hand();
  const auto clean = test::smooth_log(hand, 2.0, 1000.0);
  for (double rate_hz : {30.0, 60.0, 100.0, 120.0}) {
    const auto out = resample(clean, rate_hz);
    ASSERT_EQ(out.size(), static_cast<std::size_t>(2.0 * rate_hz) + 1) << rate_hz;
    for (std::size_t k = 0; k < out.size(); ++k) {
      EXPECT_EQ(out[k].t_ns, std::llround(static_cast<double>(k) * 1e9 / rate_hz)) << rate_hz;
    }
  }
}

TEST(Resample, ReadsTheMotionBetweenRows) {
  const auto hand = test::default_hand();
  const auto clean = test::smooth_log(hand, 1.0, 1000.0);
  const auto out = resample(clean, 30.0);
  for (const auto& s : out) {
    const double t = static_cast<double>(s.t_ns) * 1e-9;
    // the wrist moves on a line and turns at a constant rate: linear and slerp are exact
    EXPECT_TRUE(s.p_MT_m.isApprox(Eigen::Vector3d(0.3 + 0.05 * t, -0.3 - 0.02 * t, 0.9 + 0.01 * t),
                                  1e-12));
    const Eigen::Quaterniond expected(
        Eigen::AngleAxisd(0.3 * t, Eigen::Vector3d(1, 2, 3).normalized()));
    EXPECT_LT(s.q_MT.angularDistance(expected), 1e-9);
    EXPECT_EQ(s.joints_rad, clean.front().joints_rad);
  }
}

TEST(Resample, IrregularInputKeepsItsSpan) {
  const auto hand = test::default_hand();
  auto clean = test::smooth_log(hand, 1.0, 1000.0);
  clean.erase(clean.begin() + 100, clean.begin() + 400);  // a hole: read across it
  const auto out = resample(clean, 60.0);
  EXPECT_EQ(out.size(), 61u);
  EXPECT_EQ(out.back().t_ns, 1'000'000'000);
}

}  // namespace
}  // namespace vcockpit::degrade
