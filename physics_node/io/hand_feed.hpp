#pragma once
// One hand's samples on their way into the world, and the stepping rule every runner shares: the
// offline runner and the grasp study (through HandTimeline) and the lockstep physics node over DDS
// take their samples here, so a replay steps the same whoever drives it. Before each step a hand
// takes its queued samples into its ReplayDriver up to the first at or past the step's end (its
// input is interpolated there); a hand not yet begun begins at its first sample's time on the
// shared timeline, not before; and nothing is taken once the hand is past the run's end.

#include <climits>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "hand/glove_sample.hpp"
#include "physics_node/io/replay_driver.hpp"

namespace vcockpit::physics_io {

class HandFeed {
 public:
  // Queues a sample (newer than those queued); source_stamp_ns goes with it to the driver.
  void queue(const hand::GloveSample& sample, int64_t source_stamp_ns = 0);
  void reserve(std::size_t samples) { queued_.reserve(samples); }  // a whole log queued at once
  bool has_queued() const { return next_ < queued_.size(); }
  // Samples queued and not taken yet.
  std::size_t queued_count() const { return queued_.size() - next_; }
  // Samples stored: the queued ones and taken ones not let go yet (at most about twice the
  // queued ones: a long run does not grow it).
  std::size_t stored_count() const { return queued_.size(); }
  // The oldest queued sample not taken yet (has_queued() first).
  const hand::GloveSample& front() const { return queued_[next_].sample; }
  // A new source: what the old one sent and was not taken is dropped.
  void drop_queued();
  // Time stands still (a frozen world): of what is queued, only the newest (the glove's present)
  // is kept.
  void keep_newest_only();

  // The rule: takes queued samples into `driver` up to the first at or past world time until_ns,
  // with the world at world_now_ns; none once the driver's newest is past end_ns.
  void take_until(ReplayDriver& driver, int64_t until_ns, int64_t world_now_ns,
                  int64_t end_ns = INT64_MAX);

 private:
  struct Queued {
    hand::GloveSample sample;
    int64_t source_stamp_ns;
  };
  std::vector<Queued> queued_;
  std::size_t next_ = 0;  // queued_[next_..] are not taken yet
};

}  // namespace vcockpit::physics_io
