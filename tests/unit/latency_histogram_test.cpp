// LatencyHistogram: exact count/min/max, percentiles within one bin above the true value,
// overflow and negative values, no allocation while recording, and the JSON/text forms.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

#include "common/latency_histogram.hpp"
#include "tests/support/allocation_counter.hpp"

namespace vcockpit {
namespace {

TEST(LatencyHistogram, EmptyReportsZeros) {
  LatencyHistogram h;
  EXPECT_EQ(h.count(), 0u);
  EXPECT_EQ(h.percentile_ns(0.5), 0);
  EXPECT_EQ(h.max_ns(), 0);
  EXPECT_EQ(h.min_ns(), 0);
  EXPECT_EQ(latency_json_us(h), nlohmann::ordered_json::parse(
                                    R"({"p50": 0.000, "p99": 0.000, "max": 0.000, "count": 0})"));
}

TEST(LatencyHistogram, PercentilesOfOneToHundredMicroseconds) {
  LatencyHistogram h;  // 1 us bins
  for (int us = 100; us >= 1; --us) h.record_ns(us * 1000 - 300);  // 0.7, 1.7, ... 99.7 us
  EXPECT_EQ(h.count(), 100u);
  EXPECT_EQ(h.min_ns(), 700);
  EXPECT_EQ(h.max_ns(), 99'700);
  // rank 50 is 49.7 us, reported as its bin's upper edge 50 us; rank 99 is 98.7 us -> 99 us
  EXPECT_EQ(h.percentile_ns(0.5), 50'000);
  EXPECT_EQ(h.percentile_ns(0.99), 99'000);
  EXPECT_EQ(h.percentile_ns(1.0), 99'700) << "clamped to the exact max";
  EXPECT_EQ(h.percentile_ns(0.0), 1'000) << "rank 1: the first bin's edge";
  EXPECT_NEAR(h.mean_ns(), 50'200.0, 1e-6);
}

TEST(LatencyHistogram, PercentileIsNeverBelowTheTrueValueAndAtMostOneBinAbove) {
  std::mt19937_64 rng(7);
  std::lognormal_distribution<double> dist(11.0, 0.8);  // around 60 us, tail into ms
  LatencyHistogram h;
  std::vector<int64_t> values;
  for (int i = 0; i < 20'000; ++i) {
    const auto v = static_cast<int64_t>(dist(rng));
    values.push_back(v);
    h.record_ns(v);
  }
  std::sort(values.begin(), values.end());
  for (double q : {0.01, 0.25, 0.5, 0.9, 0.99, 0.999}) {
    const auto rank = static_cast<std::size_t>(std::ceil(q * static_cast<double>(values.size())));
    const int64_t truth = values[rank - 1];
    const int64_t got = h.percentile_ns(q);
    EXPECT_GE(got, truth) << q;
    EXPECT_LE(got - truth, h.bin_width_ns()) << q;
  }
  EXPECT_EQ(h.max_ns(), values.back());
}

TEST(LatencyHistogram, ValuesBeyondTheRangeOverflowButKeepAnExactMax) {
  LatencyHistogram h(1'000, 10'000);  // 10 bins of 1 us
  for (int i = 0; i < 98; ++i) h.record_ns(2'500);
  h.record_ns(50'000);
  h.record_ns(7'000'000);
  EXPECT_EQ(h.overflow_count(), 2u);
  EXPECT_EQ(h.percentile_ns(0.5), 3'000);
  // rank 99 (50 us) is in the overflow: only the max is known there, never below the truth
  EXPECT_EQ(h.percentile_ns(0.99), 7'000'000);
  EXPECT_EQ(h.max_ns(), 7'000'000);
  EXPECT_EQ(h.range_ns(), 10'000);
}

TEST(LatencyHistogram, NegativeValuesCountInTheFirstBinWithAnExactMin) {
  LatencyHistogram h;
  h.record_ns(-400);
  h.record_ns(200);
  EXPECT_EQ(h.negative_count(), 1u);
  EXPECT_EQ(h.min_ns(), -400);
  EXPECT_EQ(h.percentile_ns(0.5), 200) << "first bin's edge, clamped to the max";
}

TEST(LatencyHistogram, ResetEmptiesIt) {
  LatencyHistogram h;
  h.record_ns(5'000);
  h.reset();
  EXPECT_EQ(h.count(), 0u);
  h.record_ns(1'500);
  EXPECT_EQ(h.percentile_ns(0.5), 1'500);
  EXPECT_EQ(h.min_ns(), 1'500);
}

TEST(LatencyHistogram, RecordingDoesNotAllocate) {
  LatencyHistogram h;
  test::g_allocations = 0;
  test::g_count_allocations = true;
  for (int64_t v = -10; v < 200'000'000; v += 997) h.record_ns(v);
  (void)h.percentile_ns(0.99);
  test::g_count_allocations = false;
  EXPECT_EQ(test::g_allocations.load(), 0);
}

TEST(LatencyHistogram, RejectsABadShape) {
  EXPECT_THROW(LatencyHistogram(0, 1'000), std::invalid_argument);
  EXPECT_THROW(LatencyHistogram(-1, 1'000), std::invalid_argument);
  EXPECT_THROW(LatencyHistogram(1'000, 999), std::invalid_argument);
}

TEST(LatencyHistogram, JsonAndTextInMicroseconds) {
  LatencyHistogram h;
  h.record_ns(61'200);
  h.record_ns(1'312'417);
  EXPECT_EQ(latency_json_us(h),
            nlohmann::ordered_json::parse(
                R"({"p50": 62.000, "p99": 1312.417, "max": 1312.417, "count": 2})"));
  EXPECT_EQ(latency_text_us(h), "p50 62.0 us, p99 1312.4 us, max 1312.4 us (2)");
}

}  // namespace
}  // namespace vcockpit
