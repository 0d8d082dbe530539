#pragma once
// The instructor's RESTART_REPLAY (cockpit/sim_command) as a glove driver takes it: each is
// answered on cockpit/sim_ack, refused for a source that cannot start over. The other commands
// are the physics node's and are left to it; the freezes and unfreezes, and the physics node's
// answers to them, say whether its time is frozen, so that a replay restarted while frozen
// starts when time goes on (run_publisher).

#include <cstdint>
#include <string>

#include "dds/dds_participant.hpp"

namespace vcockpit::glove {

class ReplayCommands {
 public:
  ReplayCommands(DdsParticipant& participant, std::string node_name);
  // Takes every pending command and acknowledgement (no blocking); true when a restart was
  // asked and `can_restart`.
  bool take_restart(bool can_restart);
  uint64_t restarts() const { return restarts_; }
  // The physics node's time is frozen, as the latest freeze or unfreeze taken says: the
  // instructor's command, or the physics node's answer to one (false before any: a driver
  // started after a freeze does not know of it).
  bool physics_frozen() const { return physics_frozen_; }

 private:
  Reader<cockpit::SimCommand> reader_;
  Writer<cockpit::SimAck> ack_writer_;
  Reader<cockpit::SimAck> ack_reader_;
  std::string node_name_;
  cockpit::SimCommand command_;
  cockpit::SimAck ack_;
  uint64_t restarts_ = 0;
  bool physics_frozen_ = false;
};

}  // namespace vcockpit::glove
