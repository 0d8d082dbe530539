#include "physics_node/io/hand_input.hpp"

namespace vcockpit::physics_io {

physics::HandInput hand_input_from_glove(const physics::HandModel& hand,
                                         const glove::GloveSample& sample) {
  physics::HandInput input;
  input.q_rad = sample.joints_rad;
  physics::clamp_to_limits(hand, input.q_rad);
  Eigen::Isometry3d X_MT = Eigen::Isometry3d::Identity();
  X_MT.linear() = sample.q_MT.normalized().toRotationMatrix();
  X_MT.translation() = sample.p_MT_m;
  input.X_GH = hand.tracker.X_GM * physics::X_MH_from_tracker(hand, X_MT, input.q_rad);
  input.tracking = true;
  return input;
}

}  // namespace vcockpit::physics_io
