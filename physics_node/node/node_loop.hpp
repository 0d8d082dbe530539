#pragma once
// physics_node over DDS.
//
// Real time: steps at a fixed rate (1 kHz default) on the monotonic clock, publishes the world
// at --publish-hz (90 default) and node_status once a second. Each step's hand is the source's
// hand a small, rate-adaptive delay ago, interpolated between the samples around it
// (physics_io::InputFollower: about one sample interval + 2 ms; --input-delay fixes it, 0 = the
// newest sample at once); the hand's lag behind its source is measured (hand_lag).
// A step that ends after its slot is counted late; steps are never skipped silently: a node that
// fell behind runs them back to back, and only beyond kMaxCatchUpSteps does it resynchronise,
// counting every step it dropped as late and saying so in the log and the status.
//
// Samples go to the world's hand of their hand_id (a hand the scene has not is ignored and
// counted); each hand has its own gate, timeline and glove liveliness, so one glove lost leaves
// the other hand working.
//
// Lockstep: the world advances to each sample's stamp (world time 0 = the first sample) with each
// hand interpolated between its samples, exactly as the offline runner does with the same logs
// (physics_io::ReplayDriver per hand, one timeline), so a lockstep replay gives the same result.
// With two glove drivers, --lockstep-hands makes every step wait for both. It
// publishes at --publish-hz of simulated time, and when it has caught up with its input at most
// at --publish-hz of wall time (a replay at its own pace would otherwise publish every sample)
// and at once when the input pauses or ends.
//
// Gaps between samples longer than --max-gap are not bridged: the hand holds the earlier sample.
// Glove lost (real time: no sample for --glove-timeout of wall time, or the writer's liveliness
// lost; lockstep, as offline: the samples' timeline has none for that long): the hand stays
// where it was, held objects are released ("glove lost"), the status says so; samples resume ->
// tracking resumes. Input counts (hand::InputCounts) go to node_status and the stop log.
//
// With --checkpoint the world is saved as it runs, and --resume starts from the newest save
// (physics_io::world_checkpoint, checkpoint_writer.hpp).
//
// Both modes measure their input latency and step cost (loop_stats.hpp), print them when they
// stop and, with `stats_out`, write them to a JSON file.

#include <optional>
#include <string>
#include <vector>

#include "dds/dds_participant.hpp"
#include "physics_node/io/input_timing.hpp"
#include "physics_node/physics/scene.hpp"

namespace vcockpit::physics_node {

struct NodeOptions {
  bool lockstep = false;
  double rate_hz = 1000.0;
  double publish_hz = 90.0;
  double control_frame_hz = 100.0;  // cockpit/control_frame per second of world time (0: none)
  // lockstep: before the first step, wait (at most 30 s) for this many control_frame readers (a
  // systems node), so that none misses the first frames
  int wait_frame_readers = 0;
  physics_io::InputTiming timing;         // --max-gap, --glove-timeout
  std::optional<double> input_delay_s;    // real time: fixed interpolation delay (none: adaptive)
  std::string node_name = "physics_node";
  double duration_s = 0.0;  // stop by itself after this much real time (0: only on a signal)
  std::string stats_out;    // JSON file of loop statistics written at stop (empty: none)
  // lockstep: write trajectories.csv and events.jsonl here as the offline runner does (empty:
  // none), committed at stop
  std::string out_dir;
  double output_hz = 100.0;
  // lockstep: the hands (ids: 0 right, 1 left) whose samples every step waits for, one glove
  // driver each; empty: whichever hands have sent samples
  std::vector<int> lockstep_hands;
  // Surviving kill -9: the world (bodies, controls, grasps, time) is saved to checkpoint_path
  // every checkpoint_every_s of simulated time, on a freeze or unfreeze and at stop, written
  // whole or not at all (empty: never saved).
  std::string checkpoint_path;
  double checkpoint_every_s = 0.5;
  // Start from checkpoint_path's world when there is one (the rig's restart of a killed node):
  // objects, controls and grasps as they were, time going on from the checkpoint's; the hands
  // take up their gloves from the first sample. No file: the scene's start; a damaged file or
  // another scene's: an error in the log, the file kept as <path>.bad, the scene's start.
  bool resume = false;
};

constexpr int kMaxCatchUpSteps = 100;

// Runs until SIGINT/SIGTERM or for `duration_s`. Returns the process exit code.
int run_node(DdsParticipant& participant, physics::Scene scene, const NodeOptions& options);

}  // namespace vcockpit::physics_node
