// grip_fit's moment (physics_node/fit/steady_moment.hpp): the flexion sum, and the steadiest
// closed sample of the first closed stretch on a made-up recording: open, closing, held (shaking,
// then nearly still), opening, closed again and perfectly still.

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "physics_node/fit/steady_moment.hpp"
#include "tests/unit/grip_fit_samples.hpp"

namespace vcockpit::fit {
namespace {

// Every 10 ms over 0..2 s: the fist's closure c(t) rises 0.1-0.4 s, holds until 1.0 s, falls by
// 1.2 s, rises 1.5-1.7 s and holds. During the first hold the wrist shakes along x: 5 mm at
// 20 Hz until 0.7 s, then 0.2 mm; the second hold is still. `dip_at_s`: one sample at closure
// `dip`.
std::vector<hand::GloveSample> recording(double dip_at_s = -1.0, double dip = 1.0) {
  std::vector<hand::GloveSample> out;
  for (int k = 0; k <= 200; ++k) {
    const double t = 0.01 * k;
    double c = 0.0;
    if (t >= 0.1 && t < 0.4)
      c = (t - 0.1) / 0.3;
    else if (t >= 0.4 && t <= 1.0)
      c = 1.0;
    else if (t > 1.0 && t < 1.2)
      c = 1.0 - (t - 1.0) / 0.2;
    else if (t >= 1.5 && t < 1.7)
      c = (t - 1.5) / 0.2;
    else if (t >= 1.7)
      c = 1.0;
    if (std::abs(t - dip_at_s) < 1e-9) c = dip;
    hand::GloveSample s = test::fist_sample(c, hand::log_seconds_to_ns(t));
    const double shake_m = t >= 0.4 && t < 0.7 ? 0.005 : t >= 0.7 && t <= 1.0 ? 0.0002 : 0.0;
    s.p_MT_m.x() += shake_m * std::sin(2.0 * M_PI * 20.0 * t);
    out.push_back(s);
  }
  return out;
}

double seconds(const Moment& m) {
  return hand::ns_to_log_seconds(m.t_ns);
}

TEST(GripFitMoment, FlexionIsTheSumOfTheFifteenFlexionChannels) {
  hand::JointAngles q{};
  q.fill(0.1);
  EXPECT_NEAR(hand_flexion_rad(q), 1.5, 1e-12);  // not the 4 spreads, palm arch or wrist
  q = test::fist_sample().joints_rad;
  EXPECT_NEAR(hand_flexion_rad(q), deg_to_rad(4 * (60 + 70 + 40) + 45 + 30 + 30), 1e-12);
}

TEST(GripFitMoment, TheStillestSampleOfTheFirstClosedStretch) {
  const hand::HandModel hand = test::grip_fit_hand();
  const auto samples = recording();
  const auto m = steadiest_closed_moment(hand, samples);
  ASSERT_TRUE(m);
  // in the first hold's near-still part (window +-50 ms inside it), not the second, stiller hold
  EXPECT_GE(seconds(*m), 0.75 - 1e-9);
  EXPECT_LE(seconds(*m), 0.95 + 1e-9);
  EXPECT_TRUE(m->window_whole);
  EXPECT_NEAR(m->closure_share, 1.0, 1e-12);
  // the still part moves 0.2 mm at most each way: under 4e-4 m / 0.1 m = 0.004 rad
  EXPECT_LT(m->motion, 0.0041);
  EXPECT_GT(m->motion, 0.0);
  EXPECT_DOUBLE_EQ(m->motion, sample_motion(hand, samples, m->index, {}));
  // the second hold is stiller (exactly still): only the first-stretch rule keeps it out
  EXPECT_EQ(sample_motion(hand, samples, 185, {}), 0.0);
}

TEST(GripFitMoment, TheStretchItsClosingItsOpeningAndTheMomentsToTry) {
  const hand::HandModel hand = test::grip_fit_hand();
  const auto samples = recording();
  const auto stretch = first_closed_stretch(hand, samples);
  ASSERT_TRUE(stretch);
  const auto t = [&](std::size_t i) { return hand::ns_to_log_seconds(samples[i].t_ns); };
  // closed (85 %) from 0.36 s (the closure rises 0.1-0.4 s) to 1.02 s (it falls 1.0-1.2 s);
  // below 75 % from 1.06 s
  EXPECT_NEAR(t(stretch->first), 0.36, 1e-9);
  EXPECT_NEAR(t(stretch->last_closed), 1.03, 1e-9);
  EXPECT_NEAR(t(stretch->end), 1.06, 1e-9);
  // the closing: the last sample within 5 % of the most open before (0.11 s: 3.3 %), no more
  // than 0.3 s before the stretch (0.06 s)
  EXPECT_NEAR(t(stretch->closing), 0.11, 1e-9);
  // opening: after the last sample within 5 % of the highest (1.01 s: 95 %, within rounding)
  EXPECT_GE(t(stretch->opening), 1.0 - 1e-9);
  EXPECT_LE(t(stretch->opening), 1.01 + 1e-9);
  // the moments end 0.5 s after the stretch's start
  EXPECT_NEAR(t(stretch->last_moment), 0.86, 1e-9);
  const std::vector<std::size_t> moments = moments_across(*stretch, samples, 0.03);
  ASSERT_FALSE(moments.empty());
  EXPECT_EQ(moments.front(), stretch->closing);
  for (std::size_t k = 1; k < moments.size(); ++k) {
    EXPECT_NEAR(t(moments[k]) - t(moments[k - 1]), 0.03, 1e-9) << k;
  }
  EXPECT_LE(moments.back(), stretch->last_moment);
  EXPECT_GT(t(moments.back()), 0.86 - 0.03);
  EXPECT_EQ(moments_across(*stretch, samples, 0.0).size(),
            stretch->last_moment - stretch->closing + 1);
  // a closing longer than closing_s starts that long before the stretch
  MomentRule short_closing;
  short_closing.closing_s = 0.1;
  EXPECT_NEAR(t(first_closed_stretch(hand, samples, short_closing)->closing), 0.26, 1e-9);
}

TEST(GripFitMoment, AShallowDipDoesNotEndTheStretchADeepOneDoes) {
  const hand::HandModel hand = test::grip_fit_hand();
  // to 80 %: below closed (85 %), above reopened (75 %): the stretch goes on
  const auto shallow = steadiest_closed_moment(hand, recording(0.5, 0.8));
  ASSERT_TRUE(shallow);
  EXPECT_GE(seconds(*shallow), 0.75 - 1e-9);
  // to 50 % at 0.6 s: the first stretch ends there, within the shaking
  const auto deep = steadiest_closed_moment(hand, recording(0.6, 0.5));
  ASSERT_TRUE(deep);
  EXPECT_GE(seconds(*deep), 0.35);
  EXPECT_LT(seconds(*deep), 0.6);
}

TEST(GripFitMoment, AConstantLogTakesItsFirstWholeWindowAndAForcedTimeTheNearestSample) {
  const hand::HandModel hand = test::grip_fit_hand();
  std::vector<hand::GloveSample> still;
  for (int k = 0; k <= 20; ++k)
    still.push_back(test::fist_sample(1.0, k * 10'000'000));
  const auto m = steadiest_closed_moment(hand, still);
  ASSERT_TRUE(m);
  EXPECT_EQ(m->index, 5u);  // t 0.05 s: the first whose +-50 ms lies within the log
  EXPECT_EQ(m->motion, 0.0);
  EXPECT_EQ(m->closure_share, 1.0);

  const auto samples = recording();
  const auto at = moment_at(hand, samples, hand::log_seconds_to_ns(0.504));
  ASSERT_TRUE(at);
  EXPECT_EQ(at->index, 50u);
  EXPECT_FALSE(steadiest_closed_moment(hand, {}));
}

}  // namespace
}  // namespace vcockpit::fit
