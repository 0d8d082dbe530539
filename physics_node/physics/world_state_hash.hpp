#pragma once
// A fingerprint of a WorldState for determinism tests (Box2D's and Jolt's golden state hash):
// FNV-1a 64 over the bit patterns of every number in the state, in this fixed order:
//   time_ns, steps, substeps;
//   the body count, then per body: X_GO, v_G, w_G, held_by;
//   hand_active; hand_from and hand_to, each: X_GH, the joint count and q_rad, tracking;
//   X_GH; the link count and each X_GL;
//   the grasp count, then per object: X_HO, held_since_ns, failing_since_ns, released_at_ns,
//     history_next, history_count, the ring's size and every pose in it (stale ones too);
//   the anchor count, then per anchor: body_a, body_b, p_A, r_A, r_B, sticking.
// A pose is its 3x4 [R | p], column by column (12 numbers); a vector its x, y, z. Each number is
// fed as 8 bytes, least significant first: a double as its IEEE-754 binary64 bits (so -0.0 and
// 0.0 differ, and so do NaNs with different payloads), an integer or bool widened to 64 bits
// (two's complement; a bool is 0 or 1).

#include <cstdint>

#include "physics_node/physics/world_state.hpp"

namespace vcockpit::physics {

uint64_t hash_world_state(const WorldState& state);

}  // namespace vcockpit::physics
