#include "common/fixed_decimal.hpp"

#include <array>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <stdexcept>

namespace vcockpit {
namespace {

constexpr std::array<uint64_t, 10> kPow10 = {1,          10,          100,        1000,
                                             10000,      100000,      1000000,    10000000,
                                             100000000,  1000000000};
constexpr int kMaxFastDecimals = 9;
constexpr double kMaxFastMagnitude = 1e15;  // |v| 10^9 < 2^80: the product fits in 128 bits

char* write_general(char* first, char* last, double v, int decimals) {
  const auto [end, error] = std::to_chars(first, last, v, std::chars_format::fixed, decimals);
  return error == std::errc() ? end : nullptr;
}

}  // namespace

char* write_fixed(char* first, char* last, double v, int decimals) {
  if (decimals < 0 || decimals > kMaxFastDecimals || !(std::fabs(v) < kMaxFastMagnitude))
    return write_general(first, last, v, decimals);
  // |v| = m 2^e exactly
  const auto bits = std::bit_cast<uint64_t>(v);
  const bool negative = (bits >> 63) != 0;
  const int biased = static_cast<int>((bits >> 52) & 0x7ff);
  uint64_t m = bits & ((uint64_t{1} << 52) - 1);
  int e = -1074;  // a subnormal's
  if (biased != 0) {
    m |= uint64_t{1} << 52;
    e = biased - 1075;
  }
  // |v| = whole + f / 2^s with s = -e (|v| < 1e15 < 2^50 makes e negative; kept general)
  __extension__ typedef unsigned __int128 u128;  // (GCC and Clang on 64-bit targets)
  const uint64_t p = kPow10[static_cast<std::size_t>(decimals)];
  uint64_t whole = 0;
  uint64_t fraction = 0;  // round(f 10^decimals / 2^s), half to even
  if (e >= 0) {
    whole = m << e;  // (< 1e15: no bit lost)
  } else {
    const int s = -e;
    uint64_t f = m;
    if (s < 64) {
      whole = m >> s;
      f = m - (whole << s);
    }
    if (s < 128) {
      const u128 scaled = static_cast<u128>(f) * p;  // < 2^53 2^30
      auto digits = static_cast<uint64_t>(scaled >> s);
      const u128 rest = scaled - (static_cast<u128>(digits) << s);
      const u128 half = static_cast<u128>(1) << (s - 1);
      // (a tie goes to the even last digit written: the fraction's, or with no decimals the
      // whole part's)
      const uint64_t last_digit = decimals > 0 ? digits : whole;
      if (rest > half || (rest == half && (last_digit & 1) != 0)) ++digits;
      if (digits == p) {  // rounded up into the whole part
        digits = 0;
        ++whole;
      }
      fraction = digits;
    }  // else: below 2^-44 at most, which rounds to zero
  }
  // sign, whole part, point and zero-padded fraction: at most 1 + 16 + 1 + 9 characters
  char* out = first;
  if (last - first < 27 + decimals) {
    char buffer[40];
    char* end = write_fixed(buffer, buffer + sizeof buffer, v, decimals);
    if (end == nullptr || end - buffer > last - first) return nullptr;
    for (char* c = buffer; c != end; ++c) *out++ = *c;
    return out;
  }
  if (negative) *out++ = '-';
  out = std::to_chars(out, last, whole).ptr;
  if (decimals > 0) {
    *out++ = '.';
    uint64_t rest = fraction;
    for (int d = decimals - 1; d >= 0; --d) {
      out[d] = static_cast<char>('0' + rest % 10);
      rest /= 10;
    }
    out += decimals;
  }
  return out;
}

void append_fixed(std::string& out, double v, int decimals) {
  char text[400];  // room for DBL_MAX's 309 integer digits
  char* end = write_fixed(text, text + sizeof text, v, decimals);
  if (end == nullptr) throw std::logic_error("a value too long to write: " + std::to_string(v));
  out.append(text, end);
}

}  // namespace vcockpit
