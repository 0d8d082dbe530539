#pragma once
// A validated glove sample -> the hand the physics sees: X_GH from the tracker (eqs. 26-27,
// hand/tracker.hpp) and the joint angles as the SampleValidator left them (clamped once there).

#include "hand/glove_sample.hpp"
#include "physics_node/physics/world.hpp"

namespace vcockpit::physics_io {

physics::HandInput hand_input_from_glove(const hand::HandModel& hand,
                                         const hand::GloveSample& sample);

}  // namespace vcockpit::physics_io
