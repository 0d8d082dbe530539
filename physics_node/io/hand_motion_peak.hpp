#pragma once
// The fastest the simulated hand moved from one step to the next: the wrist's speed (m/s) and the
// fastest joint (rad/s). A sample applied within one step shows up here as a spike (a 33 Hz log
// held and jumped moved the hand 30x faster than the recorded motion); interpolation removes it.
// The offline summary and the real-time node's statistics report it.

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "physics_node/physics/world.hpp"

namespace vcockpit::physics_io {

class HandMotionPeak {
 public:
  // After each step.
  void record(const physics::World& world) {
    if (!world.hand_active()) return;
    const Eigen::Vector3d p_m = world.X_GH().translation();
    const auto& q_rad = world.state().hands[0].to.q_rad;
    const int64_t t_ns = world.time_ns();
    if (have_last_ && t_ns > last_t_ns_) {
      const double dt_s = static_cast<double>(t_ns - last_t_ns_) * 1e-9;
      wrist_mps_ = std::max(wrist_mps_, (p_m - last_p_m_).norm() / dt_s);
      for (std::size_t j = 0; j < q_rad.size(); ++j) {
        joint_radps_ = std::max(joint_radps_, std::abs(q_rad[j] - last_q_rad_[j]) / dt_s);
      }
    }
    last_p_m_ = p_m;
    last_q_rad_ = q_rad;
    last_t_ns_ = t_ns;
    have_last_ = true;
  }
  double wrist_mps() const { return wrist_mps_; }
  double joint_radps() const { return joint_radps_; }

 private:
  Eigen::Vector3d last_p_m_ = Eigen::Vector3d::Zero();
  physics::JointAngles last_q_rad_{};
  int64_t last_t_ns_ = 0;
  bool have_last_ = false;
  double wrist_mps_ = 0.0;
  double joint_radps_ = 0.0;
};

}  // namespace vcockpit::physics_io
