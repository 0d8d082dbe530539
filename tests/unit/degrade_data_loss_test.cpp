// dropouts and gaps: exact dropout counts, gap lengths in their range, ends kept, bad gaps named.

#include <gtest/gtest.h>

#include "glove_driver/degrade/data_loss.hpp"
#include "glove_driver/degrade/degrade_error.hpp"
#include "tests/unit/degrade_samples.hpp"

namespace vcockpit::degrade {
namespace {

TEST(Dropouts, ExactlyTheRateOfTheRowsAfterTheFirst) {
  const auto hand = test::default_hand();
  const auto clean = test::smooth_log(hand, 4.0, 1000.0);  // 4001 rows
  for (double rate : {0.0, 0.01, 0.02, 0.1, 0.5}) {
    const auto rows = mark_dropouts(clean, rate, 9);
    ASSERT_EQ(rows.size(), clean.size());
    std::size_t dropped = 0;
    for (std::size_t i = 0; i < rows.size(); ++i) {
      dropped += rows[i].valid ? 0 : 1;
      EXPECT_EQ(rows[i].sample.t_ns, clean[i].t_ns);
    }
    EXPECT_EQ(dropped, static_cast<std::size_t>(std::llround(rate * 4000))) << rate;
    EXPECT_TRUE(rows.front().valid);
  }
}

TEST(Dropouts, SpreadOverTheLog) {
  const auto hand = test::default_hand();
  const auto rows = mark_dropouts(test::smooth_log(hand, 4.0, 1000.0), 0.02, 9);
  int first_half = 0;
  for (std::size_t i = 0; i < rows.size() / 2; ++i) first_half += rows[i].valid ? 0 : 1;
  EXPECT_GT(first_half, 20);  // 40 in 80, binomial: 40 +- 4.5
  EXPECT_LT(first_half, 60);
}

// The holes between consecutive rows longer than one period, minus that period.
std::vector<int64_t> holes_ns(const std::vector<hand::GloveSample>& s, int64_t period_ns) {
  std::vector<int64_t> out;
  for (std::size_t i = 1; i < s.size(); ++i) {
    if (s[i].t_ns - s[i - 1].t_ns > period_ns) out.push_back(s[i].t_ns - s[i - 1].t_ns - period_ns);
  }
  return out;
}

TEST(Gaps, LengthsInTheirRangeAndTheEndsKept) {
  const auto hand = test::default_hand();
  const auto clean = test::smooth_log(hand, 8.0, 1000.0);
  for (uint64_t seed = 1; seed <= 20; ++seed) {
    auto cut = clean;
    const auto placed = cut_gaps(cut, Gaps{2, 0.1, 0.7, {}}, seed);
    ASSERT_EQ(placed.size(), 2u);
    const auto holes = holes_ns(cut, 1'000'000);
    ASSERT_EQ(holes.size(), 2u) << "seed " << seed;
    for (std::size_t g = 0; g < 2; ++g) {
      // rows on a 1 ms grid: a hole is the gap's length to within one period
      EXPECT_LT(std::abs(holes[g] - placed[g].length_ns), 1'000'000);
      EXPECT_GE(placed[g].length_ns, 100'000'000);
      EXPECT_LE(placed[g].length_ns, 700'000'000);
    }
    EXPECT_EQ(cut.front().t_ns, clean.front().t_ns);
    EXPECT_EQ(cut.back().t_ns, clean.back().t_ns);
    const auto removed = clean.size() - cut.size();
    EXPECT_NEAR(static_cast<double>(removed),
                static_cast<double>(holes[0] + holes[1]) / 1e6, 2.0);
  }
}

TEST(Gaps, AtGivenTimes) {
  const auto hand = test::default_hand();
  auto cut = test::smooth_log(hand, 4.0, 1000.0);
  const auto placed = cut_gaps(cut, Gaps{0, 0.3, 0.3, {1.0, 2.5}}, 1);
  ASSERT_EQ(placed.size(), 2u);
  EXPECT_EQ(placed[0].start_ns, 1'000'000'000);
  EXPECT_EQ(placed[1].start_ns, 2'500'000'000);
  for (const auto& s : cut) {
    EXPECT_FALSE(s.t_ns >= 1'000'000'000 && s.t_ns < 1'300'000'000);
    EXPECT_FALSE(s.t_ns >= 2'500'000'000 && s.t_ns < 2'800'000'000);
  }
  EXPECT_EQ(cut.size(), 4001u - 600u);
}

TEST(Gaps, ThatDoNotFitAreErrors) {
  const auto hand = test::default_hand();
  auto cut = test::smooth_log(hand, 1.0, 1000.0);
  auto error_of = [&](const Gaps& g) -> std::string {
    try {
      auto copy = cut;
      cut_gaps(copy, g, 1);
    } catch (const DegradeError& e) {
      return e.what();
    }
    return "(no error)";
  };
  EXPECT_NE(error_of(Gaps{0, 0.3, 0.3, {0.9}}).find("does not fit"), std::string::npos);
  EXPECT_NE(error_of(Gaps{0, 0.3, 0.3, {0.2, 0.4}}).find("overlaps"), std::string::npos);
  EXPECT_NE(error_of(Gaps{3, 0.5, 0.7, {}}).find("cannot place 3 gaps"), std::string::npos);
  EXPECT_NE(error_of(Gaps{1, 0.5, 0.2, {}}).find("0 < min <= max"), std::string::npos);
}

}  // namespace
}  // namespace vcockpit::degrade
