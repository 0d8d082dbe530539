#include "physics_node/node/lockstep_input.hpp"

#include <algorithm>

namespace vcockpit::physics_node {

void LockstepInput::queue(HandChannel& ch, const hand::GloveSample& sample, bool new_source,
                          int64_t source_stamp_ns) {
  if (new_source) {
    ch.replay.restart();
    const HandChannel* begun = nullptr;
    for (const HandChannel& other : hands_)
      if (&other != &ch && other.replay.has_sample()) begun = &other;
    if (begun != nullptr && !ch.replay.has_sample() && ch.received == 1)
      ch.replay.set_origin(begun->replay.source_time_at_world_zero() + world_.time_ns());
    ch.feed.drop_queued();
  }
  ch.feed.queue(sample, source_stamp_ns);
}

bool LockstepInput::take_for_step(int64_t step_end_ns, bool& any) {
  bool ready = true;
  any = false;
  for (HandChannel& ch : hands_) {
    ch.feed.take_until(ch.replay, step_end_ns, world_.time_ns());
    if (!ch.replay.has_sample()) {
      ready = ready && !ch.expected;
      continue;
    }
    any = true;
    ready = ready && ch.replay.newest_world_ns() >= step_end_ns;
  }
  return ready && any;
}

void LockstepInput::set_inputs(int64_t step_end_ns) {
  for (HandChannel& ch : hands_)
    if (ch.replay.has_sample()) ch.replay.input_for_step_ending(step_end_ns);
}

void LockstepInput::hold_frozen() {
  for (HandChannel& ch : hands_) {
    if (!ch.feed.has_queued()) continue;
    ch.feed.keep_newest_only();
    ch.arrived_frozen = true;
  }
}

void LockstepInput::resume_after_freeze() {
  bool any = false;
  int64_t origin_ns = 0;
  for (HandChannel& ch : hands_) {
    if (!ch.arrived_frozen || !ch.feed.has_queued()) continue;
    const int64_t t_ns = ch.feed.front().t_ns;
    origin_ns = any ? std::max(origin_ns, t_ns) : t_ns;
    any = true;
  }
  for (HandChannel& ch : hands_) {
    if (!ch.arrived_frozen || !ch.feed.has_queued()) continue;
    ch.replay.restart();
    ch.replay.set_origin(origin_ns);
    ch.arrived_frozen = false;
  }
}

bool LockstepInput::started() const {
  for (const HandChannel& ch : hands_)
    if (ch.replay.started()) return true;
  return false;
}

}  // namespace vcockpit::physics_node
