#pragma once
// The physics node's stepping, the same in both modes (node_loop.cpp): before a step the
// commands from other nodes (cockpit/control_command; the world refuses a control or position it
// does not have, and a control a hand holds); the step, timed; then its events published and
// logged (faults, GRASP and RELEASE, CONTROL), the control frame published on its period
// (cockpit/control_frame), the lockstep --out recorder fed, the stages'
// times summed for node_status, and every --checkpoint-every of simulated time the world offered
// to the checkpoint writer. --resume starts the world from the newest checkpoint.

#include <array>
#include <cstdint>
#include <memory>

#include "cockpit.h"
#include "dds/dds_participant.hpp"
#include "physics_node/io/hand_motion_peak.hpp"
#include "physics_node/io/run_recorder.hpp"
#include "physics_node/io/world_checkpoint.hpp"
#include "physics_node/node/checkpoint_writer.hpp"
#include "physics_node/node/control_frame_publisher.hpp"
#include "physics_node/node/loop_stats.hpp"
#include "physics_node/node/node_loop.hpp"
#include "physics_node/node/sim_commands.hpp"
#include "physics_node/node/state_publisher.hpp"
#include "physics_node/physics/world.hpp"

namespace vcockpit::physics_node {

class WorldStepper {
 public:
  // With options.checkpoint_path: the checkpoints' folder is made and, with options.resume, the
  // world and the freeze are restored from the newest checkpoint (a damaged one is kept aside as
  // .bad, and the world starts from the scene). Throws std::runtime_error when the folder cannot
  // be made.
  WorldStepper(DdsParticipant& participant, physics::World& world, StatePublisher& publisher,
               SimCommands& sim, const NodeOptions& options);

  // One step: the commands, the step (its compute time to `stats`), its events and outputs.
  void step(LoopStats& stats);
  // The last step's (or reset's) events published and logged.
  void publish_events();
  // Every checkpoint_every_s of simulated time (or now, `force`): the world to the writer thread.
  void maybe_checkpoint(bool force = false);
  // At stop: the last world saved, and how saving went in the log.
  void finish_checkpoints();

  // Lockstep --out: trajectories.csv and events.jsonl as the offline runner writes them.
  bool recording() const { return recorder_ != nullptr; }
  // The first row, once the hands have their first samples (the offline runner's).
  void start_recording_once();
  void commit_recording();

  uint32_t grasps(int hand) const { return grasps_[static_cast<std::size_t>(hand)]; }
  const physics_io::HandMotionPeak& hand_peak() const { return hand_peak_; }
  uint64_t commands_refused() const { return commands_refused_; }
  const ControlFramePublisher& control_frames() const { return frames_; }
  ControlFramePublisher& control_frames() { return frames_; }

  // For node_status: the steps and their stages' summed times since the last take.
  uint64_t steps_in_period() const { return steps_in_period_; }
  const std::array<int64_t, physics::kStageCount>& stage_ns() const { return stage_ns_; }
  void clear_period();

 private:
  void take_commands();
  void resume_from_checkpoint();
  void log_events();

  const NodeOptions& options_;
  physics::World& world_;
  StatePublisher& publisher_;
  SimCommands& sim_;
  Reader<cockpit::ControlCommand> command_reader_;
  ControlFramePublisher frames_;
  cockpit::ControlCommand command_;
  uint64_t commands_refused_ = 0;
  std::array<uint32_t, physics::kMaxHands> grasps_{};  // per world hand
  physics_io::HandMotionPeak hand_peak_;
  uint64_t steps_in_period_ = 0;
  std::array<int64_t, physics::kStageCount> stage_ns_{};
  std::unique_ptr<physics_io::RunRecorder> recorder_;  // lockstep --out
  bool recording_started_ = false;
  std::unique_ptr<CheckpointWriter> checkpointer_;  // --checkpoint
  uint64_t fingerprint_ = 0;
  int64_t next_checkpoint_ns_ = 0;
  physics_io::Checkpoint checkpoint_;  // reused: a copy of the world's state
};

}  // namespace vcockpit::physics_node
