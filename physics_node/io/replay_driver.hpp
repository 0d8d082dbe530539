#pragma once
// Advances a world through a stream of glove samples on the samples' own timeline: the one rule
// the offline runner, the lockstep node, the tests and the benchmarks share, so the same samples
// give the same world whether they come from a file or over DDS.
//
// World time 0 is the first sample (or, after restart(), the world's time when the next sample
// comes); that sample is the hand at once. Every later step ends at some world time T, and the
// hand it moves to is the input at T:
//   - between two samples at most `max_gap` apart: interpolated (sample_interpolation.hpp), so
//     the hand moves over the whole interval between their stamps, never in one step;
//   - between two samples further apart (a gap not bridged), or after the newest sample: the
//     earlier sample, held; once it is older than the glove timeout the glove is lost
//     (tracking = false: the hand stays, held objects are let go) until the next sample.
// A step whose end is past the newest sample waits for the next one (feed() steps only up to
// it): one sample of look-ahead, which offline and lockstep replay can afford. Only accepted
// samples are fed, so a rejected or dropped one is never an end point.

#include <cstdint>

#include "common/assert.hpp"
#include "hand/glove_sample.hpp"
#include "hand/input_counts.hpp"
#include "hand/sample_intervals.hpp"
#include "physics_node/io/input_timing.hpp"
#include "physics_node/physics/world.hpp"

namespace vcockpit::physics_io {

// What the hand shows after the last step: the source's time it stands for, the source stamp
// interpolated the same way (for latency), and whether the glove is tracked.
struct ShownInput {
  int64_t sample_time_ns = 0;
  int64_t source_stamp_ns = 0;
  bool tracking = false;
};

class ReplayDriver {
 public:
  // Drives the world's hand `hand_index` (World::hand_count()), whose model is `hand`.
  ReplayDriver(physics::World& world, const hand::HandModel& hand, const InputTiming& timing = {},
               int hand_index = 0);
  // Sets the timeline's origin: source time t0_ns is the world's present. Several drivers (one
  // per hand) share one timeline this way; without it the first sample is the present.
  void set_origin(int64_t t0_ns) {
    t0_ns_ = t0_ns - world_.time_ns();
    started_ = true;
  }
  // The source time at world time 0 (valid once started).
  int64_t source_time_at_world_zero() const { return t0_ns_; }
  // World time (ns) of the newest sample taken; whether one has been taken.
  int64_t newest_world_ns() const { return newest_.world_t_ns; }
  bool has_sample() const { return have_newest_; }
  // Sets the world's hand input for the step that ends at world time end_ns (for a caller that
  // steps the world itself: several drivers, one per hand, then one world step).
  void input_for_step_ending(int64_t end_ns) { apply_input_at(end_ns); }

  // World time (ns) of `sample`; starts the timeline at the first sample.
  int64_t world_time_of(const hand::GloveSample& sample) {
    if (!started_) {
      t0_ns_ = sample.t_ns - world_.time_ns();
      started_ = true;
    }
    return sample.t_ns - t0_ns_;
  }

  // Takes the next sample (newer than the last; `source_stamp_ns` only for shown()), then steps
  // the world through every step that ends at or before the sample's time. `step()` advances the
  // world by one step (world.step() and whatever the caller records around it).
  template <class Step>
  void feed(const hand::GloveSample& sample, Step&& step, int64_t source_stamp_ns = 0) {
    push(sample, source_stamp_ns);
    while (world_.time_ns() + step_ns_ <= newest_.world_t_ns)
      one_step(step);
  }

  // Takes the next sample without stepping (the look-ahead past the end of a shorter run).
  void push(const hand::GloveSample& sample, int64_t source_stamp_ns = 0);

  // Steps until world time reaches t_ns; past the newest sample the hand holds it.
  template <class Step>
  void step_until(int64_t t_ns, Step&& step) {
    while (world_.time_ns() < t_ns)
      one_step(step);
  }

  // A new source (a restarted glove driver): its first sample is the world's present, and no
  // interval joins it to the old source's samples.
  void restart();
  bool started() const { return started_; }

  const ShownInput& shown() const { return shown_; }
  // intervals (interpolated, gaps bridged and not), the longest, times the glove was lost
  const hand::InputCounts& counts() const { return counts_; }

 private:
  struct Known {
    hand::GloveSample sample;  // on the source's timeline
    int64_t world_t_ns = 0;
    int64_t source_stamp_ns = 0;
  };

  template <class Step>
  void one_step(Step& step) {
    apply_input_at(world_.time_ns() + step_ns_);
    const int64_t before_ns = world_.time_ns();
    step();
    VCOCKPIT_ASSERT(world_.time_ns() == before_ns + step_ns_,
                    "the step callable must step the world exactly once");
  }
  // Sets the world's hand input for the step that ends at world time end_ns.
  void apply_input_at(int64_t end_ns);
  void show(const hand::GloveSample& sample, int64_t source_stamp_ns, bool tracking);

  physics::World& world_;
  const hand::HandModel& hand_;
  InputTiming timing_;
  int hand_index_;
  int64_t step_ns_;
  int64_t t0_ns_ = 0;
  bool started_ = false;
  bool have_newest_ = false;
  bool have_previous_ = false;
  bool bridged_ = false;  // previous -> newest is interpolated
  Known previous_;
  Known newest_;
  hand::IntervalTracker intervals_;
  hand::InputCounts counts_;
  ShownInput shown_;
};

}  // namespace vcockpit::physics_io
