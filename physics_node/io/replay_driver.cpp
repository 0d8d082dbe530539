#include "physics_node/io/replay_driver.hpp"

#include <cmath>

#include "physics_node/io/hand_input.hpp"
#include "physics_node/io/sample_interpolation.hpp"

namespace vcockpit::physics_io {

ReplayDriver::ReplayDriver(physics::World& world, const hand::HandModel& hand,
                           const InputTiming& timing, int hand_index)
    : world_(world),
      hand_(hand),
      timing_(timing),
      hand_index_(hand_index),
      step_ns_(std::llround(world.scene().step_s * 1e9)) {
  check_input_timing(timing_);
}

void ReplayDriver::push(const hand::GloveSample& sample, int64_t source_stamp_ns) {
  const bool first = !started_;
  const int64_t world_t_ns = world_time_of(sample);
  if (first || !have_newest_) {
    newest_ = {sample, world_t_ns, source_stamp_ns};
    have_newest_ = true;
    have_previous_ = false;
    show(sample, source_stamp_ns, true);  // the hand at the world's present: no sweep from nowhere
    return;
  }
  VCOCKPIT_ASSERT(sample.t_ns > newest_.sample.t_ns, "samples must come in time order");
  const int64_t interval_ns = sample.t_ns - newest_.sample.t_ns;
  const hand::IntervalKind kind = intervals_.add(interval_ns, timing_.max_gap_ns);
  hand::count_interval(counts_, kind, interval_ns, true);
  bridged_ = kind != hand::IntervalKind::kBeyondMaxGap;
  previous_ = newest_;
  have_previous_ = true;
  newest_ = {sample, world_t_ns, source_stamp_ns};
}

void ReplayDriver::restart() {
  started_ = false;
  have_newest_ = false;
  have_previous_ = false;
  intervals_.reset();
}

void ReplayDriver::apply_input_at(int64_t end_ns) {
  VCOCKPIT_ASSERT(have_newest_, "a replay steps only after its first sample");
  if (have_previous_ && end_ns < newest_.world_t_ns && bridged_) {
    const int64_t t_ns = end_ns + t0_ns_;
    show(interpolate_sample(previous_.sample, newest_.sample, t_ns),
         interpolate_stamp_ns(previous_.source_stamp_ns, newest_.source_stamp_ns,
                              previous_.sample.t_ns, newest_.sample.t_ns, t_ns),
         true);
    return;
  }
  // held: the newest sample, or the earlier one of a gap not bridged
  const Known& held = have_previous_ && end_ns < newest_.world_t_ns ? previous_ : newest_;
  show(held.sample, held.source_stamp_ns, end_ns - held.world_t_ns <= timing_.glove_timeout_ns);
}

void ReplayDriver::show(const hand::GloveSample& sample, int64_t source_stamp_ns, bool tracking) {
  if (shown_.tracking && !tracking) ++counts_.glove_lost;
  shown_ = {sample.t_ns, source_stamp_ns, tracking};
  physics::HandInput input = hand_input_from_glove(hand_, sample);
  input.tracking = tracking;
  world_.set_hand_input(input, hand_index_);
}

}  // namespace vcockpit::physics_io
