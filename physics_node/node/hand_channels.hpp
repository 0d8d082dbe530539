#pragma once
// The physics node's input: cockpit/hand_sample taken from DDS and sent to the world's hand of
// its hand_id (a hand the scene has not is ignored and counted). Each hand has its own gate,
// timeline (lockstep: a replay driver fed by a HandFeed, as the offline runner; real time: an
// input follower), source and glove liveliness, so one glove lost leaves the other hand working.
// A different writer (a restarted glove driver) starts its hand's own timeline: time order is
// checked per source. Used by both of the node's modes (node_loop.cpp).

#include <cstdint>
#include <vector>

#include "cockpit.h"
#include "common/clock.hpp"
#include "dds/dds_participant.hpp"
#include "hand/glove_sample.hpp"
#include "hand/input_counts.hpp"
#include "physics_node/io/hand_feed.hpp"
#include "physics_node/io/input_follower.hpp"
#include "physics_node/io/replay_driver.hpp"
#include "physics_node/node/loop_stats.hpp"
#include "physics_node/node/node_loop.hpp"
#include "physics_node/node/sample_gate.hpp"
#include "physics_node/physics/world.hpp"

namespace vcockpit::physics_node {

// One hand's input.
struct HandChannel {
  HandChannel(physics::World& world, int hand_index, const NodeOptions& options);
  int hand;
  const hand::HandModel& model;
  SampleGate gate;
  physics_io::ReplayDriver replay;      // lockstep: the world advanced to each sample's stamp
  physics_io::InputFollower follower;  // real time: the hand a small delay behind the samples
  bool expected = false;               // lockstep: the world waits for this hand's samples
  dds::InstanceHandle_t source;
  bool have_source = false;
  uint64_t received = 0;
  int64_t last_sample_wall_ns = 0;
  uint64_t glove_lost = 0;             // real time (lockstep: the replay driver counts)
  bool tracking = false;
  bool have_input = false;
  physics::HandInput input;
  // lockstep: samples received and not yet given to the replay driver (it takes each as the
  // world reaches it, by the offline runner's rule)
  physics_io::HandFeed feed;
  bool arrived_frozen = false;  // lockstep: samples came while time was frozen
};

class HandChannels {
 public:
  HandChannels(DdsParticipant& participant, physics::World& world, const NodeOptions& options);

  // Takes every pending sample; the accepted ones go to `on_sample(channel, sample, new_source,
  // take_ns)` (source_stamp_ns() of the message taken says when it left its source), their
  // latencies to `stats`. No allocation.
  template <class OnSample>
  void drain(LoopStats& stats, OnSample on_sample) {
    drain_while(stats, on_sample, [] { return true; });
  }
  // The same, while `more()` says so: what is left waits in DDS (lockstep: a reliable keep-all
  // reader that is not taken from holds its writer back).
  template <class OnSample, class More>
  void drain_while(LoopStats& stats, OnSample on_sample, More more) {
    dds::SampleInfo info;
    while (more() && reader_.take(message_, &info)) {
      const int64_t take_ns = monotonic_now_ns();
      HandChannel* ch = accept(info);
      if (ch == nullptr) continue;
      stats.record_sample(info, message_.source_stamp_ns(), take_ns);
      ch->last_sample_wall_ns = take_ns;
      on_sample(*ch, sample_, new_source_, take_ns);
    }
  }
  // Lockstep: some hand has at least `count` samples queued that the world has not taken.
  bool any_feed_holds(std::size_t count) const {
    for (const HandChannel& ch : channels_)
      if (ch.feed.queued_count() >= count) return true;
    return false;
  }
  // Lockstep: waits up to `timeout_ns` for samples; false when none came.
  bool wait_for_data(int64_t timeout_ns) { return reader_.wait_for_data(timeout_ns); }
  int64_t source_stamp_ns() const { return message_.source_stamp_ns(); }

  // Real time: a glove is alive while its samples come within the glove timeout of wall time
  // and its writer is alive.
  bool glove_alive(const HandChannel& ch, int64_t now_ns) const;
  bool any_alive(int64_t now_ns) const;
  // Real time: each hand's tracking from its glove's liveliness now, a change logged (a glove
  // lost is counted); true when any glove is alive.
  bool track_gloves(int64_t now_ns);

  // Everything counted about the input so far: the gate's, the timing's (follower in real time,
  // replay driver in lockstep), glove lost.
  hand::InputCounts counts(const HandChannel& ch) const;
  hand::InputCounts counts() const;
  uint64_t received() const { return received_; }
  uint64_t rejected() const;
  const char* side_name(int hand) const;

  std::vector<HandChannel>::iterator begin() { return channels_.begin(); }
  std::vector<HandChannel>::iterator end() { return channels_.end(); }
  std::vector<HandChannel>::const_iterator begin() const { return channels_.begin(); }
  std::vector<HandChannel>::const_iterator end() const { return channels_.end(); }
  std::size_t size() const { return channels_.size(); }
  HandChannel& front() { return channels_.front(); }
  const HandChannel& front() const { return channels_.front(); }

 private:
  // The channel of message_, its sample checked into sample_ (new_source_ set); null when it is
  // refused.
  HandChannel* accept(const dds::SampleInfo& info);

  const NodeOptions& options_;
  const physics::World& world_;
  Reader<cockpit::HandSample> reader_;
  std::vector<HandChannel> channels_;  // per world hand
  cockpit::HandSample message_;
  hand::GloveSample sample_;
  bool new_source_ = false;
  uint64_t received_ = 0;
  uint64_t unknown_hand_ = 0;  // samples for a hand the scene has not
};

}  // namespace vcockpit::physics_node
