// Faster grip closures: the closure is found, lasts what was asked, everything around it is
// unchanged, and a hand curling while it travels is no grip.

#include <gtest/gtest.h>

#include "glove_driver/degrade/grip_closure.hpp"
#include "tests/unit/degrade_samples.hpp"

namespace vcockpit::degrade {
namespace {

TEST(GripClosure, FindsTheClosureWithTheWristStillOnly) {
  const auto hand = test::default_hand();
  const auto log = test::grip_log(hand, 0.8);
  const auto closures = find_grip_closures(log, hand);
  ASSERT_EQ(closures.size(), 1u) << "the curl at 3.2-3.8 s moves the wrist 10 cm: no grip";
  // min-jerk over [1.0, 1.8] s: its first and last millisecond move by less than a nanometre
  EXPECT_NEAR(log[closures[0].first].t_ns, 1'000'000'000, 5'000'000);
  EXPECT_NEAR(log[closures[0].last].t_ns, 1'800'000'000, 5'000'000);
  EXPECT_GT(closures[0].closure_m, 0.03);
}

TEST(GripClosure, SpedUpToTheDurationAskedFor) {
  const auto hand = test::default_hand();
  const auto clean = test::grip_log(hand, 0.8);
  for (double target_s : {0.25, 0.3, 0.5}) {
    auto fast = clean;
    EXPECT_EQ(speed_up_grip_closures(fast, hand, target_s), 1);
    const auto closures = find_grip_closures(fast, hand);
    ASSERT_EQ(closures.size(), 1u);
    const double duration_s =
        static_cast<double>(fast[closures[0].last].t_ns - fast[closures[0].first].t_ns) * 1e-9;
    EXPECT_NEAR(duration_s, target_s, 0.01) << target_s;
    EXPECT_NEAR(fast[closures[0].first].t_ns, 1'000'000'000, 5'000'000);
    // it closes as far as before, and holds that grip to the old closure's end
    for (int j = 0; j < hand::kJointCount; ++j) {
      // (the closure found ends within a few ms of 1.8 s, where min-jerk has all but stopped)
      EXPECT_NEAR(fast[1800].joints_rad[j], clean[1800].joints_rad[j], 1e-6);
      EXPECT_NEAR(fast[1000 + static_cast<int>(target_s * 1000) + 10].joints_rad[j],
                  clean[1800].joints_rad[j], 1e-6);
    }
    // before and after the closure: bit for bit the same
    for (std::size_t i : {0u, 999u, 1801u, 2600u, 3500u, 4000u}) {
      EXPECT_EQ(fast[i].joints_rad, clean[i].joints_rad) << i;
      EXPECT_EQ(fast[i].p_MT_m, clean[i].p_MT_m) << i;
      EXPECT_EQ(fast[i].t_ns, clean[i].t_ns);
    }
  }
}

TEST(GripClosure, NeverSlowedDown) {
  const auto hand = test::default_hand();
  const auto clean = test::grip_log(hand, 0.2);
  auto same = clean;
  EXPECT_EQ(speed_up_grip_closures(same, hand, 0.25), 0);
  for (std::size_t i = 0; i < clean.size(); ++i) EXPECT_EQ(same[i].joints_rad, clean[i].joints_rad);
}

}  // namespace
}  // namespace vcockpit::degrade
