// write_fixed against std::to_chars (printf's "%.*f"): the same characters for every value,
// including the halfway cases its integer path must round to even.
#include "common/fixed_decimal.hpp"

#include <gtest/gtest.h>

#include <charconv>
#include <cmath>
#include <limits>
#include <random>
#include <string>

namespace vcockpit {
namespace {

std::string reference(double v, int decimals) {
  char text[400];
  const auto [end, error] = std::to_chars(text, text + sizeof text, v, std::chars_format::fixed, decimals);
  EXPECT_EQ(error, std::errc());
  return std::string(text, end);
}

std::string ours(double v, int decimals) {
  std::string out;
  append_fixed(out, v, decimals);
  return out;
}

TEST(FixedDecimal, SpecialValuesAreWrittenAsPrintfWritesThem) {
  for (int d : {0, 1, 6, 9, 12}) {
    for (double v : {0.0, -0.0, 1.0, -1.0, 0.5, 1.5, 2.5, -2.5, 1e-300, -1e-300, 4.9e-324,
                     999999999999999.9, 1e15, -1e15, 1e300, std::numeric_limits<double>::max(),
                     std::numeric_limits<double>::infinity(),
                     -std::numeric_limits<double>::infinity(),
                     std::numeric_limits<double>::quiet_NaN()}) {
      EXPECT_EQ(ours(v, d), reference(v, d)) << v << " with " << d << " decimals";
    }
  }
}

TEST(FixedDecimal, ExactHalfwayValuesRoundToEven) {
  // k / 2^10 with 9 decimals has at most 10 binary digits after the point: many end in 5 at
  // the tenth decimal, exactly halfway
  int halfway = 0;
  for (int k = -5000; k <= 5000; ++k) {
    const double v = std::ldexp(static_cast<double>(k), -10);
    for (int d = 0; d <= 9; ++d) {
      EXPECT_EQ(ours(v, d), reference(v, d)) << v << " with " << d << " decimals";
      const double scaled = v * std::pow(10.0, d);
      if (scaled - std::floor(scaled) == 0.5) ++halfway;
    }
  }
  EXPECT_GT(halfway, 1000);  // the cases meant are really there
}

TEST(FixedDecimal, RandomValuesOfEveryMagnitudeMatchToChars) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-60, 60);
  std::uniform_int_distribution<int> decimals(0, 9);
  for (int i = 0; i < 200000; ++i) {
    const double v = std::ldexp(mantissa(rng), exponent(rng));
    const int d = decimals(rng);
    ASSERT_EQ(ours(v, d), reference(v, d)) << v << " with " << d << " decimals";
  }
}

TEST(FixedDecimal, ATooSmallBufferIsRefusedNotOverrun) {
  char text[8] = {'x', 'x', 'x', 'x', 'x', 'x', 'x', 'x'};
  EXPECT_EQ(write_fixed(text, text + 4, 123.456, 3), nullptr);
  char* end = write_fixed(text, text + 7, 123.456, 3);
  ASSERT_NE(end, nullptr);
  EXPECT_EQ(std::string(text, end), "123.456");
  EXPECT_EQ(text[7], 'x');
}

}  // namespace
}  // namespace vcockpit
