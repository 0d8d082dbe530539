#include "physics_node/node/sim_commands.hpp"

#include <spdlog/spdlog.h>

#include <cstdio>

#include "common/clock.hpp"

namespace vcockpit::physics_node {

const char* sim_command_name(cockpit::SimCommandKind kind) {
  switch (kind) {
    case cockpit::FREEZE: return "freeze";
    case cockpit::UNFREEZE: return "unfreeze";
    case cockpit::RESET_TO_START: return "reset to start";
    case cockpit::SAVE_CHECKPOINT: return "save checkpoint";
    case cockpit::RESET_TO_CHECKPOINT: return "reset to checkpoint";
    case cockpit::RESTART_REPLAY: return "restart replay";
  }
  return "unknown";
}

SimCommands::SimCommands(DdsParticipant& participant, const physics::World& world,
                         std::string node_name)
    : reader_(participant.make_reader<cockpit::SimCommand>("command")),
      ack_writer_(participant.make_writer<cockpit::SimAck>("event")),
      node_name_(std::move(node_name)),
      start_(world.state()) {}

SimCommands::Taken SimCommands::take(physics::World& world) {
  Taken taken;
  while (reader_.take(command_)) {
    if (command_.kind() == cockpit::RESTART_REPLAY) continue;  // the glove drivers'
    std::string detail;
    const bool accepted = apply(command_, world, taken, detail);
    if (accepted) {
      spdlog::info("sim command from '{}': {}", command_.source(), detail);
    } else {
      ++refused_;
      spdlog::warn("sim command from '{}' refused: {}", command_.source(), detail);
    }
    cockpit::SimAck ack;
    ack.command_seq(command_.seq());
    ack.command_source(command_.source());
    ack.kind(command_.kind());
    ack.node_name(node_name_);
    ack.accepted(accepted);
    ack.detail(detail.substr(0, 128));
    ack.sim_time_ns(world.time_ns());
    ack.frozen(frozen_);
    ack_writer_.write(ack);
  }
  return taken;
}

bool SimCommands::apply(const cockpit::SimCommand& command, physics::World& world, Taken& taken,
                        std::string& detail) {
  const std::string given = command.checkpoint().to_string();
  const std::string name = given.empty() ? "default" : given;
  char at[48];
  std::snprintf(at, sizeof at, "%.3f s", ns_to_seconds(world.time_ns()));
  switch (command.kind()) {
    case cockpit::FREEZE:
      detail = frozen_ ? std::string("already frozen at ") + at : std::string("frozen at ") + at;
      frozen_ = true;
      return true;
    case cockpit::UNFREEZE:
      detail = frozen_ ? std::string("time goes on from ") + at : std::string("not frozen");
      taken.unfrozen = taken.unfrozen || frozen_;
      frozen_ = false;
      return true;
    case cockpit::RESET_TO_START:
      world.reset_objects(start_);
      taken.reset = true;
      taken.reset_to_start = true;
      detail = std::string("objects and controls back to the start at ") + at;
      return true;
    case cockpit::SAVE_CHECKPOINT:
      if (checkpoints_.count(name) == 0 && checkpoints_.size() >= kMaxCheckpoints) {
        detail = "checkpoint '" + name + "' not saved: " + std::to_string(kMaxCheckpoints) +
                 " checkpoints already (save over one of them)";
        return false;
      }
      checkpoints_[name] = world.state();
      detail = "checkpoint '" + name + "' saved at " + at;
      return true;
    case cockpit::RESET_TO_CHECKPOINT: {
      const auto it = checkpoints_.find(name);
      if (it == checkpoints_.end()) {
        detail = "no checkpoint '" + name + "'";
        return false;
      }
      world.reset_objects(it->second);
      taken.reset = true;
      char saved[48];
      std::snprintf(saved, sizeof saved, "%.3f s", ns_to_seconds(it->second.time_ns));
      detail = "objects and controls back to checkpoint '" + name + "' (saved at " + saved +
               ") at " + at;
      return true;
    }
    case cockpit::RESTART_REPLAY:
      break;
  }
  detail = "unknown command " + std::to_string(static_cast<int>(command.kind()));
  return false;
}

}  // namespace vcockpit::physics_node
