#include "common/latency_histogram.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

namespace vcockpit {

LatencyHistogram::LatencyHistogram(int64_t bin_width_ns, int64_t range_ns)
    : bin_width_ns_(bin_width_ns) {
  if (bin_width_ns <= 0 || range_ns < bin_width_ns) {
    throw std::invalid_argument("latency histogram: need 0 < bin width (" +
                                std::to_string(bin_width_ns) + " ns) <= range (" +
                                std::to_string(range_ns) + " ns)");
  }
  bins_.assign(static_cast<std::size_t>((range_ns + bin_width_ns - 1) / bin_width_ns), 0);
}

void LatencyHistogram::record_ns(int64_t value_ns) noexcept {
  if (count_ == 0) {
    min_ns_ = max_ns_ = value_ns;
  } else {
    min_ns_ = std::min(min_ns_, value_ns);
    max_ns_ = std::max(max_ns_, value_ns);
  }
  ++count_;
  sum_ns_ += static_cast<double>(value_ns);
  if (value_ns < 0) {
    ++negative_;
    value_ns = 0;
  }
  const auto bin = static_cast<uint64_t>(value_ns / bin_width_ns_);
  if (bin >= bins_.size()) {
    ++overflow_;
    return;
  }
  uint32_t& slot = bins_[bin];
  if (slot != std::numeric_limits<uint32_t>::max()) ++slot;
}

void LatencyHistogram::reset() noexcept {
  std::fill(bins_.begin(), bins_.end(), 0u);
  count_ = overflow_ = negative_ = 0;
  min_ns_ = max_ns_ = 0;
  sum_ns_ = 0.0;
}

double LatencyHistogram::mean_ns() const {
  return count_ ? sum_ns_ / static_cast<double>(count_) : 0.0;
}

int64_t LatencyHistogram::percentile_ns(double q) const {
  if (count_ == 0) return 0;
  q = std::clamp(q, 0.0, 1.0);
  // the small tolerance keeps q * count = 99.000000001 (0.99 * 100 in binary) at rank 99
  const double exact_rank = q * static_cast<double>(count_);
  auto rank = static_cast<uint64_t>(std::ceil(exact_rank - 1e-9 * exact_rank));
  rank = std::clamp<uint64_t>(rank, 1, count_);
  uint64_t seen = 0;
  for (std::size_t i = 0; i < bins_.size(); ++i) {
    seen += bins_[i];
    if (seen >= rank) {
      const int64_t upper_ns = static_cast<int64_t>(i + 1) * bin_width_ns_;
      return std::clamp(upper_ns, min_ns_, max_ns_);
    }
  }
  return max_ns_;  // the ranked value is in the overflow
}

nlohmann::ordered_json latency_json_us(const LatencyHistogram& h) {
  const auto us = [](int64_t ns) { return static_cast<double>(ns) / 1e3; };
  return {{"p50", us(h.percentile_ns(0.5))},
          {"p99", us(h.percentile_ns(0.99))},
          {"max", us(h.max_ns())},
          {"count", h.count()}};
}

std::string latency_text_us(const LatencyHistogram& h) {
  char text[160];
  std::snprintf(text, sizeof text, "p50 %.1f us, p99 %.1f us, max %.1f us (%llu)",
                static_cast<double>(h.percentile_ns(0.5)) * 1e-3,
                static_cast<double>(h.percentile_ns(0.99)) * 1e-3,
                static_cast<double>(h.max_ns()) * 1e-3, static_cast<unsigned long long>(h.count()));
  return text;
}

}  // namespace vcockpit
