#pragma once
// One reading of the glove and the wrist tracker, as the glove library handles it: time in
// integer nanoseconds (no drift over long logs), tracker pose X_MT as position + quaternion, and
// the 22 calibrated joint angles.

#include <Eigen/Geometry>

#include <cstdint>

#include "hand/hand_joints.hpp"

namespace vcockpit::hand {

struct GloveSample {
  int64_t t_ns = 0;                                         // the source's timeline
  Eigen::Vector3d p_MT_m = Eigen::Vector3d::Zero();          // tracker position in frame M
  Eigen::Quaterniond q_MT = Eigen::Quaterniond::Identity();  // tracker orientation, M <- T
  hand::JointAngles joints_rad{};                         // Joint order
};

// Log time (seconds, as written in t_s) <-> nanoseconds, exactly invertible for printed %.17g.
int64_t log_seconds_to_ns(double t_s);
double ns_to_log_seconds(int64_t t_ns);

}  // namespace vcockpit::hand
