#pragma once
// The instructor's RESTART_REPLAY (cockpit/sim_command) as a glove driver takes it: each is
// answered on cockpit/sim_ack, refused for a source that cannot start over. The other commands
// are the physics node's and are left to it.

#include <cstdint>
#include <string>

#include "dds/dds_participant.hpp"

namespace vcockpit::glove {

class ReplayCommands {
 public:
  ReplayCommands(DdsParticipant& participant, std::string node_name);
  // Takes every pending command (no blocking); true when a restart was asked and `can_restart`.
  bool take_restart(bool can_restart);
  uint64_t restarts() const { return restarts_; }

 private:
  Reader<cockpit::SimCommand> reader_;
  Writer<cockpit::SimAck> ack_writer_;
  std::string node_name_;
  cockpit::SimCommand command_;
  uint64_t restarts_ = 0;
};

}  // namespace vcockpit::glove
