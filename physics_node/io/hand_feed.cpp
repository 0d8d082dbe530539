#include "physics_node/io/hand_feed.hpp"

namespace vcockpit::physics_io {

void HandFeed::queue(const hand::GloveSample& sample, int64_t source_stamp_ns) {
  // what was taken is let go: all of it when the queue ran dry, else once it is the larger part
  // (a source that stays ahead of the world never lets the queue run dry: no growth in a long run)
  if (next_ == queued_.size()) {
    queued_.clear();
    next_ = 0;
  } else if (next_ >= 64 && next_ * 2 >= queued_.size()) {
    queued_.erase(queued_.begin(), queued_.begin() + static_cast<std::ptrdiff_t>(next_));
    next_ = 0;
  }
  queued_.push_back({sample, source_stamp_ns});
}

void HandFeed::drop_queued() {
  queued_.erase(queued_.begin() + static_cast<std::ptrdiff_t>(next_), queued_.end());
}

void HandFeed::keep_newest_only() {
  if (!has_queued()) return;
  queued_.erase(queued_.begin(), queued_.end() - 1);
  next_ = 0;
}

void HandFeed::take_until(ReplayDriver& driver, int64_t until_ns, int64_t world_now_ns,
                          int64_t end_ns) {
  while (has_queued() && (!driver.has_sample() || driver.newest_world_ns() < until_ns)) {
    const Queued& q = queued_[next_];
    // begins later on the shared timeline
    if (!driver.has_sample() && driver.started() && driver.world_time_of(q.sample) > world_now_ns)
      break;
    if (driver.has_sample() && driver.newest_world_ns() > end_ns) break;  // past the end already
    driver.push(q.sample, q.source_stamp_ns);
    ++next_;
  }
}

}  // namespace vcockpit::physics_io
