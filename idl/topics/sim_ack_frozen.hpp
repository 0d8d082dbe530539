#pragma once
// Whether the physics node's time is frozen, read from a cockpit/sim_ack. The physics node's
// answer to FREEZE or UNFREEZE says so (accepted or not: a freeze of a frozen world is refused,
// and says frozen). Only those are read: the systems node also answers RESET_TO_START with a world
// time and `frozen` false (it does not know), and glove drivers answer with no world time (-1).

#include <optional>

#include "cockpit.h"

namespace vcockpit {

inline std::optional<bool> physics_frozen_after(const cockpit::SimAck& ack) {
  if (ack.sim_time_ns() < 0) return std::nullopt;
  if (ack.kind() != cockpit::FREEZE && ack.kind() != cockpit::UNFREEZE) return std::nullopt;
  return ack.frozen();
}

}  // namespace vcockpit
