#include "physics_node/io/input_follower.hpp"

#include <algorithm>
#include <limits>

#include "common/assert.hpp"
#include "physics_node/io/sample_interpolation.hpp"

namespace vcockpit::physics_io {

InputFollower::InputFollower(const FollowerOptions& options) : options_(options), ring_(kCapacity) {
  VCOCKPIT_ASSERT(
      options.max_gap_ns >= 0 && options.margin_ns >= 0 && options.fixed_delay_ns.value_or(0) >= 0,
      "follower times must not be negative");
  reset();
}

void InputFollower::reset() {
  head_ = 0;
  size_ = 0;
  have_at_ = false;
  reached_t_ns_ = std::numeric_limits<int64_t>::min();
  intervals_.reset();
  delay_ns_ = target_delay_ns();
}

int64_t InputFollower::target_delay_ns() const {
  if (options_.fixed_delay_ns) return *options_.fixed_delay_ns;
  return intervals_.typical_ns() + options_.margin_ns;
}

void InputFollower::push(const hand::GloveSample& sample, int64_t arrival_ns,
                         int64_t source_stamp_ns) {
  Entry e{sample, arrival_ns, source_stamp_ns, false};
  const int64_t offset_ns = arrival_ns - sample.t_ns;
  if (size_ == 0 && !have_at_) {
    offset_ns_ = offset_ns;  // a new timeline
  } else {
    // up by 1 ms per second of arrivals (a division: no overflow however long the pause)
    const int64_t creep_ns = std::max<int64_t>(arrival_ns - last_arrival_ns_, 0) /
                             (1'000'000'000 / kOffsetCreepPerSecond_ns);
    offset_ns_ = std::min(offset_ns_ + creep_ns, offset_ns);
  }
  last_arrival_ns_ = arrival_ns;
  if (size_ > 0) {
    const hand::GloveSample& newest = entry(size_ - 1).sample;
    VCOCKPIT_ASSERT(sample.t_ns > newest.t_ns, "samples must come in time order");
    const int64_t interval_ns = sample.t_ns - newest.t_ns;
    // the hand has gone past the newest sample: it waited there for this one (judged once the
    // usual interval, and so the delay, is known: before that the hand only waits to start)
    const bool delay_known = intervals_.typical_ns() > 0;
    const hand::IntervalKind kind = intervals_.add(interval_ns, options_.max_gap_ns);
    const bool late =
        delay_known && kind != hand::IntervalKind::kBeyondMaxGap && reached_t_ns_ > newest.t_ns;
    hand::count_interval(counts_, kind, interval_ns, true, late);
    e.bridged_from_previous = kind != hand::IntervalKind::kBeyondMaxGap;
    // until a few intervals are known the hand has hardly moved: take the delay at once
    if (counts_.intervals <= static_cast<uint64_t>(hand::IntervalTracker::kMinHistory)) {
      delay_ns_ = target_delay_ns();
    }
  }
  if (size_ == kCapacity) {  // the oldest is far behind the shown time by now
    head_ = (head_ + 1) % kCapacity;
    --size_;
  }
  ring_[static_cast<std::size_t>((head_ + size_) % kCapacity)] = e;
  ++size_;
}

bool InputFollower::at(int64_t now_ns, FollowedInput& out) {
  if (size_ == 0) return false;
  if (have_at_) {
    const int64_t max_change_ns = std::max<int64_t>(now_ns - last_at_ns_, 0) / 10;
    const int64_t target_ns = target_delay_ns();
    delay_ns_ += std::clamp(target_ns - delay_ns_, -max_change_ns, max_change_ns);
  }
  last_at_ns_ = now_ns;
  have_at_ = true;
  const int64_t t_ns = shown_time_ns(now_ns);
  // keep one sample at or before the shown time
  while (size_ >= 2 && entry(1).sample.t_ns <= t_ns) {
    head_ = (head_ + 1) % kCapacity;
    --size_;
  }
  reached_t_ns_ = t_ns;
  const Entry& a = entry(0);
  if (size_ >= 2 && t_ns > a.sample.t_ns && entry(1).bridged_from_previous) {
    const Entry& b = entry(1);
    out.sample = interpolate_sample(a.sample, b.sample, t_ns);
    out.source_stamp_ns = interpolate_stamp_ns(a.source_stamp_ns, b.source_stamp_ns, a.sample.t_ns,
                                               b.sample.t_ns, t_ns);
    return true;
  }
  // before the oldest (the start), waiting for the next sample, or a gap not bridged: hold
  out.sample = a.sample;
  out.source_stamp_ns = a.source_stamp_ns;
  return true;
}

}  // namespace vcockpit::physics_io
