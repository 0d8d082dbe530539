#pragma once
// How the recorded hand comes to a placed object before the chosen moment (grip_fit's scene: the
// object stands still on its pedestal until the hand takes it). A link deep in the object before
// the moment is a hand that sweeps through where the object stands, which in the simulator
// pushes it away instead of closing on it: grip_fit prefers placements the hand comes least
// deep into, and warns of one it passes through.

#include <Eigen/Geometry>

#include <cstdint>
#include <vector>

#include "hand/glove_sample.hpp"
#include "hand/hand_model.hpp"
#include "physics_node/fit/grip_hand.hpp"
#include "physics_node/physics/scene.hpp"

namespace vcockpit::fit {

struct RecordedHand {
  int64_t t_ns = 0;
  GripHand hand;
};

// The tracked hands of the samples before moment_index (the moment itself when it is the first).
std::vector<RecordedHand> hands_before(const hand::HandModel& model,
                                       const std::vector<hand::GloveSample>& samples,
                                       std::size_t moment_index);

struct HandApproach {
  double first_m = 0.0;    // the least link distance from the object at the first hand
  double nearest_m = 0.0;  // the least over all the hands (< 0: a link inside the object)
  int64_t nearest_t_ns = 0;
  hand::Link nearest_link = hand::Link::kPalm;
};

// Over `hands` (none: all zero).
HandApproach hand_approach(const std::vector<RecordedHand>& hands, const physics::Shape& shape,
                           const Eigen::Isometry3d& X_GO);

}  // namespace vcockpit::fit
