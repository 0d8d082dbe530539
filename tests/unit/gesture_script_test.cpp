// GestureScript: keyframes, minimum-jerk motion, the tracker mounting, bad scripts.

#include <gtest/gtest.h>

#include <cmath>

#include "common/yaml_config.hpp"
#include "glove_driver/glove/gesture_script.hpp"
#include "hand/hand_yaml.hpp"
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
}  // namespace
}  // namespace vcockpit::glove
