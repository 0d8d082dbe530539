#pragma once
// The kinematic hand of paper §3: a Denavit–Hartenberg chain per finger (eq. 1, chained as
// eqs. 8–10), glove channel ranges, collision geometry, and where the wrist tracker sits.
//
// Hand frame H (right hand): origin at the wrist sensor, +x along the middle finger toward the
// fingertips, +y toward the thumb side, +z out of the back of the hand; the palm faces -z, so
// flexion moves fingertips toward -z. A left hand is the mirror image in the xz plane.
//
// Link frame L of a phalanx: origin at its proximal joint, +x along the phalanx toward the tip;
// its collision capsule is the segment [0, length] on x_L swept by the radius.

#include <Eigen/Geometry>

#include <array>
#include <string>
#include <vector>

#include "hand/hand_joints.hpp"

namespace vcockpit::hand {

// Range of one glove channel (rad). Samples are clamped into [min, max] (and counted).
struct JointRange {
  double rest_rad = 0.0;
  double min_rad = 0.0;
  double max_rad = 0.0;
};

// One row of paper eq. 1: T(i-1, i) from alpha, a, d and theta.
struct DhRow {
  double alpha_rad = 0.0;
  double a_m = 0.0;
  double d_m = 0.0;
  double theta_offset_rad = 0.0;
  int joint = -1;      // glove channel (Joint index) driving theta; -1: theta = theta_offset
  double scale = 1.0;  // theta = theta_offset + scale * q[joint]
  int link = -1;       // Link whose proximal joint frame this row's output defines; -1 none
};

struct FingerChain {
  Eigen::Isometry3d X_HB = Eigen::Isometry3d::Identity();  // chain base (frame 0) in H
  std::vector<DhRow> rows;                                  // palm -> root -> middle -> tip
};

struct Capsule {
  double radius_m = 0.0;
  double length_m = 0.0;
};

enum class TrackerMount { kBackOfHand, kForearm };

struct TrackerConfig {
  std::string euler_axes = "zyx";                           // (psi, theta, gamma) convention
  Eigen::Isometry3d X_GM = Eigen::Isometry3d::Identity();  // measurement frame in world (eq. 27)
  TrackerMount mount = TrackerMount::kBackOfHand;
};

struct HandModel {
  bool left = false;
  std::array<JointRange, kJointCount> joints{};
  std::array<FingerChain, kFingerCount> fingers{};
  std::array<Capsule, kLinkCount> capsules{};  // per phalanx; the palm entry is unused
  Eigen::Isometry3d X_HP = Eigen::Isometry3d::Identity();  // palm box centre in H
  Eigen::Vector3d palm_size_m = Eigen::Vector3d::Zero();    // palm box full extents
  // Where a hand tracker's palm joint lies in H (hand.yaml palm.tracking_point; by default the
  // palm box's centre): retargeting's anchor, which a calibration measures (hand/tracking/).
  Eigen::Vector3d p_H_palm_joint = Eigen::Vector3d::Zero();
  // ... and its wrist joint (palm.wrist_tracking_point; by default H's origin).
  Eigen::Vector3d p_H_wrist_joint = Eigen::Vector3d::Zero();
  TrackerConfig tracker;

  JointAngles rest_pose() const;
};

// Link poses in the hand frame, and fingertips (distal capsule ends).
struct HandLinkPoses {
  std::array<Eigen::Isometry3d, kLinkCount> X_HL;
  std::array<Eigen::Vector3d, kFingerCount> p_H_tip;
};

// Forward kinematics (eq. 1 per row, product along each chain). No allocation; angles are used
// as given (clamp first with clamp_to_limits).
void forward_kinematics(const HandModel& model, const JointAngles& q, HandLinkPoses& out);
// The same for one finger: its three links and its tip; the rest of `out` is left as it was
// (the proxy's probes move one finger's joints at a time).
void finger_kinematics(const HandModel& model, Finger finger, const JointAngles& q,
                       HandLinkPoses& out);

// One finger's chain at one q, kept so that a change of one joint re-poses only what it moves
// (the proxy's finite-difference Jacobian probes each joint in turn): each row's frame before it
// and its theta's cosine and sine, and the finger's links and tip.
struct FingerChainCache {
  static constexpr int kMaxRows = 16;  // (hand.yaml allows no more per finger)
  Finger finger = Finger::kThumb;
  std::array<Eigen::Matrix3d, kMaxRows> R_before;
  std::array<Eigen::Vector3d, kMaxRows> p_before;
  std::array<double, kMaxRows> cos_theta{};
  std::array<double, kMaxRows> sin_theta{};
  std::array<Eigen::Isometry3d, kLinkCount> X_HL;  // this finger's links only
  Eigen::Vector3d p_H_tip = Eigen::Vector3d::Zero();
};

// finger_kinematics, keeping the chain in `cache`.
void finger_kinematics(const HandModel& model, Finger finger, const JointAngles& q,
                       HandLinkPoses& out, FingerChainCache& cache);
// The cached finger at q, where q differs from the cached angles in channel `joint` alone: its
// three links and tip into `out`, bit for bit what finger_kinematics gives, recomputing only the
// rows from the first that `joint` drives (one sine and cosine each for the rows it drives).
void finger_kinematics_probe(const HandModel& model, const FingerChainCache& cache,
                             const JointAngles& q, int joint, HandLinkPoses& out);

// T(i-1, i) of eq. 1 as an isometry, for any row and joint value (the general form, not the
// paper's printed instances).
Eigen::Isometry3d dh_transform(const DhRow& row, double theta_rad);

// Clamps every channel into its range; returns how many channels were out of range.
int clamp_to_limits(const HandModel& model, JointAngles& q);

// The mirror image (left hand from right and back): every pose reflected in the xz plane.
HandModel mirrored(const HandModel& model);

}  // namespace vcockpit::hand
