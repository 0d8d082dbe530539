// Retargeting tracked joints to the DH hand, and the hand-size calibration: closed forms on
// frames the model makes itself, the rules for lost joints and time, and the fingertip error on
// the six real Leap Motion recordings (tests/data/real/leap/).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "hand/config/hand_yaml.hpp"
#include "hand/tracker.hpp"
#include "hand/tracking/hand_calibration.hpp"
#include "hand/tracking/leapjs_import.hpp"
#include "hand/tracking/retarget.hpp"

namespace vcockpit::hand::tracking {
namespace {

std::string source_dir() { return std::getenv("VCOCKPIT_SOURCE_DIR"); }

HandModel default_hand() { return load_hand_model(source_dir() + "/config/hand.yaml"); }

double deg(double d) { return d * M_PI / 180.0; }

// The frame a tracker would give for `model` at `q` and `X_GH`: every joint the model has.
JointsFrame frame_of(const HandModel& model, const JointAngles& q, const Eigen::Isometry3d& X_GH,
                     int64_t t_ns = 0) {
  HandLinkPoses P;
  forward_kinematics(model, q, P);
  JointsFrame f;
  f.t_ns = t_ns;
  f.left_hand = model.left;
  const auto set = [&](XrJoint j, const Eigen::Vector3d& p_H) {
    f[j].valid = true;
    f[j].p_m = X_GH * p_H;
  };
  set(XrJoint::kPalm, model.p_H_palm_joint);
  set(XrJoint::kWrist, model.p_H_wrist_joint);
  for (int finger = 0; finger < kFingerCount; ++finger) {
    const XrFingerChain chain = xr_finger_chain(finger);
    const auto links = finger_links(static_cast<Finger>(finger));
    const int first = chain.count - 4;
    for (int k = 0; k < 3; ++k)
      set(chain.joints[static_cast<std::size_t>(first + k)], P.X_HL[static_cast<std::size_t>(links[static_cast<std::size_t>(k)])].translation());
    set(chain.joints[static_cast<std::size_t>(first + 3)], P.p_H_tip[static_cast<std::size_t>(finger)]);
  }
  return f;
}

JointAngles grip_pose(const HandModel& model) {
  JointAngles q = model.rest_pose();
  const auto set = [&](Joint j, double d) { q[static_cast<std::size_t>(j)] = deg(d); };
  set(Joint::kThumbRotation, 40); set(Joint::kThumbMcp, 25); set(Joint::kThumbIp, 30);
  set(Joint::kThumbAbduction, -10);
  set(Joint::kIndexMcp, 50); set(Joint::kIndexPip, 60); set(Joint::kIndexDip, 30);
  set(Joint::kMiddleMcp, 60); set(Joint::kMiddlePip, 70); set(Joint::kMiddleDip, 35);
  set(Joint::kRingMcp, 65); set(Joint::kRingPip, 75); set(Joint::kRingDip, 40);
  set(Joint::kLittleMcp, 70); set(Joint::kLittlePip, 80); set(Joint::kLittleDip, 45);
  set(Joint::kMiddleIndexAbduction, 8); set(Joint::kRingMiddleAbduction, 5);
  set(Joint::kLittleRingAbduction, 10);
  return q;
}

Eigen::Isometry3d some_pose() {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = Eigen::AngleAxisd(0.7, Eigen::Vector3d(0.3, -0.5, 0.8).normalized()).toRotationMatrix();
  X.translation() = Eigen::Vector3d(0.35, -0.3, 0.85);
  return X;
}

// The model's own hand, posed and placed, comes back: the same wrist and the same channels.
TEST(Retarget, AFrameTheModelMadeGivesBackItsPoseAndAngles) {
  for (const bool left : {false, true}) {
    SCOPED_TRACE(left ? "left" : "right");
    const HandModel model = left ? mirrored(default_hand()) : default_hand();
    const JointAngles q = grip_pose(model);
    Retargeter retarget(model);
    const RetargetResult& r = retarget.fit(frame_of(model, q, some_pose()));
    ASSERT_TRUE(r.placed);
    EXPECT_LT((r.X_GH.translation() - some_pose().translation()).norm(), 1e-6);
    EXPECT_LT(Eigen::AngleAxisd(r.X_GH.linear().transpose() * some_pose().linear()).angle(), 1e-6);
    for (int j = 0; j < kJointCount; ++j)
      EXPECT_NEAR(r.q_rad[static_cast<std::size_t>(j)], q[static_cast<std::size_t>(j)], deg(0.05))
          << joint_name(static_cast<Joint>(j));
    for (double e : r.tip_error_m) EXPECT_LT(e, 1e-5);
    // and the glove sample gives that hand through the tracker's mounting (eqs. 26-27)
    const GloveSample s = retarget.glove_sample(5);
    EXPECT_LT((X_GH_from_sample(model, s).translation() - some_pose().translation()).norm(), 1e-9);
  }
}

// Beyond a joint's range the fit stops at the limit: a finger bent backwards stays straight.
TEST(Retarget, AnglesStayWithinTheJointsRanges) {
  const HandModel model = default_hand();
  HandModel bendy = model;
  for (auto& range : bendy.joints) {
    range.min_rad = -M_PI;
    range.max_rad = M_PI;
  }
  JointAngles q = grip_pose(model);
  q[static_cast<std::size_t>(Joint::kIndexMcp)] = deg(-30);  // hyperextended
  Retargeter retarget(model);
  const RetargetResult& r = retarget.fit(frame_of(bendy, q, some_pose()));
  EXPECT_EQ(r.q_rad[static_cast<std::size_t>(Joint::kIndexMcp)], 0.0);
  for (int j = 0; j < kJointCount; ++j) {
    EXPECT_GE(r.q_rad[static_cast<std::size_t>(j)], model.joints[static_cast<std::size_t>(j)].min_rad);
    EXPECT_LE(r.q_rad[static_cast<std::size_t>(j)], model.joints[static_cast<std::size_t>(j)].max_rad);
  }
}

// A finger the tracker lost keeps its last angles; a frame without a placeable palm keeps the
// whole last hand and says so.
TEST(Retarget, ALostFingerKeepsItsLastAnglesAndALostPalmTheLastHand) {
  const HandModel model = default_hand();
  Retargeter retarget(model);
  const JointAngles gripped = grip_pose(model);
  const JointAngles fitted = retarget.fit(frame_of(model, gripped, some_pose(), 0)).q_rad;
  JointsFrame open = frame_of(model, model.rest_pose(), some_pose(), 10'000'000);
  for (XrJoint j : {XrJoint::kIndexIntermediate, XrJoint::kIndexDistal, XrJoint::kIndexTip}) open[j].valid = false;
  const RetargetResult& r = retarget.fit(open);
  ASSERT_TRUE(r.placed);
  for (Joint j : {Joint::kIndexMcp, Joint::kIndexPip, Joint::kIndexDip})
    EXPECT_EQ(r.q_rad[static_cast<std::size_t>(j)], fitted[static_cast<std::size_t>(j)]);
  EXPECT_LT(r.tip_error_m[1], 0.0) << "not tracked";
  EXPECT_NEAR(r.q_rad[static_cast<std::size_t>(Joint::kMiddlePip)], model.rest_pose()[static_cast<std::size_t>(Joint::kMiddlePip)], deg(0.1));

  JointsFrame no_palm = frame_of(model, gripped, some_pose(), 20'000'000);
  for (XrJoint j : {XrJoint::kPalm, XrJoint::kWrist, XrJoint::kThumbMetacarpal}) no_palm[j].valid = false;
  const JointAngles before = r.q_rad;
  EXPECT_FALSE(retarget.fit(no_palm).placed) << "the knuckles alone are a line";
  EXPECT_EQ(retarget.fit(no_palm).q_rad, before);
}

// Smooth in time and deterministic: a hand closing over 100 frames gives angles that change a
// little each frame, the same bits twice.
TEST(Retarget, AClosingHandIsFollowedSmoothlyAndTheSameEveryTime) {
  const HandModel model = default_hand();
  const JointAngles open = model.rest_pose(), closed = grip_pose(model);
  std::vector<JointAngles> runs[2];
  for (auto& run : runs) {
    Retargeter retarget(model);
    for (int i = 0; i <= 100; ++i) {
      JointAngles q;
      for (int j = 0; j < kJointCount; ++j)
        q[static_cast<std::size_t>(j)] = open[static_cast<std::size_t>(j)] + (closed[static_cast<std::size_t>(j)] - open[static_cast<std::size_t>(j)]) * i / 100.0;
      run.push_back(retarget.fit(frame_of(model, q, some_pose(), i * 10'000'000)).q_rad);
    }
  }
  EXPECT_EQ(runs[0], runs[1]);
  for (std::size_t i = 1; i < runs[0].size(); ++i)
    for (int j = 0; j < kJointCount; ++j)
      EXPECT_LT(std::abs(runs[0][i][static_cast<std::size_t>(j)] - runs[0][i - 1][static_cast<std::size_t>(j)]), deg(2.0)) << i;
}

// A user's hand 15 % larger than the model, opening and closing: the calibration finds its bones,
// knuckles and palm, and the calibrated hand fits the tips within a millimetre.
TEST(HandCalibration, ALargerHandIsMeasuredAndThenFitted) {
  const HandModel model = default_hand();
  HandModel user = model;
  for (auto& chain : user.fingers) {
    chain.X_HB.translation() *= 1.15;
    for (auto& row : chain.rows) row.a_m *= 1.15;
  }
  user.p_H_palm_joint *= 1.15;
  std::vector<JointsFrame> frames;
  for (int i = 0; i < 50; ++i) {
    JointAngles q = model.rest_pose();
    const JointAngles g = grip_pose(model);
    for (int j = 0; j < kJointCount; ++j)
      q[static_cast<std::size_t>(j)] += (g[static_cast<std::size_t>(j)] - q[static_cast<std::size_t>(j)]) * std::abs(i % 20 - 10) / 10.0;
    frames.push_back(frame_of(user, q, some_pose(), i * 10'000'000));
  }
  const HandCalibration c = estimate_hand(model, frames);
  EXPECT_EQ(c.steady_frames, 49);
  EXPECT_NEAR(c.bone_m[1][0], 0.046 * 1.15, 1e-9) << "the index's proximal phalanx";
  const HandModel fitted = calibrated(model, c);
  double worst_default = 0.0, worst_calibrated = 0.0;
  Retargeter a(model), b(fitted);
  for (const JointsFrame& f : frames) {
    for (double e : a.fit(f).tip_error_m) worst_default = std::max(worst_default, e);
    for (double e : b.fit(f).tip_error_m) worst_calibrated = std::max(worst_calibrated, e);
  }
  std::printf("tip error, worst: default hand %.1f mm, calibrated %.2f mm\n", worst_default * 1e3,
              worst_calibrated * 1e3);
  EXPECT_GT(worst_default, 0.005);
  EXPECT_LT(worst_calibrated, 0.001);
}

// The real recordings, each calibrated on itself: the fitted tips within 5 mm of the tracked
// ones at the median (p99 printed for the record).
TEST(RetargetRealLeap, EveryRecordingsTipsAreFittedWithin5mmAtTheMedianOnceCalibrated) {
  const HandModel right = default_hand(), left = mirrored(right);
  Eigen::Isometry3d X_GS = Eigen::Isometry3d::Identity();
  X_GS.linear() = R_G_xr();
  for (const char* name : {"grab", "HandSplay-110fps", "wave", "three-claps", "gun", "brian"}) {
    SCOPED_TRACE(name);
    const LeapImport in = import_leapjs(source_dir() + "/tests/data/real/leap/" + name + ".json");
    std::vector<JointsFrame> sides[2];
    for (const JointsFrame& f : in.frames) sides[f.left_hand ? 1 : 0].push_back(to_cockpit(f, X_GS));
    for (int s = 0; s < 2; ++s) {
      if (sides[s].empty()) continue;
      const HandModel& model = s == 1 ? left : right;
      const HandModel hand = calibrated(model, estimate_hand(model, sides[s]));
      Retargeter retarget(hand);
      std::vector<double> errors;
      for (const JointsFrame& f : sides[s])
        for (double e : retarget.fit(f).tip_error_m)
          if (e >= 0.0) errors.push_back(e);
      std::sort(errors.begin(), errors.end());
      const double p50 = errors[errors.size() / 2], p99 = errors[errors.size() * 99 / 100];
      std::printf("%-17s %s: %zu tips, error p50 %.1f mm, p99 %.1f mm\n", name, s == 1 ? "left " : "right",
                  errors.size(), p50 * 1e3, p99 * 1e3);
      EXPECT_LT(p50, 0.005);
      EXPECT_LT(p99, 0.035) << "where Leap's hand bends beyond the model's ranges (29 mm today)";
    }
  }
}

}  // namespace
}  // namespace vcockpit::hand::tracking
