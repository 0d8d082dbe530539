#pragma once
// Where the hand is, from the wrist tracker (paper eqs. 26-27):
//   eq. 26  X_MT from the tracker's reading (x, y, z and an orientation) in its measurement frame M;
//           the palm H relative to the tracker T: identity when the tracker is on the back of the
//           hand, the wrist pitch and yaw channels when it is on the forearm (X_MH = X_MT X_TH);
//   eq. 27  X_GH = X_GM X_MH, with X_GM the tracker's mounting in the world (hand.yaml).

#include <Eigen/Geometry>

#include "hand/glove_sample.hpp"
#include "hand/hand_model.hpp"

namespace vcockpit::hand {

// Palm pose relative to the tracker's measurement frame for the tracker pose X_MT (eq. 26).
Eigen::Isometry3d X_MH_from_tracker(const HandModel& model, const Eigen::Isometry3d& X_MT,
                                    const JointAngles& q);

// The hand in the world for a sample (eqs. 26-27). The sample's joints are used as they are
// (SampleValidator has clamped them).
Eigen::Isometry3d X_GH_from_sample(const HandModel& model, const GloveSample& sample);

}  // namespace vcockpit::hand
