#pragma once
// Several hands' glove samples replayed on one timeline: the offline runner's loop, shared with
// the grasp study (bench/study) so that a trial is replayed exactly as `physics_node --offline`
// replays a log. One ReplayDriver per hand (replay_driver.hpp); the earliest first sample is world
// time 0. Each hand's samples go through a HandFeed (hand_feed.hpp: the stepping rule the
// lockstep node shares): before each step each hand takes its samples up to the first at or
// past the step's end (its look-ahead); a hand whose samples start later joins when the world
// reaches its first sample, and one whose samples have ended holds its last (and loses the glove
// after the timeout, as a live glove that stopped would).

#include <cstddef>
#include <cstdint>
#include <vector>

#include "hand/glove_sample.hpp"
#include "hand/input_counts.hpp"
#include "physics_node/io/hand_feed.hpp"
#include "physics_node/io/input_timing.hpp"
#include "physics_node/io/replay_driver.hpp"
#include "physics_node/physics/world.hpp"

namespace vcockpit::physics_io {

// One hand's accepted samples (sorted, strictly increasing time, at least one) and the world's
// hand (index) they drive.
struct HandSamples {
  int hand = 0;
  std::vector<hand::GloveSample> samples;
};

class HandTimeline {
 public:
  // `hands` must outlive the timeline. The run ends at world time end_ns: with `past_samples`
  // (a --duration) at the first step that reaches it; without, at the last step that ends by it
  // (where a lockstep replay of the samples stops).
  HandTimeline(physics::World& world, const std::vector<HandSamples>& hands,
               const InputTiming& timing, int64_t end_ns, bool past_samples);

  // The earliest first sample's time (the source time of world time 0); the span from it to the
  // latest last sample (ns).
  static int64_t first_ns(const std::vector<HandSamples>& hands);
  static int64_t span_ns(const std::vector<HandSamples>& hands);

  // Runs the world to the end: `step()` steps it once (world.step() and whatever the caller
  // records around it).
  template <class Step>
  void run(Step&& step) {
    while (prepare_next_step()) step();
  }
  // Sets every hand's input for the next step; false once the run has ended.
  bool prepare_next_step();

  // Hand k's (in `hands` order) intervals and glove losses so far.
  const hand::InputCounts& counts(std::size_t k) const { return drivers_[k].counts(); }

 private:
  physics::World& world_;
  int64_t end_ns_;
  bool past_samples_;
  int64_t step_ns_;
  std::vector<ReplayDriver> drivers_;
  std::vector<HandFeed> feeds_;
};

}  // namespace vcockpit::physics_io
