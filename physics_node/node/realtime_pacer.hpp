#pragma once
// Real time's pacing (node_loop.cpp): a step slot every period on the monotonic clock, the world
// published every publish period. A step that ends after its slot is late; steps are never
// skipped silently: a node that fell behind runs them back to back, and only beyond
// kMaxCatchUpSteps does it resynchronise, counting every slot it dropped as late.

#include <cstdint>

#include "common/clock.hpp"
#include "physics_node/node/node_loop.hpp"

namespace vcockpit::physics_node {

class RealtimePacer {
 public:
  RealtimePacer(int64_t period_ns, int64_t publish_period_ns, int64_t start_ns)
      : period_ns_(period_ns), publish_period_ns_(publish_period_ns), next_ns_(start_ns),
        next_publish_ns_(start_ns) {}

  // Sleeps until this slot begins.
  void wait_for_slot() const { sleep_until_ns(next_ns_); }
  // The end of this slot: where the step's hand is taken.
  int64_t slot_end_ns() const { return next_ns_ + period_ns_; }
  // A step of this slot ended at `end_ns`: late if after the slot.
  void step_ended(int64_t end_ns) {
    if (end_ns > slot_end_ns()) ++late_steps_;
  }
  // True when the world is due to be published at `now_ns` (then the next is a period on, or a
  // period from now when publishing fell behind).
  bool publish_due(int64_t now_ns) {
    if (now_ns < next_publish_ns_) return false;
    next_publish_ns_ += publish_period_ns_;
    if (next_publish_ns_ < now_ns) next_publish_ns_ = now_ns + publish_period_ns_;
    return true;
  }
  // On to the next slot. Far behind at `now_ns` (a stall): resynchronised, every dropped slot
  // counted late; returns how many were dropped (0: none).
  int64_t next_slot(int64_t now_ns) {
    next_ns_ += period_ns_;
    const int64_t behind = (now_ns - next_ns_) / period_ns_;
    if (behind <= kMaxCatchUpSteps) return 0;
    late_steps_ += static_cast<uint64_t>(behind);
    next_ns_ += behind * period_ns_;
    return behind;
  }
  uint64_t late_steps() const { return late_steps_; }

 private:
  int64_t period_ns_;
  int64_t publish_period_ns_;
  int64_t next_ns_;
  int64_t next_publish_ns_;
  uint64_t late_steps_ = 0;
};

}  // namespace vcockpit::physics_node
