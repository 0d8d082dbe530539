#pragma once
// The instructor's commands to the simulation (cockpit/sim_command), as the physics node takes
// them: freeze and unfreeze time, put the objects and controls back to the scene's start or to
// a named checkpoint (World::reset_objects: time goes on, the hands stay with their gloves), and
// save such a checkpoint. Each is logged and answered on cockpit/sim_ack, refusals with why.
// RESTART_REPLAY is the glove drivers' and is left to them. Checkpoints live as long as the
// node, at most kMaxCheckpoints of them.

#include <cstdint>
#include <map>
#include <string>

#include "dds/dds_participant.hpp"
#include "physics_node/physics/world.hpp"

namespace vcockpit::physics_node {

class SimCommands {
 public:
  static constexpr std::size_t kMaxCheckpoints = 16;

  // `world` as the scene starts it: what RESET_TO_START puts back.
  SimCommands(DdsParticipant& participant, const physics::World& world, std::string node_name);

  // What the loop must do after take().
  struct Taken {
    bool reset = false;     // the objects were put back: publish their events and the world now
    bool reset_to_start = false;  // ... to the scene's start (the aircraft's systems start again)
    bool unfrozen = false;  // time goes on again: the hands follow their gloves from now
  };
  // Takes every pending command (no blocking).
  Taken take(physics::World& world);

  bool frozen() const { return frozen_; }
  // a resumed node: frozen as its checkpoint was
  void restore_frozen(bool frozen) { frozen_ = frozen; }
  uint64_t refused() const { return refused_; }

 private:
  // Carries out one command; returns the acknowledgement's detail, accepted or not.
  bool apply(const cockpit::SimCommand& command, physics::World& world, Taken& taken,
             std::string& detail);

  Reader<cockpit::SimCommand> reader_;
  Writer<cockpit::SimAck> ack_writer_;
  std::string node_name_;
  physics::WorldState start_;
  std::map<std::string, physics::WorldState> checkpoints_;
  bool frozen_ = false;
  uint64_t refused_ = 0;
  cockpit::SimCommand command_;
};

const char* sim_command_name(cockpit::SimCommandKind kind);

}  // namespace vcockpit::physics_node
