#include "glove_driver/node/replay_commands.hpp"

#include <spdlog/spdlog.h>

#include "idl/topics/sim_ack_frozen.hpp"

namespace vcockpit::glove {

ReplayCommands::ReplayCommands(DdsParticipant& participant, std::string node_name)
    : reader_(participant.make_reader<cockpit::SimCommand>("command")),
      ack_writer_(participant.make_writer<cockpit::SimAck>("event")),
      ack_reader_(participant.make_reader<cockpit::SimAck>("event")),
      node_name_(std::move(node_name)) {}

bool ReplayCommands::take_restart(bool can_restart) {
  while (ack_reader_.take(ack_))
    if (const std::optional<bool> frozen = physics_frozen_after(ack_)) physics_frozen_ = *frozen;
  bool restart = false;
  while (reader_.take(command_)) {
    // A freeze or unfreeze is the physics node's to take; its answer may come after the
    // instructor's next command (another writer, no order between them), so the command itself
    // says first what time will do: an instructor's freeze, then restart, arrive in that order.
    if (command_.kind() == cockpit::FREEZE) physics_frozen_ = true;
    if (command_.kind() == cockpit::UNFREEZE) physics_frozen_ = false;
    if (command_.kind() != cockpit::RESTART_REPLAY) continue;  // the physics node's
    cockpit::SimAck ack;
    ack.command_seq(command_.seq());
    ack.command_source(command_.source());
    ack.kind(command_.kind());
    ack.node_name(node_name_);
    ack.accepted(can_restart);
    ack.detail(can_restart ? "the replay starts over from the log's start"
                           : "this source cannot start over (only a replayed log can)");
    ack.sim_time_ns(-1);
    ack.frozen(false);
    ack_writer_.write(ack);
    if (can_restart) {
      spdlog::info("sim command from '{}': the replay starts over", command_.source());
      restart = true;
      ++restarts_;
    } else {
      spdlog::warn("sim command from '{}' refused: this source cannot start over",
                   command_.source());
    }
  }
  return restart;
}

}  // namespace vcockpit::glove
