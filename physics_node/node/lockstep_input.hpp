#pragma once
// Lockstep's input (node_loop.cpp): the samples each hand receives are queued in its HandFeed,
// and the world steps by the offline runner's rule (physics_io::HandFeed): before each step each
// hand takes its samples up to the first at or past the step's end, and the step waits until
// every hand that has begun (and every --lockstep-hands hand) has one, as more may still come.
// World time 0 is the first sample; a later source (a restarted glove driver) continues from
// where the world is; a second hand's first source shares the first hand's timeline (one clock).
// While time is frozen each hand keeps only its newest sample, and after it the hands take up
// their gloves from there.

#include <cstdint>

#include "hand/glove_sample.hpp"
#include "physics_node/node/hand_channels.hpp"
#include "physics_node/physics/world.hpp"

namespace vcockpit::physics_node {

class LockstepInput {
 public:
  LockstepInput(HandChannels& hands, const physics::World& world) : hands_(hands), world_(world) {}

  // A sample accepted for hand `ch` (drain's callback).
  void queue(HandChannel& ch, const hand::GloveSample& sample, bool new_source,
             int64_t source_stamp_ns);
  // Each hand takes its samples for the step ending at step_end_ns; true when the step can be
  // taken now. `any`: some hand has begun (the run's first row can be written).
  bool take_for_step(int64_t step_end_ns, bool& any);
  // The hands' inputs for that step, interpolated at its end.
  void set_inputs(int64_t step_end_ns);
  // Frozen: what keeps arriving is not stepped through; each hand keeps only its newest.
  void hold_frozen();
  // Unfrozen: the world's time stood still while the gloves' went on; each hand that sent
  // samples meanwhile starts a new timeline at its newest, all at one origin (the latest of
  // them is the world's present, so none begins in the future: a hand every step waits for must
  // have its sample now), and the world goes on from where it stopped.
  void resume_after_freeze();
  // Some hand's timeline has begun.
  bool started() const;

 private:
  HandChannels& hands_;
  const physics::World& world_;
};

}  // namespace vcockpit::physics_node
