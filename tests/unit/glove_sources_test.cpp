// Replay timing, sample validation and synthetic gestures.

#include <gtest/gtest.h>

#include <cmath>

#include "common/yaml_config.hpp"
#include "glove_driver/glove/gesture_script.hpp"
#include "glove_driver/glove/replay_cursor.hpp"
#include "hand/sample_validator.hpp"
#include "hand/tracker.hpp"
#include "hand/hand_yaml.hpp"

namespace vcockpit::glove {
namespace {

hand::HandModel default_hand() {
  return load_hand_model(std::string(std::getenv("VCOCKPIT_SOURCE_DIR")) + "/config/hand.yaml");
}

std::vector<hand::GloveSample> samples_every_10ms(int n, int64_t t0_ns = 5'000'000'000) {
  std::vector<hand::GloveSample> out(n);
  for (int i = 0; i < n; ++i) out[i].t_ns = t0_ns + 10'000'000LL * i;
  return out;
}

TEST(ReplayCursor, KeepsRelativeTimingScaledByRate) {
  const auto samples = samples_every_10ms(5);
  ReplayCursor cursor(samples, {/*rate=*/2.0, /*loop=*/false, /*start_offset_s=*/0.0});
  hand::GloveSample s;
  int64_t due = -1;
  std::vector<int64_t> dues, times;
  while (cursor.next(s, due)) {
    dues.push_back(due);
    times.push_back(s.t_ns);
  }
  EXPECT_EQ(dues, (std::vector<int64_t>{0, 5'000'000, 10'000'000, 15'000'000, 20'000'000}));
  EXPECT_EQ(times.front(), samples.front().t_ns);  // source stamps are the log's own
}

TEST(ReplayCursor, StartOffsetSkipsTheBeginning) {
  const auto samples = samples_every_10ms(10);
  ReplayCursor cursor(samples, {1.0, false, 0.035});
  hand::GloveSample s;
  int64_t due = -1;
  ASSERT_TRUE(cursor.next(s, due));
  EXPECT_EQ(s.t_ns, samples[4].t_ns);
  EXPECT_EQ(due, 0);
  EXPECT_THROW(ReplayCursor(samples, {1.0, false, 10.0}), std::invalid_argument);
  EXPECT_THROW(ReplayCursor(samples, {-1.0, false, 0.0}), std::invalid_argument);
}

TEST(ReplayCursor, LoopingKeepsTimeIncreasingWithTheSameSpacing) {
  const auto samples = samples_every_10ms(3);
  ReplayCursor cursor(samples, {0.0, true, 0.0});
  hand::GloveSample s;
  int64_t due = -1;
  std::vector<int64_t> times;
  for (int i = 0; i < 7 && cursor.next(s, due); ++i) times.push_back(s.t_ns - samples[0].t_ns);
  EXPECT_EQ(times, (std::vector<int64_t>{0, 10'000'000, 20'000'000, 30'000'000, 40'000'000,
                                         50'000'000, 60'000'000}));
  EXPECT_EQ(due, 0);  // rate 0: nothing waits
}

TEST(SampleValidator, RejectsNonFiniteBadQuaternionAndStaleAndClampsJoints) {
  const auto hand = default_hand();
  hand::SampleValidator validator(hand);
  hand::GloveSample ok;
  ok.t_ns = 100;
  ok.joints_rad = hand.rest_pose();
  EXPECT_TRUE(validator.accept(ok));

  hand::GloveSample nan = ok;
  nan.t_ns = 200;
  nan.joints_rad[3] = std::nan("");
  EXPECT_FALSE(validator.accept(nan));

  hand::GloveSample bad_q = ok;
  bad_q.t_ns = 200;
  bad_q.q_MT = Eigen::Quaterniond(2, 0, 0, 0);
  EXPECT_FALSE(validator.accept(bad_q));

  hand::GloveSample stale = ok;
  stale.t_ns = 100;
  EXPECT_FALSE(validator.accept(stale));

  hand::GloveSample beyond = ok;
  beyond.t_ns = 300;
  beyond.joints_rad[static_cast<int>(hand::Joint::kIndexPip)] = 10.0;
  EXPECT_TRUE(validator.accept(beyond));
  EXPECT_EQ(beyond.joints_rad[static_cast<int>(hand::Joint::kIndexPip)],
            hand.joints[static_cast<int>(hand::Joint::kIndexPip)].max_rad);

  const auto& c = validator.counts();
  EXPECT_EQ(c.accepted, 2u);
  EXPECT_EQ(c.rejected_nonfinite, 1u);
  EXPECT_EQ(c.rejected_out_of_range, 1u);
  EXPECT_EQ(c.rejected_stale, 1u);
  EXPECT_EQ(c.clamped, 1u);
  EXPECT_EQ(c.rejected(), 3u);
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
