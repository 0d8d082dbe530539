#pragma once
// What the physics node says about itself, the same in both modes (node_loop.cpp):
// cockpit/node_status about once a second (rates, input counts, each hand's tracking and grasps,
// late steps, the stages' mean times), and at stop the latency and input lines of the log and
// the --stats-out file.

#include <cstdint>

#include "physics_node/node/hand_channels.hpp"
#include "physics_node/node/loop_stats.hpp"
#include "physics_node/node/node_loop.hpp"
#include "physics_node/node/state_publisher.hpp"
#include "physics_node/node/world_stepper.hpp"
#include "physics_node/physics/world.hpp"

namespace vcockpit::physics_node {

class NodeStatusReporter {
 public:
  NodeStatusReporter(const NodeOptions& options, const physics::World& world,
                     const HandChannels& hands, WorldStepper& stepper, StatePublisher& publisher);

  // The time spent publishing the world, for the status's publish stage.
  void add_publish_ns(int64_t ns) { publish_ns_ += ns; }
  // Once a second of wall time: node_status with `detail` ("tracking", "lockstep, waiting", ..)
  // and `late_steps` (real time; 0 in lockstep).
  void maybe_publish(int64_t now_ns, bool alive, const char* detail, uint64_t late_steps);
  // At stop: the log's figures, and the --stats-out file. `report` has the mode's own fields;
  // the steps of this run (a resumed world's earlier ones not counted), samples and input are
  // filled here.
  void report_stop(StatsReport report, uint64_t steps_this_run, const LoopStats& stats) const;

 private:
  const NodeOptions& options_;
  const physics::World& world_;
  const HandChannels& hands_;
  WorldStepper& stepper_;
  StatePublisher& publisher_;
  uint64_t received_at_last_status_ = 0;
  int64_t publish_ns_ = 0;
  int64_t last_status_ns_ = 0;
};

// Real time: node_status's detail — "frozen", "no glove yet", "glove lost" (every hand with
// input lost), "tracking", or which hand's glove is lost.
void realtime_status_detail(const HandChannels& hands, bool frozen, char* out, std::size_t size);

}  // namespace vcockpit::physics_node
