#pragma once
// Advances a world through a stream of glove samples on the samples' own timeline: the one rule
// the offline runner, the lockstep node, the tests and the benchmarks share.
//
// World time 0 is the first sample (or, after restart(), the world's time when the next sample
// comes). A sample takes effect at the first step boundary at or after its stamp, and the latest
// such sample wins, so each step uses the newest sample not later than its start. The same
// samples therefore give the same world whether they come from a file or over DDS.

#include <cstdint>

#include "common/assert.hpp"
#include "hand/glove_sample.hpp"
#include "physics_node/io/hand_input.hpp"
#include "physics_node/physics/world.hpp"

namespace vcockpit::physics_io {

class ReplayDriver {
 public:
  ReplayDriver(physics::World& world, const hand::HandModel& hand) : world_(world), hand_(hand) {}

  // World time (ns) at which `sample` takes effect; starts the timeline at the first sample.
  int64_t world_time_of(const hand::GloveSample& sample) {
    if (!started_) {
      t0_ns_ = sample.t_ns - world_.time_ns();
      started_ = true;
    }
    return sample.t_ns - t0_ns_;
  }

  // Steps the world up to the sample's time, then applies it. `step()` advances the world by one
  // step (world.step() and whatever the caller records around it).
  template <class Step>
  void feed(const hand::GloveSample& sample, Step&& step) {
    step_until(world_time_of(sample), step);
    world_.set_hand_input(hand_input_from_glove(hand_, sample));
  }

  // Steps with the current input until world time reaches t_ns.
  template <class Step>
  void step_until(int64_t t_ns, Step&& step) {
    while (world_.time_ns() < t_ns) {
      const int64_t before_ns = world_.time_ns();
      step();
      VCOCKPIT_ASSERT(world_.time_ns() > before_ns, "the step callable must step the world");
    }
  }

  // A new source (a restarted glove driver): its first sample is the world's present.
  void restart() { started_ = false; }
  bool started() const { return started_; }

 private:
  physics::World& world_;
  const hand::HandModel& hand_;
  int64_t t0_ns_ = 0;
  bool started_ = false;
};

}  // namespace vcockpit::physics_io
