// GestureScript: keyframes, minimum-jerk motion, the tracker mounting, bad scripts.

#include <gtest/gtest.h>

#include <cmath>

#include "common/yaml_config.hpp"
#include "glove_driver/glove/gesture_script.hpp"
#include "hand/config/hand_yaml.hpp"
#include "hand/tracker.hpp"

namespace vcockpit::glove {
namespace {

hand::HandModel default_hand() {
  return load_hand_model(std::string(std::getenv("VCOCKPIT_SOURCE_DIR")) + "/config/hand.yaml");
}

constexpr const char* kScript = R"(rate_hz: 500
shapes:
  half: {index_mcp: 45}
keyframes:
  - {t_s: 0.0, position: [0.0, 0.0, 1.0], rpy_deg: [0, 0, 0], shape: open}
  - {t_s: 1.0, position: [0.2, 0.0, 1.0], shape: half}
  - {t_s: 2.0, rpy_deg: [0, 0, 90], shape: power}
)";

TEST(GestureScript, HitsKeyframesExactlyAndMovesSmoothlyBetween) {
  const auto hand = default_hand();
  const auto script = GestureScript::parse(ConfigNode::load_string(kScript, "script.yaml"), hand);
  EXPECT_EQ(script.rate_hz(), 500.0);
  EXPECT_EQ(script.duration_ns(), 2'000'000'000);
  Eigen::Isometry3d X_GH;
  hand::JointAngles q;
  script.evaluate(1'000'000'000, X_GH, q);
  EXPECT_TRUE(X_GH.translation().isApprox(Eigen::Vector3d(0.2, 0, 1.0), 1e-12));
  EXPECT_NEAR(q[static_cast<int>(hand::Joint::kIndexMcp)], M_PI / 4, 1e-12);
  // halfway: minimum jerk is symmetric, so half the distance
  script.evaluate(500'000'000, X_GH, q);
  EXPECT_NEAR(X_GH.translation().x(), 0.1, 1e-12);
  // zero velocity at a keyframe: 1 ms either side moves much less than the mean speed would
  Eigen::Isometry3d before, after;
  script.evaluate(999'000'000, before, q);
  script.evaluate(1'001'000'000, after, q);
  EXPECT_LT((after.translation() - before.translation()).norm(), 1e-6);  // mean: 4e-4 m
  // the last keyframe keeps the position and turns the hand 90 deg about z
  script.evaluate(5'000'000'000, X_GH, q);
  EXPECT_TRUE(X_GH.translation().isApprox(Eigen::Vector3d(0.2, 0, 1.0), 1e-12));
  EXPECT_TRUE((X_GH.linear() * Eigen::Vector3d::UnitX()).isApprox(Eigen::Vector3d::UnitY(), 1e-9));
}

TEST(GestureScript, SampleGoesThroughTheTrackerMounting) {
  const auto hand = default_hand();
  const auto script = GestureScript::parse(ConfigNode::load_string(kScript, "script.yaml"), hand);
  const hand::GloveSample s = script.sample_at(700'000'000);
  Eigen::Isometry3d X_GH_expected;
  hand::JointAngles q;
  script.evaluate(700'000'000, X_GH_expected, q);
  Eigen::Isometry3d X_MT = Eigen::Isometry3d::Identity();
  X_MT.linear() = s.q_MT.toRotationMatrix();
  X_MT.translation() = s.p_MT_m;
  const Eigen::Isometry3d X_GH =
      hand.tracker.X_GM * hand::X_MH_from_tracker(hand, X_MT, s.joints_rad);
  EXPECT_TRUE(X_GH.isApprox(X_GH_expected, 1e-9));
}

TEST(GestureScript, BadScriptsNameFileLineAndKey) {
  const auto hand = default_hand();
  auto error_of = [&](const std::string& text) -> std::string {
    try {
      GestureScript::parse(ConfigNode::load_string(text, "bad.yaml"), hand);
    } catch (const ConfigError& e) {
      return e.what();
    }
    return "(no error)";
  };
  EXPECT_NE(error_of("keyframes:\n  - {t_s: 0, position: [0,0,0], rpy_deg: [0,0,0], shape: fist}\n")
                .find("bad.yaml:2:"),
            std::string::npos);
  EXPECT_NE(error_of("keyframes:\n  - {t_s: 0, position: [0,0,0], rpy_deg: [0,0,0], shape: fist}\n")
                .find("unknown hand shape 'fist'"),
            std::string::npos);
  EXPECT_NE(error_of("keyframes:\n  - {t_s: 0, position: [0,0,0], rpy_deg: [0,0,0]}\n"
                     "  - {t_s: 0, shape: open}\n")
                .find("bad.yaml:3:"),
            std::string::npos);
  EXPECT_NE(error_of("keyframes:\n  - {t_s: 0, position: [0,0,0], rpy_deg: [0,0,0], speed: 2}\n")
                .find("unknown key 'speed'"),
            std::string::npos);
  EXPECT_NE(error_of("shapes:\n  x: {index_mpc: 3}\nkeyframes:\n  - {t_s: 0, position: [0,0,0], "
                     "rpy_deg: [0,0,0]}\n")
                .find("shapes.x.index_mpc: unknown joint"),
            std::string::npos);
  EXPECT_NE(error_of("rate_hz: 0\nkeyframes: []\n").find("rate_hz: must be in"), std::string::npos);
}

constexpr const char* kGraspScript = R"(shapes:
  grip: {thumb_rotation: 50, thumb_ip: 30, index_mcp: 40, index_pip: 40, middle_mcp: 40, middle_pip: 40}
grasp_point: {shape: grip, fingers: [index, middle]}
keyframes:
  - {t_s: 0.0, position: [0.2, -0.4, 0.9], rpy_deg: [0, 0, 0], shape: open}
  - {t_s: 1.0, grasp_at: [0.45, -0.35, 0.76], rpy_deg: [0, 0, -10], shape: open}
  - {t_s: 2.0, shape: grip}
  - {t_s: 3.0, rpy_deg: [0, 0, 80]}
  - {t_s: 4.0, grasp_at: [0.35, -0.40, 0.86]}
)";

hand::HandModel scaled(hand::HandModel h, double s) {
  for (auto& f : h.fingers) {
    f.X_HB.translation() *= s;
    for (auto& row : f.rows) row.a_m *= s;
  }
  for (auto& c : h.capsules) c.length_m *= s;
  h.X_HP.translation() *= s;
  h.palm_size_m *= s;
  return h;
}

TEST(GestureScript, GraspPointIsMidwayBetweenThumbAndFingers) {
  const auto hand = default_hand();
  const auto script = GestureScript::parse(ConfigNode::load_string(kGraspScript, "g.yaml"), hand);
  hand::JointAngles grip = script.keyframes()[2].joints_rad;
  hand::HandLinkPoses poses;
  hand::forward_kinematics(hand, grip, poses);
  const Eigen::Vector3d expected =
      0.5 * (poses.p_H_tip[0] + 0.5 * (poses.p_H_tip[1] + poses.p_H_tip[2]));
  EXPECT_TRUE(script.p_H_grasp().isApprox(expected, 1e-12));
  EXPECT_TRUE(grasp_point_H(hand, grip, {hand::Finger::kIndex, hand::Finger::kMiddle})
                  .isApprox(expected, 1e-12));
}

TEST(GestureScript, GraspAtPutsTheGraspPointThereForEveryHandSize) {
  const auto hand = default_hand();
  Eigen::Vector3d wrist_at_1s[2];
  int i = 0;
  for (const auto& h : {hand, scaled(hand, 0.85)}) {
    const auto script = GestureScript::parse(ConfigNode::load_string(kGraspScript, "g.yaml"), h);
    Eigen::Isometry3d X_GH;
    hand::JointAngles q;
    // at every keyframe given by grasp_at, and while the hand only turns (3 s): the point stays
    for (int64_t t_ns : {1'000'000'000LL, 2'000'000'000LL, 2'500'000'000LL, 3'000'000'000LL}) {
      script.evaluate(t_ns, X_GH, q);
      EXPECT_TRUE((X_GH * script.p_H_grasp()).isApprox(Eigen::Vector3d(0.45, -0.35, 0.76), 1e-9))
          << t_ns;
    }
    // between two grasp_at keyframes the point moves on the straight line (min-jerk halfway)
    script.evaluate(3'500'000'000, X_GH, q);
    EXPECT_TRUE((X_GH * script.p_H_grasp()).isApprox(Eigen::Vector3d(0.40, -0.375, 0.81), 1e-9));
    script.evaluate(1'000'000'000, X_GH, q);
    wrist_at_1s[i++] = X_GH.translation();
  }
  // the smaller hand's wrist comes closer to the object: the wrist follows from the hand's size
  EXPECT_GT((wrist_at_1s[0] - wrist_at_1s[1]).norm(), 0.01);
}

TEST(GestureScript, BadGraspPointsAreNamed) {
  const auto hand = default_hand();
  auto error_of = [&](const std::string& text) -> std::string {
    try {
      GestureScript::parse(ConfigNode::load_string(text, "bad.yaml"), hand);
    } catch (const ConfigError& e) {
      return e.what();
    }
    return "(no error)";
  };
  const std::string first = "keyframes:\n  - {t_s: 0, grasp_at: [0,0,0], rpy_deg: [0,0,0]}\n";
  EXPECT_NE(error_of(first).find("grasp_at needs the script's grasp_point"), std::string::npos);
  EXPECT_NE(error_of("grasp_point: {shape: power, fingers: [thumb]}\n" + first)
                .find("expected index, middle, ring or little, found 'thumb'"),
            std::string::npos);
  EXPECT_NE(error_of("grasp_point: {shape: fist, fingers: [index]}\n" + first)
                .find("unknown hand shape 'fist'"),
            std::string::npos);
  EXPECT_NE(error_of("grasp_point: {shape: power, fingers: []}\n" + first)
                .find("name at least one finger"),
            std::string::npos);
  EXPECT_NE(error_of("grasp_point: {shape: power, fingers: [index]}\nkeyframes:\n"
                     "  - {t_s: 0, position: [0,0,0], grasp_at: [0,0,0], rpy_deg: [0,0,0]}\n")
                .find("give one of position (the wrist), grasp_at and tip_at"),
            std::string::npos);
  const std::string tip_first = "keyframes:\n  - {t_s: 0, tip_at: [0,0,0], rpy_deg: [0,0,0]}\n";
  EXPECT_NE(error_of(tip_first).find("tip_at needs the script's tip_point"), std::string::npos);
  EXPECT_NE(error_of("tip_point: {shape: open, finger: toe}\n" + tip_first)
                .find("expected thumb, index, middle, ring or little, found 'toe'"),
            std::string::npos);
}

constexpr const char* kTipScript = R"(tip_point: {shape: open, finger: index}
grasp_point: {shape: pinch, fingers: [index]}
keyframes:
  - {t_s: 0.0, position: [0.2, 0.0, 1.0], rpy_deg: [0, 0, 0], shape: open}
  - {t_s: 1.0, tip_at: [0.78, -0.10, 1.0], rpy_deg: [0, 30, 0]}
  - {t_s: 2.0, tip_at: [0.80, -0.10, 1.0]}
  - {t_s: 3.0, rpy_deg: [0, 0, 0]}
  - {t_s: 4.0, grasp_at: [0.6, 0.0, 1.0]}
)";

// The fingertip's centre goes where tip_at says, for every hand size, moves straight between two
// tip_at keyframes and stays put while the hand turns; a change of anchor moves the wrist.
TEST(GestureScript, TipAtPutsTheFingertipThereForEveryHandSize) {
  const auto hand = default_hand();
  for (const auto& h : {hand, scaled(hand, 0.85)}) {
    const auto script = GestureScript::parse(ConfigNode::load_string(kTipScript, "t.yaml"), h);
    hand::HandLinkPoses poses;
    hand::forward_kinematics(h, builtin_shapes(h).at("open"), poses);
    EXPECT_TRUE(script.p_H_tip().isApprox(poses.p_H_tip[1], 1e-12));
    Eigen::Isometry3d X_GH;
    hand::JointAngles q;
    script.evaluate(1'000'000'000, X_GH, q);
    EXPECT_TRUE((X_GH * script.p_H_tip()).isApprox(Eigen::Vector3d(0.78, -0.10, 1.0), 1e-9));
    script.evaluate(1'500'000'000, X_GH, q);
    EXPECT_TRUE((X_GH * script.p_H_tip()).isApprox(Eigen::Vector3d(0.79, -0.10, 1.0), 1e-9));
    for (int64_t t_ns : {2'000'000'000LL, 2'400'000'000LL, 3'000'000'000LL}) {
      script.evaluate(t_ns, X_GH, q);
      EXPECT_TRUE((X_GH * script.p_H_tip()).isApprox(Eigen::Vector3d(0.80, -0.10, 1.0), 1e-9)) << t_ns;
    }
    script.evaluate(4'000'000'000, X_GH, q);
    EXPECT_TRUE((X_GH * script.p_H_grasp()).isApprox(Eigen::Vector3d(0.6, 0.0, 1.0), 1e-9));
  }
}

TEST(GestureScript, BundledGestureScriptsLoadForEveryHandSize) {
  const std::string dir = std::string(std::getenv("VCOCKPIT_SOURCE_DIR")) + "/config/";
  for (const char* hand_file : {"hand.yaml", "hand_small.yaml", "hand_large.yaml"}) {
    const auto hand = load_hand_model(dir + hand_file);
    for (const char* script : {"reach_grasp_lift_release", "open_hand_sweep", "cup_pick_place",
                               "ball_pick_place", "flashlight_pick_place",
                               "checklist_pick_place", "panel_switches", "panel_knobs",
                               "pedestal_levers"}) {
      EXPECT_NO_THROW(GestureScript::load(dir + "gestures/" + script + ".yaml", hand))
          << script << " with " << hand_file;
    }
  }
}

}  // namespace
}  // namespace vcockpit::glove
