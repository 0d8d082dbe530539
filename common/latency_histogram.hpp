#pragma once
// A latency histogram for real-time loops: fixed-width bins allocated once at construction, so
// record_ns() never allocates, locks or throws. Values beyond the range land in an overflow count;
// count, min and max stay exact. Percentiles are the upper edge of the bin holding the ranked
// value, clamped to [min, max]: never below the true value, at most one bin width above it.
//
// Default: 1 us bins up to 100 ms (100,000 bins, 400 KB): latencies of tens of microseconds read
// to the microsecond, and anything slower than 100 ms is a stall that shows in the max.

#include <nlohmann/json_fwd.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace vcockpit {

class LatencyHistogram {
 public:
  static constexpr int64_t kDefaultBinWidth_ns = 1'000;
  static constexpr int64_t kDefaultRange_ns = 100'000'000;

  // Bins of `bin_width_ns` covering [0, range_ns). Throws std::invalid_argument unless
  // 0 < bin_width_ns <= range_ns.
  explicit LatencyHistogram(int64_t bin_width_ns = kDefaultBinWidth_ns,
                            int64_t range_ns = kDefaultRange_ns);

  // A negative value (a clock stepped backwards between two stamps) counts in the first bin and
  // in negative_count(); min_ns() keeps it exact.
  void record_ns(int64_t value_ns) noexcept;
  void reset() noexcept;

  uint64_t count() const { return count_; }
  uint64_t overflow_count() const { return overflow_; }
  uint64_t negative_count() const { return negative_; }
  int64_t min_ns() const { return count_ ? min_ns_ : 0; }
  int64_t max_ns() const { return count_ ? max_ns_ : 0; }
  double mean_ns() const;
  int64_t bin_width_ns() const { return bin_width_ns_; }
  int64_t range_ns() const { return static_cast<int64_t>(bins_.size()) * bin_width_ns_; }

  // The value at quantile q in [0, 1] (0.5 median, 0.99, 1 the max); 0 when empty. The rank is
  // ceil(q * count), at least 1.
  int64_t percentile_ns(double q) const;

 private:
  int64_t bin_width_ns_;
  std::vector<uint32_t> bins_;  // a bin saturates at 2^32 - 1 (49 days of 1 kHz in one bin)
  uint64_t count_ = 0;
  uint64_t overflow_ = 0;
  uint64_t negative_ = 0;
  int64_t min_ns_ = 0;
  int64_t max_ns_ = 0;
  double sum_ns_ = 0.0;
};

// {"p50": 61.0, "p99": 230.0, "max": 1312.417, "count": 5000} in microseconds (ns / 1000: the
// printed number is the exact microseconds, to the nanosecond).
nlohmann::ordered_json latency_json_us(const LatencyHistogram& h);
// "p50 61.0 us, p99 230.0 us, max 1312.4 us (5000)" for log lines.
std::string latency_text_us(const LatencyHistogram& h);

}  // namespace vcockpit
