#include "hand/sample_intervals.hpp"

#include <algorithm>

namespace vcockpit::hand {

IntervalKind IntervalTracker::add(int64_t interval_ns, int64_t max_gap_ns) {
  if (interval_ns > max_gap_ns) return IntervalKind::kBeyondMaxGap;
  const bool gap = size_ >= kMinHistory && interval_ns > 2 * typical_ns();
  window_[static_cast<std::size_t>(next_)] = interval_ns;
  next_ = (next_ + 1) % kWindow;
  size_ = std::min(size_ + 1, kWindow);
  return gap ? IntervalKind::kGap : IntervalKind::kRegular;
}

int64_t IntervalTracker::typical_ns() const {
  if (size_ == 0) return 0;
  std::array<int64_t, kWindow> sorted = window_;
  const auto end = sorted.begin() + size_;
  const auto middle = sorted.begin() + size_ / 2;
  std::nth_element(sorted.begin(), middle, end);
  return *middle;
}

void count_interval(InputCounts& counts, IntervalKind kind, int64_t interval_ns, bool moved,
                    bool late) {
  ++counts.intervals;
  counts.longest_interval_ns = std::max(counts.longest_interval_ns, interval_ns);
  if (kind == IntervalKind::kBeyondMaxGap) {
    ++counts.gaps_not_bridged;
  } else if (late) {
    ++counts.intervals_late;
  } else if (kind == IntervalKind::kGap) {
    ++counts.gaps_bridged;
  } else if (moved) {
    ++counts.intervals_interpolated;
  }
}

}  // namespace vcockpit::hand
