#pragma once
// hand::HandModel <-> cockpit::HandInfo: the hand's collision geometry only (side, the phalanx
// capsules, the palm box). Joint ranges, DH chains and the tracker mounting stay with the nodes
// that load hand.yaml; a node that only draws the hand (the image generator) needs nothing else.

#include <cstdint>

#include "cockpit.h"
#include "hand/hand_model.hpp"

namespace vcockpit {

// `hand_id` is the key the hand's HandState carries (0 right, 1 left).
cockpit::HandInfo to_hand_info(const hand::HandModel& model, uint32_t hand_id);

// A model with the geometry of `info` (left, capsules, X_HP, palm_size_m) and every other field
// default: no DH chains and no joint ranges, so it draws a hand but cannot pose one.
hand::HandModel from_hand_info(const cockpit::HandInfo& info);

// True when every size is finite, no capsule is negative and the palm box has positive extents:
// what a receiver checks before drawing with a HandInfo from another process.
bool hand_info_sizes_valid(const cockpit::HandInfo& info);

}  // namespace vcockpit
