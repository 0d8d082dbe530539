// The DH hand (paper §3): eq. 1 against hand-computed matrices, eqs. 8-10 chaining, proper link
// rotations, flexion toward the palm, mirroring, clamping and the tracker mounts.

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <new>
#include <random>
#include <string>

#include "common/pose.hpp"
#include "hand/config/hand_yaml.hpp"
#include "hand/hand_model.hpp"
#include "hand/tracker.hpp"
#include "tests/support/allocation_counter.hpp"

namespace vcockpit::hand {
namespace {

// to prove forward_kinematics allocates nothing
using test::g_allocations;
using test::g_count_allocations;

constexpr double kTol = 1e-12;
constexpr double kTolM = 1e-12;  // positions (m)
constexpr uint32_t kSeed = 20050704;

std::string source_dir() {
  if (const char* dir = std::getenv("VCOCKPIT_SOURCE_DIR")) return dir;
  const std::string file = __FILE__;  // <repo>/tests/unit/hand_kinematics_test.cpp
  return file.substr(0, file.rfind("/tests/unit/"));
}

const HandModel& shipped_hand() {
  static const HandModel model = load_hand_model(source_dir() + "/config/hand.yaml");
  return model;
}

std::size_t idx(Link link) {
  return static_cast<std::size_t>(link);
}
std::size_t idx(Finger finger) {
  return static_cast<std::size_t>(finger);
}
std::size_t idx(Joint joint) {
  return static_cast<std::size_t>(joint);
}

double row_theta(const DhRow& row, const JointAngles& q) {
  return row.joint < 0 ? row.theta_offset_rad : row.theta_offset_rad + row.scale * q[row.joint];
}

JointAngles random_pose(const HandModel& model, std::mt19937& rng) {
  JointAngles q{};
  for (int j = 0; j < kJointCount; ++j) {
    std::uniform_real_distribution<double> u(model.joints[j].min_rad, model.joints[j].max_rad);
    q[j] = u(rng);
  }
  return q;
}

HandLinkPoses fk(const HandModel& model, const JointAngles& q) {
  HandLinkPoses poses;
  forward_kinematics(model, q, poses);
  return poses;
}

void expect_proper_rotation(const Eigen::Matrix3d& R, const std::string& what) {
  EXPECT_TRUE((R.transpose() * R).isApprox(Eigen::Matrix3d::Identity(), kTol)) << what;
  EXPECT_NEAR(R.determinant(), 1.0, kTol) << what;
}

Eigen::Isometry3d mirror(const Eigen::Isometry3d& X) {
  const Eigen::Matrix4d M = Eigen::Vector4d(1, -1, 1, 1).asDiagonal();
  return Eigen::Isometry3d(M * X.matrix() * M);
}

DhRow row_of(double alpha_deg, double a_m, double d_m) {
  DhRow row;
  row.alpha_rad = deg_to_rad(alpha_deg);
  row.a_m = a_m;
  row.d_m = d_m;
  return row;
}

// ---- eq. 1 ----------------------------------------------------------------------------------

TEST(DhTransform, MatchesHandComputedMatrices) {
  const double c30 = std::sqrt(3.0) / 2.0;
  Eigen::Matrix4d expected;
  // clang-format off
  // alpha 90 deg, a 0.1 m, d 0.2 m, theta 30 deg
  expected << c30, 0, 0.5, 0.1 * c30,
              0.5, 0, -c30, 0.05,
              0, 1, 0, 0.2,
              0, 0, 0, 1;
  EXPECT_TRUE(dh_transform(row_of(90, 0.1, 0.2), deg_to_rad(30)).matrix().isApprox(expected, kTol));
  // alpha 0, a 0.05 m, d 0, theta 90 deg: a planar link turned a quarter
  expected << 0, -1, 0, 0,
              1, 0, 0, 0.05,
              0, 0, 1, 0,
              0, 0, 0, 1;
  EXPECT_TRUE(dh_transform(row_of(0, 0.05, 0), deg_to_rad(90)).matrix().isApprox(expected, kTol));
  // alpha -90 deg, a 0.03 m, d -0.01 m, theta 0: y -> -z, z -> y
  expected << 1, 0, 0, 0.03,
              0, 0, 1, 0,
              0, -1, 0, -0.01,
              0, 0, 0, 1;
  // clang-format on
  EXPECT_TRUE(dh_transform(row_of(-90, 0.03, -0.01), 0.0).matrix().isApprox(expected, kTol));
}

TEST(DhTransform, IsRzTzTxRxAndIgnoresTheRowsOwnOffset) {
  std::mt19937 rng(kSeed);
  std::uniform_real_distribution<double> angle(-M_PI, M_PI), length(0.0, 0.1);
  for (int i = 0; i < 50; ++i) {
    DhRow row = row_of(0, length(rng), length(rng) - 0.05);
    row.alpha_rad = angle(rng);
    row.theta_offset_rad = angle(rng);  // theta_rad is the full theta: the offset is not re-added
    const double theta = angle(rng);
    const Eigen::Isometry3d expected = Eigen::AngleAxisd(theta, Eigen::Vector3d::UnitZ()) *
                                       Eigen::Translation3d(0, 0, row.d_m) *
                                       Eigen::Translation3d(row.a_m, 0, 0) *
                                       Eigen::AngleAxisd(row.alpha_rad, Eigen::Vector3d::UnitX());
    const Eigen::Isometry3d T = dh_transform(row, theta);
    EXPECT_TRUE(T.matrix().isApprox(expected.matrix(), kTol));
    expect_proper_rotation(T.linear(), "dh_transform");
  }
}

// ---- link poses -----------------------------------------------------------------------------

TEST(HandKinematics, EveryLinkRotationIsProperForRandomAngles) {
  const HandModel& model = shipped_hand();
  std::mt19937 rng(kSeed);
  for (int sample = 0; sample < 200; ++sample) {
    const HandLinkPoses poses = fk(model, random_pose(model, rng));
    for (int l = 0; l < kLinkCount; ++l) {
      expect_proper_rotation(poses.X_HL[l].linear(), std::string(link_name(static_cast<Link>(l))));
    }
  }
}

TEST(HandKinematics, FlatHandIsStraightWithConfiguredSegmentLengths) {
  const HandModel& model = shipped_hand();
  const HandLinkPoses poses = fk(model, JointAngles{});
  EXPECT_TRUE(poses.X_HL[idx(Link::kPalm)].isApprox(model.X_HP, kTol));
  for (int f = 0; f < kFingerCount; ++f) {
    const auto finger = static_cast<Finger>(f);
    const auto links = finger_links(finger);
    double total_m = 0;
    for (std::size_t k = 0; k < 3; ++k) {
      const double length_m = model.capsules[idx(links[k])].length_m;
      total_m += length_m;
      const Eigen::Vector3d p_from = poses.X_HL[idx(links[k])].translation();
      const Eigen::Vector3d p_to =
          k < 2 ? Eigen::Vector3d(poses.X_HL[idx(links[k + 1])].translation()) : poses.p_H_tip[f];
      EXPECT_NEAR((p_to - p_from).norm(), length_m, kTolM) << link_name(links[k]);
    }
    const Eigen::Vector3d p_root = poses.X_HL[idx(links[0])].translation();
    EXPECT_NEAR((poses.p_H_tip[f] - p_root).norm(), total_m, kTolM) << finger_name(finger);
    if (finger == Finger::kThumb) continue;
    // the four fingers lie along +x, in the palm's mid-plane
    const Eigen::Vector3d dir = (poses.p_H_tip[f] - p_root).normalized();
    EXPECT_TRUE(dir.isApprox(Eigen::Vector3d::UnitX(), 1e-9)) << finger_name(finger);
  }
  // thumb forward-sideways: along +x and +y, in the palm plane
  const Eigen::Vector3d thumb_dir =
      (poses.p_H_tip[idx(Finger::kThumb)] - poses.X_HL[idx(Link::kThumbProximal)].translation());
  EXPECT_GT(thumb_dir.x(), 0.0);
  EXPECT_GT(thumb_dir.y(), 0.0);
  EXPECT_NEAR(thumb_dir.z(), 0.0, kTolM);
}

// Fingertip of `finger` and its distance to the palm centre after adding `delta_rad` to `joint`.
struct Tip {
  Eigen::Vector3d p_H;
  double to_palm_m;
};
Tip tip_after(const HandModel& model, JointAngles q, Finger finger, Joint joint, double delta_rad) {
  q[idx(joint)] += delta_rad;
  const HandLinkPoses poses = fk(model, q);
  const Eigen::Vector3d p_H = poses.p_H_tip[idx(finger)];
  return {p_H, (p_H - model.X_HP.translation()).norm()};
}

TEST(HandKinematics, FlexionCurlsEachFingertipTowardThePalm) {
  const HandModel& model = shipped_hand();
  struct Case {
    Finger finger;
    Joint joint;
  };
  const Case cases[] = {{Finger::kThumb, Joint::kThumbMcp},   {Finger::kThumb, Joint::kThumbIp},
                        {Finger::kIndex, Joint::kIndexMcp},   {Finger::kIndex, Joint::kIndexPip},
                        {Finger::kIndex, Joint::kIndexDip},   {Finger::kMiddle, Joint::kMiddleMcp},
                        {Finger::kMiddle, Joint::kMiddlePip}, {Finger::kMiddle, Joint::kMiddleDip},
                        {Finger::kRing, Joint::kRingMcp},     {Finger::kRing, Joint::kRingPip},
                        {Finger::kRing, Joint::kRingDip},     {Finger::kLittle, Joint::kLittleMcp},
                        {Finger::kLittle, Joint::kLittlePip}, {Finger::kLittle, Joint::kLittleDip}};
  const double delta_rad = deg_to_rad(20);
  for (const JointAngles& q : {JointAngles{}, model.rest_pose()}) {
    for (const Case& c : cases) {
      const Tip before = tip_after(model, q, c.finger, c.joint, 0.0);
      const Tip after = tip_after(model, q, c.finger, c.joint, delta_rad);
      EXPECT_LT(after.p_H.z(), before.p_H.z() - 1e-3) << joint_name(c.joint);
      EXPECT_LT(after.to_palm_m, before.to_palm_m) << joint_name(c.joint);
    }
  }
}

TEST(HandKinematics, AbductionSpreadsFingersInThePalmPlane) {
  const HandModel& model = shipped_hand();
  const double delta_rad = deg_to_rad(10);
  const JointAngles flat{};
  // index spreads toward +y (thumb side), little toward -y, both without leaving the palm plane
  const Tip index = tip_after(model, flat, Finger::kIndex, Joint::kMiddleIndexAbduction, delta_rad);
  const Tip little =
      tip_after(model, flat, Finger::kLittle, Joint::kLittleRingAbduction, delta_rad);
  const Tip index0 = tip_after(model, flat, Finger::kIndex, Joint::kMiddleIndexAbduction, 0.0);
  const Tip little0 = tip_after(model, flat, Finger::kLittle, Joint::kLittleRingAbduction, 0.0);
  EXPECT_GT(index.p_H.y(), index0.p_H.y() + 1e-3);
  EXPECT_LT(little.p_H.y(), little0.p_H.y() - 1e-3);
  EXPECT_NEAR(index.p_H.z(), index0.p_H.z(), kTolM);
  EXPECT_NEAR(little.p_H.z(), little0.p_H.z(), kTolM);
}

TEST(HandKinematics, PalmArchMovesLittleKnuckleToThePalmSide) {
  const HandModel& model = shipped_hand();
  JointAngles q{};
  const auto root_z = [&] {
    return fk(model, q).X_HL[idx(Link::kLittleProximal)].translation().z();
  };
  const double flat_z = root_z();
  q[idx(Joint::kPalmArch)] = deg_to_rad(20);
  EXPECT_LT(root_z(), flat_z - 5e-3);
}

// eqs. 8-10: root = X_HB T(0,1)..., middle and tip frames are plain products of eq. 1.
TEST(HandKinematics, ChainIsTheProductOfEq1AsInEqs8To10) {
  const HandModel& model = shipped_hand();
  std::mt19937 rng(kSeed + 1);
  for (int sample = 0; sample < 20; ++sample) {
    const JointAngles q = random_pose(model, rng);
    const HandLinkPoses poses = fk(model, q);

    // the index finger written out: rows abduction, MCP, PIP, DIP
    const auto& rows = model.fingers[idx(Finger::kIndex)].rows;
    ASSERT_EQ(rows.size(), 4u);
    const auto T = [&](std::size_t i) { return dh_transform(rows[i], row_theta(rows[i], q)); };
    const Eigen::Isometry3d X_HB = model.fingers[idx(Finger::kIndex)].X_HB;
    const Eigen::Isometry3d root = X_HB * T(0);
    const Eigen::Isometry3d middle = X_HB * T(0) * T(1);
    const Eigen::Isometry3d distal = X_HB * T(0) * T(1) * T(2);
    const Eigen::Isometry3d tip = X_HB * T(0) * T(1) * T(2) * T(3);
    const auto turned = [&](const Eigen::Isometry3d& X, std::size_t next) {
      return X * dh_transform(row_of(0, 0, rows[next].d_m), row_theta(rows[next], q));
    };
    EXPECT_TRUE(poses.X_HL[idx(Link::kIndexProximal)].isApprox(turned(root, 1), kTol));
    EXPECT_TRUE(poses.X_HL[idx(Link::kIndexMiddle)].isApprox(turned(middle, 2), kTol));
    EXPECT_TRUE(poses.X_HL[idx(Link::kIndexDistal)].isApprox(turned(distal, 3), kTol));
    EXPECT_TRUE(poses.p_H_tip[idx(Finger::kIndex)].isApprox(tip.translation(), kTol));

    // every finger: the tagged rows' outputs and the last row's output
    for (int f = 0; f < kFingerCount; ++f) {
      const FingerChain& chain = model.fingers[f];
      Eigen::Isometry3d X = chain.X_HB;
      for (std::size_t i = 0; i < chain.rows.size(); ++i) {
        X = X * dh_transform(chain.rows[i], row_theta(chain.rows[i], q));
        if (chain.rows[i].link >= 0) {
          EXPECT_TRUE(poses.X_HL[chain.rows[i].link].translation().isApprox(X.translation(), kTol));
        }
      }
      EXPECT_TRUE(poses.p_H_tip[f].isApprox(X.translation(), kTol)) << f;
    }
  }
}

// A probe of one joint (finger_kinematics_probe, the proxy's Jacobian) re-poses only the rows
// that joint moves, and gives bit for bit what a full forward kinematics gives: every joint of
// every finger at random poses of the shipped hand and its mirror image, a joint of another
// finger leaving the cached finger as it was.
TEST(HandKinematics, AProbeOfOneJointIsTheFingersForwardKinematicsBitForBit) {
  std::mt19937 rng(kSeed);
  for (const HandModel& model : {shipped_hand(), mirrored(shipped_hand())}) {
    for (int sample = 0; sample < 50; ++sample) {
      const JointAngles q = random_pose(model, rng);
      for (int f = 0; f < kFingerCount; ++f) {
        const auto finger = static_cast<Finger>(f);
        HandLinkPoses at;
        FingerChainCache cache;
        finger_kinematics(model, finger, q, at, cache);
        for (int j = 0; j < kJointCount; ++j) {
          JointAngles probe = q;
          probe[static_cast<std::size_t>(j)] += 1e-4;
          HandLinkPoses full, probed;
          finger_kinematics(model, finger, probe, full);
          finger_kinematics_probe(model, cache, probe, j, probed);
          for (const Link link : finger_links(finger)) {
            const auto l = static_cast<std::size_t>(link);
            EXPECT_EQ(std::memcmp(full.X_HL[l].matrix().data(), probed.X_HL[l].matrix().data(),
                                  16 * sizeof(double)),
                      0)
                << finger_name(finger) << " " << link_name(link) << ", probing "
                << joint_name(static_cast<Joint>(j));
          }
          const auto tip = static_cast<std::size_t>(f);
          EXPECT_EQ(std::memcmp(full.p_H_tip[tip].data(), probed.p_H_tip[tip].data(), 3 * sizeof(double)), 0)
              << finger_name(finger) << " tip, probing " << joint_name(static_cast<Joint>(j));
        }
      }
    }
  }
}

TEST(HandKinematics, ForwardKinematicsDoesNotAllocate) {
  const HandModel& model = shipped_hand();
  const JointAngles q = model.rest_pose();
  HandLinkPoses poses;
  g_allocations = 0;
  g_count_allocations = true;
  forward_kinematics(model, q, poses);
  g_count_allocations = false;
  EXPECT_EQ(g_allocations.load(), 0);
}

// ---- mirroring ------------------------------------------------------------------------------

TEST(HandMirror, LeftHandIsTheMirrorImage) {
  const HandModel& right = shipped_hand();
  const HandModel left = mirrored(right);
  EXPECT_TRUE(left.left);
  EXPECT_TRUE(left.tracker.X_GM.isApprox(right.tracker.X_GM, 0.0));
  std::mt19937 rng(kSeed + 2);
  for (int sample = 0; sample < 50; ++sample) {
    const JointAngles q = random_pose(right, rng);
    const HandLinkPoses pr = fk(right, q), pl = fk(left, q);
    for (int l = 0; l < kLinkCount; ++l) {
      expect_proper_rotation(pl.X_HL[l].linear(), "left link");
      EXPECT_TRUE(pl.X_HL[l].isApprox(mirror(pr.X_HL[l]), kTol)) << l;
    }
    for (int f = 0; f < kFingerCount; ++f) {
      EXPECT_TRUE(pl.p_H_tip[f].isApprox(
          Eigen::Vector3d(pr.p_H_tip[f].x(), -pr.p_H_tip[f].y(), pr.p_H_tip[f].z()), kTol));
    }
  }
  const HandLinkPoses rest = fk(left, left.rest_pose());
  EXPECT_LT(rest.p_H_tip[idx(Finger::kThumb)].y(), -0.03);
  EXPECT_GT(fk(right, right.rest_pose()).p_H_tip[idx(Finger::kThumb)].y(), 0.03);
}

TEST(HandMirror, MirroringTwiceGivesTheOriginal) {
  const HandModel& model = shipped_hand();
  const HandModel twice = mirrored(mirrored(model));
  EXPECT_EQ(twice.left, model.left);
  EXPECT_TRUE(twice.X_HP.isApprox(model.X_HP, 0.0));
  for (int f = 0; f < kFingerCount; ++f) {
    EXPECT_TRUE(twice.fingers[f].X_HB.isApprox(model.fingers[f].X_HB, 0.0));
    ASSERT_EQ(twice.fingers[f].rows.size(), model.fingers[f].rows.size());
    for (std::size_t i = 0; i < model.fingers[f].rows.size(); ++i) {
      const DhRow &a = twice.fingers[f].rows[i], &b = model.fingers[f].rows[i];
      EXPECT_EQ(a.alpha_rad, b.alpha_rad);
      EXPECT_EQ(a.theta_offset_rad, b.theta_offset_rad);
      EXPECT_EQ(a.scale, b.scale);
      EXPECT_EQ(a.a_m, b.a_m);
      EXPECT_EQ(a.d_m, b.d_m);
      EXPECT_EQ(a.joint, b.joint);
      EXPECT_EQ(a.link, b.link);
    }
  }
}

// ---- limits ---------------------------------------------------------------------------------

TEST(HandLimits, ClampCountsAndClampsOutOfRangeChannels) {
  const HandModel& model = shipped_hand();
  JointAngles q = model.rest_pose();
  EXPECT_EQ(clamp_to_limits(model, q), 0);
  EXPECT_EQ(q, model.rest_pose());

  const JointRange& mcp = model.joints[idx(Joint::kIndexMcp)];
  const JointRange& yaw = model.joints[idx(Joint::kWristYaw)];
  q[idx(Joint::kIndexMcp)] = mcp.min_rad - 0.5;
  q[idx(Joint::kWristYaw)] = yaw.max_rad + 0.01;
  q[idx(Joint::kThumbIp)] = std::nan("");
  q[idx(Joint::kRingPip)] = model.joints[idx(Joint::kRingPip)].max_rad;  // on the limit: fine
  EXPECT_EQ(clamp_to_limits(model, q), 3);
  EXPECT_EQ(q[idx(Joint::kIndexMcp)], mcp.min_rad);
  EXPECT_EQ(q[idx(Joint::kWristYaw)], yaw.max_rad);
  EXPECT_EQ(q[idx(Joint::kThumbIp)], model.joints[idx(Joint::kThumbIp)].rest_rad);
  EXPECT_EQ(q[idx(Joint::kRingPip)], model.joints[idx(Joint::kRingPip)].max_rad);
  EXPECT_EQ(clamp_to_limits(model, q), 0);
}

// ---- tracker mounts -------------------------------------------------------------------------

TEST(HandTracker, BackOfHandMountIgnoresTheWrist) {
  HandModel model = shipped_hand();
  model.tracker.mount = TrackerMount::kBackOfHand;
  const Eigen::Isometry3d X_MT = pose_from_position_rpy_deg({0.3, -0.1, 1.2}, {10, -20, 30});
  JointAngles q{};
  q[idx(Joint::kWristPitch)] = 0.5;
  q[idx(Joint::kWristYaw)] = -0.3;
  EXPECT_TRUE(X_MH_from_tracker(model, X_MT, q).isApprox(X_MT, 0.0));
}

TEST(HandTracker, ForearmMountTurnsByWristYawThenPitch) {
  HandModel model = shipped_hand();
  model.tracker.mount = TrackerMount::kForearm;
  const Eigen::Isometry3d X_MT = pose_from_position_rpy_deg({0.3, -0.1, 1.2}, {10, -20, 30});
  JointAngles q{};
  EXPECT_TRUE(X_MH_from_tracker(model, X_MT, q).isApprox(X_MT, kTol));

  // wrist flexion (+pitch) turns the fingers (+x of H) toward the palm side (-z of the forearm)
  q[idx(Joint::kWristPitch)] = deg_to_rad(30);
  Eigen::Isometry3d X_TH = X_MT.inverse() * X_MH_from_tracker(model, X_MT, q);
  EXPECT_TRUE((X_TH.linear() * Eigen::Vector3d::UnitX())
                  .isApprox(Eigen::Vector3d(std::cos(deg_to_rad(30)), 0, -0.5), kTol));
  EXPECT_TRUE(X_TH.translation().isZero(kTol));

  // radial deviation (+yaw) turns a right hand toward its thumb (+y), a left one toward -y
  q = JointAngles{};
  q[idx(Joint::kWristYaw)] = deg_to_rad(15);
  X_TH = X_MT.inverse() * X_MH_from_tracker(model, X_MT, q);
  EXPECT_GT((X_TH.linear() * Eigen::Vector3d::UnitX()).y(), 0.2);
  const HandModel left = mirrored(model);
  X_TH = X_MT.inverse() * X_MH_from_tracker(left, X_MT, q);
  EXPECT_LT((X_TH.linear() * Eigen::Vector3d::UnitX()).y(), -0.2);

  // both: X_MT * Rz(yaw) * Ry(pitch)
  q[idx(Joint::kWristPitch)] = deg_to_rad(-40);
  const Eigen::Isometry3d expected = X_MT *
                                     Eigen::AngleAxisd(deg_to_rad(15), Eigen::Vector3d::UnitZ()) *
                                     Eigen::AngleAxisd(deg_to_rad(-40), Eigen::Vector3d::UnitY());
  EXPECT_TRUE(X_MH_from_tracker(model, X_MT, q).isApprox(expected, kTol));
}

}  // namespace
}  // namespace vcockpit::hand
