// Intervals between samples (hand/sample_intervals.hpp) and the shared counts
// (hand/input_counts.hpp): the usual interval is the median of the recent ones, a gap is more than
// twice that, beyond the max gap is not bridged; every interval lands in exactly one count.

#include "hand/sample_intervals.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "hand/input_counts.hpp"

namespace vcockpit::hand {
namespace {

constexpr int64_t kMs = 1'000'000;

TEST(IntervalTracker, TheUsualIntervalIsTheMedianAndALoneDropDoesNotMoveIt) {
  IntervalTracker t;
  EXPECT_EQ(t.typical_ns(), 0);
  for (int64_t ms : {30, 31, 29, 30, 32, 30})
    t.add(ms * kMs, 250 * kMs);
  EXPECT_EQ(t.typical_ns(), 30 * kMs);
  EXPECT_EQ(t.add(61 * kMs, 250 * kMs), IntervalKind::kGap) << "just over twice the usual";
  EXPECT_EQ(t.typical_ns(), 30 * kMs) << "one gap among seven does not move the median";
  EXPECT_EQ(t.add(59 * kMs, 250 * kMs), IntervalKind::kRegular) << "just under twice";
}

TEST(IntervalTracker, NoGapBeforeThreeIntervalsAndBeyondTheMaxGapIsNotRemembered) {
  IntervalTracker t;
  EXPECT_EQ(t.add(1 * kMs, 250 * kMs), IntervalKind::kRegular);
  EXPECT_EQ(t.add(100 * kMs, 250 * kMs), IntervalKind::kRegular) << "too little history to judge";
  EXPECT_EQ(t.add(1 * kMs, 250 * kMs), IntervalKind::kRegular);
  EXPECT_EQ(t.add(251 * kMs, 250 * kMs), IntervalKind::kBeyondMaxGap);
  EXPECT_EQ(t.typical_ns(), 1 * kMs) << "the median of 1, 100, 1; the 251 ms gap is left out";
  EXPECT_EQ(t.add(250 * kMs, 250 * kMs), IntervalKind::kGap) << "the max gap itself is bridged";
}

TEST(IntervalTracker, FollowsAChangeOfRateWithinEightIntervals) {
  IntervalTracker t;
  for (int i = 0; i < 15; ++i)
    t.add(1 * kMs, 250 * kMs);
  int gaps = 0;
  for (int i = 0; i < 15; ++i)
    gaps += t.add(30 * kMs, 250 * kMs) == IntervalKind::kGap ? 1 : 0;
  EXPECT_EQ(gaps, 8) << "1 kHz -> 33 Hz: the first eight 30 ms intervals are gaps, then the usual";
  EXPECT_EQ(t.typical_ns(), 30 * kMs);
}

TEST(InputCounts, EveryIntervalLandsInExactlyOneCount) {
  InputCounts c;
  count_interval(c, IntervalKind::kRegular, 10 * kMs, true);
  count_interval(c, IntervalKind::kRegular, 10 * kMs, true, true);
  count_interval(c, IntervalKind::kGap, 100 * kMs, true);
  count_interval(c, IntervalKind::kBeyondMaxGap, 400 * kMs, true);
  count_interval(c, IntervalKind::kRegular, 10 * kMs, false);  // a node that moves no hand
  EXPECT_EQ(c.intervals, 5u);
  EXPECT_EQ(c.intervals_interpolated, 1u);
  EXPECT_EQ(c.intervals_late, 1u);
  EXPECT_EQ(c.gaps_bridged, 1u);
  EXPECT_EQ(c.gaps_not_bridged, 1u);
  EXPECT_EQ(c.longest_interval_ns, 400 * kMs);
}

TEST(InputCounts, SumsAddAndTheLongestIntervalIsTheLonger) {
  InputCounts a, b;
  a.clamped = 2;
  a.missing_columns = 1;
  a.longest_interval_ns = 5;
  a.rejected_stale = 1;
  b.clamped = 3;
  b.glove_lost = 1;
  b.longest_interval_ns = 3;
  b.rejected_nonfinite = 2;
  a += b;
  EXPECT_EQ(a.clamped, 5u);
  EXPECT_EQ(a.missing_columns, 1u);
  EXPECT_EQ(a.glove_lost, 1u);
  EXPECT_EQ(a.longest_interval_ns, 5);
  EXPECT_EQ(a.rejected(), 3u);
  const auto json = input_counts_json(a);
  EXPECT_EQ(json["clamped"], 5u);
  EXPECT_EQ(json["rejected"], 3u);
  EXPECT_NE(input_counts_text(a).find("clamped 5, missing columns 1"), std::string::npos)
      << input_counts_text(a);
}

}  // namespace
}  // namespace vcockpit::hand
