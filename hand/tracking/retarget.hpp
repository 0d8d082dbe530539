#pragma once
// Retargeting: tracked hand joints (OpenXR's set) to the DH hand's glove channels and wrist pose,
// so a hand-tracking recording or a live tracker drives the rig as a glove does.
//
// Each frame, in the hand's world frame G:
//   1. the hand frame H from the palm: a weighted Kabsch fit of the model's palm points (the
//      tracker's palm joint, HandModel::p_H_palm_joint; the four knuckles, the thumb's base, the wrist) to the tracked ones that are valid
//      (at least three). It needs no joint orientation, so a tracker that gives positions only
//      (MediaPipe's landmarks) works the same; a model of the other side's hand is refused.
//   2. each finger's channels by damped Gauss-Newton (Levenberg-Marquardt) on the positions of
//      its joints beyond the knuckle and its tip, the tip weighted double ("fingertips first"),
//      in H, relative to the knuckle and scaled by the model's over the tracked finger's length
//      (so an uncalibrated hand still takes the tracked finger's shape), within the joints'
//      ranges, warm-started from the previous frame with a small pull toward it (a 10 deg change
//      costs as much as 1 mm of fit): smooth in time, no flips between solutions. The fingers
//      are fitted thumb to little; the little finger's chain starts on the ring's abduction, so
//      the ring goes first. The palm arch and the wrist channels stay at rest.
//   3. a finger none of whose joints beyond the knuckle is valid keeps its last angles; a frame
//      whose palm cannot be placed keeps the last hand (the sample is marked so).
// Deterministic: the same frames in the same order give the same bits. No allocation per frame.

#include <Eigen/Geometry>

#include <array>

#include "hand/glove_sample.hpp"
#include "hand/hand_model.hpp"
#include "hand/tracking/joints_log.hpp"

namespace vcockpit::hand::tracking {

struct RetargetOptions {
  int max_iterations = 20;
  double tip_weight = 2.0;
  // the pull toward the previous frame's angles: m of fit per rad of change
  double smoothing_m_per_rad = 0.001 / (10.0 * 3.14159265358979323846 / 180.0);
};

struct RetargetResult {
  bool placed = false;  // the palm was placed this frame (false: the last hand is kept)
  Eigen::Isometry3d X_GH = Eigen::Isometry3d::Identity();
  JointAngles q_rad{};
  // per finger: the distance of the fitted tip from the tracked one (m); -1 when not tracked
  std::array<double, kFingerCount> tip_error_m{};
};

class Retargeter {
 public:
  explicit Retargeter(const HandModel& model, const RetargetOptions& options = {});

  // Fits one frame whose positions are in G (to_cockpit). Its side must be the model's.
  const RetargetResult& fit(const JointsFrame& frame_G);
  // Forgets the previous frame (a new recording, or the hand was lost for long).
  void reset();

  // The glove sample that gives this hand (the wrist tracker's reading through the model's
  // mounting, eqs. 26-27 inverted).
  GloveSample glove_sample(int64_t t_ns) const;

 private:
  bool place_palm(const JointsFrame& frame);
  void fit_finger(Finger finger, const JointsFrame& frame, const Eigen::Isometry3d& X_HG);

  const HandModel& model_;
  RetargetOptions options_;
  RetargetResult result_;
  bool have_previous_ = false;
  HandLinkPoses poses_;
};

// A frame's positions and orientations moved into G: X_GS is the tracking space in G.
JointsFrame to_cockpit(const JointsFrame& frame, const Eigen::Isometry3d& X_GS);

// The rotation from the `xr` space (x right, y up, z toward the user) to G (x forward, y left,
// z up).
Eigen::Matrix3d R_G_xr();

}  // namespace vcockpit::hand::tracking
