#pragma once
// A fingerprint of a WorldState for determinism tests (Box2D's and Jolt's golden state hash):
// FNV-1a 64 over every field in visit_world_state's order (world_state_fields.hpp), lengths
// included. Each number is fed as 8 bytes, least significant first: a double as its IEEE-754
// binary64 bits (so -0.0 and 0.0 differ, and so do NaNs with different payloads), an integer or
// bool widened to 64 bits (two's complement; a bool is 0 or 1).

#include <cstdint>

#include "physics_node/physics/world_state.hpp"

namespace vcockpit::physics {

uint64_t hash_world_state(const WorldState& state);

}  // namespace vcockpit::physics
