#pragma once
// A glove reading -> the hand the physics sees: X_GH = X_GM * X_MH (paper eq. 27), with X_MH from
// the tracker reading through the hand's tracker mounting (eq. 26), joints clamped into limits.

#include "glove_driver/glove/glove_sample.hpp"
#include "physics_node/physics/world.hpp"

namespace vcockpit::physics_io {

physics::HandInput hand_input_from_glove(const physics::HandModel& hand,
                                         const glove::GloveSample& sample);

}  // namespace vcockpit::physics_io
