#include "hand/tracker.hpp"

namespace vcockpit::hand {

Eigen::Isometry3d X_MH_from_tracker(const HandModel& model, const Eigen::Isometry3d& X_MT,
                                    const JointAngles& q) {
  if (model.tracker.mount == TrackerMount::kBackOfHand) return X_MT;
  const double yaw_rad = (model.left ? -1.0 : 1.0) * q[static_cast<int>(Joint::kWristYaw)];
  const double pitch_rad = q[static_cast<int>(Joint::kWristPitch)];
  Eigen::Isometry3d X_TH = Eigen::Isometry3d::Identity();
  X_TH.linear() = (Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()) *
                   Eigen::AngleAxisd(pitch_rad, Eigen::Vector3d::UnitY()))
                      .toRotationMatrix();
  return X_MT * X_TH;
}

Eigen::Isometry3d X_GH_from_sample(const HandModel& model, const GloveSample& sample) {
  Eigen::Isometry3d X_MT = Eigen::Isometry3d::Identity();
  X_MT.linear() = sample.q_MT.normalized().toRotationMatrix();
  X_MT.translation() = sample.p_MT_m;
  return model.tracker.X_GM * X_MH_from_tracker(model, X_MT, sample.joints_rad);
}

}  // namespace vcockpit::hand
