// ReplayCursor: relative timing, rate, start offset, looping, restarting.

#include <gtest/gtest.h>

#include <cmath>

#include "glove_driver/glove/replay_cursor.hpp"

namespace vcockpit::glove {
namespace {

std::vector<hand::GloveSample> samples_every_10ms(int n, int64_t t0_ns = 5'000'000'000) {
  std::vector<hand::GloveSample> out(n);
  for (int i = 0; i < n; ++i) out[i].t_ns = t0_ns + 10'000'000LL * i;
  return out;
}

TEST(ReplayCursor, KeepsRelativeTimingScaledByRate) {
  const auto samples = samples_every_10ms(5);
  ReplayCursor cursor(samples, {/*rate=*/2.0, /*loop=*/false, /*start_offset_s=*/0.0});
  hand::GloveSample s;
  int64_t due = -1;
  std::vector<int64_t> dues, times;
  while (cursor.next(s, due)) {
    dues.push_back(due);
    times.push_back(s.t_ns);
  }
  EXPECT_EQ(dues, (std::vector<int64_t>{0, 5'000'000, 10'000'000, 15'000'000, 20'000'000}));
  EXPECT_EQ(times.front(), samples.front().t_ns);  // source stamps are the log's own
}

TEST(ReplayCursor, StartOffsetSkipsTheBeginning) {
  const auto samples = samples_every_10ms(10);
  ReplayCursor cursor(samples, {1.0, false, 0.035});
  hand::GloveSample s;
  int64_t due = -1;
  ASSERT_TRUE(cursor.next(s, due));
  EXPECT_EQ(s.t_ns, samples[4].t_ns);
  EXPECT_EQ(due, 0);
  EXPECT_THROW(ReplayCursor(samples, {1.0, false, 10.0}), std::invalid_argument);
  EXPECT_THROW(ReplayCursor(samples, {-1.0, false, 0.0}), std::invalid_argument);
}

TEST(ReplayCursor, LoopingKeepsTimeIncreasingWithTheSameSpacing) {
  const auto samples = samples_every_10ms(3);
  ReplayCursor cursor(samples, {0.0, true, 0.0});
  hand::GloveSample s;
  int64_t due = -1;
  std::vector<int64_t> times;
  for (int i = 0; i < 7 && cursor.next(s, due); ++i) times.push_back(s.t_ns - samples[0].t_ns);
  EXPECT_EQ(times, (std::vector<int64_t>{0, 10'000'000, 20'000'000, 30'000'000, 40'000'000,
                                         50'000'000, 60'000'000}));
  EXPECT_EQ(due, 0);  // rate 0: nothing waits
}

TEST(ReplayCursor, RestartStartsTheLogOverWithTimeGoingOn) {
  auto samples = samples_every_10ms(10);
  for (int i = 0; i < 10; ++i) samples[i].p_MT_m.x() = i;  // which sample it is
  ReplayCursor cursor(samples, {1.0, false, 0.0});
  hand::GloveSample s;
  int64_t due = -1;
  cursor.restart();  // before any sample: nothing changes
  for (int i = 0; i < 4; ++i) ASSERT_TRUE(cursor.next(s, due));
  EXPECT_EQ(due, 30'000'000);
  cursor.restart();
  ASSERT_TRUE(cursor.next(s, due));
  EXPECT_EQ(s.p_MT_m.x(), 0.0) << "the log's first sample again";
  EXPECT_EQ(s.t_ns, samples[0].t_ns + 40'000'000) << "one interval after the last one given";
  EXPECT_EQ(due, 40'000'000);
  // to the end of the (non-looping) log, then restarted once more
  int given = 1;
  while (cursor.next(s, due)) ++given;
  EXPECT_EQ(given, 10);
  EXPECT_EQ(due, 130'000'000);
  cursor.restart();
  ASSERT_TRUE(cursor.next(s, due));
  EXPECT_EQ(s.p_MT_m.x(), 0.0);
  EXPECT_EQ(due, 140'000'000);
  EXPECT_EQ(s.t_ns, samples[0].t_ns + 140'000'000);
}

}  // namespace
}  // namespace vcockpit::glove
