#include "physics_node/io/hand_input.hpp"

#include "hand/tracker.hpp"

namespace vcockpit::physics_io {

physics::HandInput hand_input_from_glove(const hand::HandModel& hand,
                                         const hand::GloveSample& sample) {
  physics::HandInput input;
  input.q_rad = sample.joints_rad;
  input.X_GH = hand::X_GH_from_sample(hand, sample);
  input.tracking = true;
  return input;
}

}  // namespace vcockpit::physics_io
