// The replay driver (physics_io/replay_driver.hpp) on the default cockpit with the hand far from
// everything: a 33 Hz stream moves the hand over the whole interval between stamps (every step
// on the straight line, at the recorded speed, never in one step); a gap over the max gap holds
// the hand; a gap over the glove timeout loses the glove until the next sample; the counts say
// so; --max-gap 0 is the old behaviour (each sample taken in one step and held). The HandFeed
// in front of it (hand_feed.hpp) takes a source that stays ahead in order, one step at a time,
// without growing.

#include "physics_node/io/replay_driver.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <vector>

#include "hand/tracker.hpp"
#include "physics_node/config/scene_config.hpp"
#include "physics_node/io/hand_feed.hpp"
#include "physics_node/io/hand_motion_peak.hpp"

namespace vcockpit::physics_io {
namespace {

constexpr int64_t kMs = 1'000'000;

// The kinematic hand: these tests follow the tracked input itself (the proxy hand, which may
// lag it at its speed limits, has its own tests).
physics::Scene cockpit() {
  physics::Scene scene =
      load_scene(std::string(std::getenv("VCOCKPIT_SOURCE_DIR")) + "/config/cockpit.yaml");
  scene.proxy.enabled = false;
  return scene;
}

// The recorded motion: 3 m above the cockpit, moving at a constant velocity, turning at a
// constant rate about a fixed axis, the index finger closing at a constant rate.
const Eigen::Vector3d kV_mps(0.3, -0.2, 0.1);
constexpr double kTurn_radps = 1.0;
constexpr double kCurl_radps = 0.5;

hand::GloveSample truth(const hand::HandModel& hand, int64_t t_ns) {
  const double t_s = static_cast<double>(t_ns) * 1e-9;
  hand::GloveSample s;
  s.t_ns = t_ns;
  s.p_MT_m = Eigen::Vector3d(0.2, -0.4, 3.0) + kV_mps * t_s;
  s.q_MT = Eigen::Quaterniond(Eigen::AngleAxisd(kTurn_radps * t_s, Eigen::Vector3d::UnitZ()));
  s.joints_rad = hand.rest_pose();
  s.joints_rad[static_cast<int>(hand::Joint::kIndexMcp)] = 0.1 + kCurl_radps * t_s;
  return s;
}

TEST(ReplayDriver, A33HzStreamMovesTheHandOverTheWholeIntervalAtTheRecordedSpeed) {
  physics::World world(cockpit());
  const hand::HandModel& hand = world.scene().hands[0];
  ReplayDriver driver(world, hand);
  HandMotionPeak peak;
  double worst_m = 0.0, worst_rad = 0.0;
  auto step = [&] {
    world.step();
    peak.record(world);
    // the hand at the step's end is the recorded hand at that time
    const Eigen::Isometry3d expected = hand::X_GH_from_sample(hand, truth(hand, world.time_ns()));
    worst_m = std::max(worst_m, (world.X_GH().translation() - expected.translation()).norm());
    worst_rad = std::max(
        worst_rad, std::abs(world.state().hands[0].to.q_rad[static_cast<int>(hand::Joint::kIndexMcp)] -
                            (0.1 + kCurl_radps * world.time_ns() * 1e-9)));
  };
  const int64_t interval_ns = 30'303'030;  // 33 Hz, off the 1 ms step grid
  for (int k = 0; k <= 16; ++k) {
    const int64_t t_ns = k * interval_ns;
    driver.feed(truth(hand, t_ns), step);
    // one sample of look-ahead: the world stops at the last step that ends by the sample
    EXPECT_LE(world.time_ns(), t_ns);
    EXPECT_GT(world.time_ns() + 1 * kMs, t_ns);
  }
  EXPECT_EQ(world.step_count(), 484u);  // floor(16 * 30.303030 ms / 1 ms)
  EXPECT_LT(worst_m, 1e-12) << "every step on the recorded straight line";
  EXPECT_LT(worst_rad, 1e-12);
  EXPECT_NEAR(peak.wrist_mps(), kV_mps.norm(), 1e-9) << "no step faster than the recording";
  EXPECT_NEAR(peak.joint_radps(), kCurl_radps, 1e-9);
  EXPECT_EQ(driver.counts().intervals, 16u);
  EXPECT_EQ(driver.counts().intervals_interpolated, 16u);
  EXPECT_TRUE(driver.shown().tracking);
}

TEST(ReplayDriver, MaxGapZeroTakesEachSampleInOneStepAsBefore) {
  physics::World world(cockpit());
  const hand::HandModel& hand = world.scene().hands[0];
  InputTiming timing;
  timing.max_gap_ns = 0;
  ReplayDriver driver(world, hand, timing);
  HandMotionPeak peak;
  auto step = [&] {
    world.step();
    peak.record(world);
  };
  for (int k = 0; k <= 16; ++k)
    driver.feed(truth(hand, k * 30'303'030), step);
  // a 30.3 ms move done in one 1 ms step: 30x the recorded speed
  EXPECT_NEAR(peak.wrist_mps(), kV_mps.norm() * 30.303030, 1e-6);
  EXPECT_EQ(driver.counts().gaps_not_bridged, 16u);
  EXPECT_EQ(driver.counts().intervals_interpolated, 0u);
}

// Samples every 10 ms in runs, with gaps between the runs.
std::vector<hand::GloveSample> runs(const hand::HandModel& hand,
                                    const std::vector<std::pair<int, int>>& runs_ms) {
  std::vector<hand::GloveSample> out;
  for (const auto& [from_ms, to_ms] : runs_ms) {
    for (int ms = from_ms; ms <= to_ms; ms += 10)
      out.push_back(truth(hand, ms * kMs));
  }
  return out;
}

TEST(ReplayDriver, GapsOverTheMaxGapHoldAndOverTheTimeoutLoseTheGloveUntilTheNextSample) {
  physics::World world(cockpit());
  const hand::HandModel& hand = world.scene().hands[0];
  ReplayDriver driver(world, hand);  // max gap 0.25 s, glove timeout 1 s
  // 0.1 s gap (bridged), 0.3 s (held), 1.2 s (held, glove lost after 1 s)
  const auto samples = runs(hand, {{0, 100}, {200, 300}, {600, 700}, {1900, 2000}});
  auto position_at = [&](int64_t t_ns) -> Eigen::Vector3d {
    const Eigen::Isometry3d X_GH = hand::X_GH_from_sample(hand, truth(hand, t_ns));
    return X_GH.translation();
  };
  int checked = 0;
  auto step = [&] {
    world.step();
    const int64_t t = world.time_ns();
    const Eigen::Vector3d p = world.X_GH().translation();
    const bool tracking = world.state().hands[0].to.tracking;
    if (t > 100 * kMs && t < 200 * kMs) {  // bridged: on the line
      EXPECT_LT((p - position_at(t)).norm(), 1e-12) << t;
      EXPECT_TRUE(tracking);
      ++checked;
    } else if (t > 300 * kMs && t < 600 * kMs) {  // not bridged: held, still tracked
      EXPECT_LT((p - position_at(300 * kMs)).norm(), 1e-12) << t;
      EXPECT_TRUE(tracking) << t;
      ++checked;
    } else if (t > 700 * kMs && t < 1900 * kMs) {  // held; lost after the 1 s timeout
      EXPECT_LT((p - position_at(700 * kMs)).norm(), 1e-12) << t;
      EXPECT_EQ(tracking, t <= 1700 * kMs) << t;
      EXPECT_EQ(driver.shown().tracking, tracking);
      ++checked;
    } else if (t == 600 * kMs || t == 1900 * kMs) {  // the next sample, in one step
      EXPECT_LT((p - position_at(t)).norm(), 1e-12) << t;
      EXPECT_TRUE(tracking);
      ++checked;
    }
  };
  for (const auto& s : samples)
    driver.feed(s, step);
  EXPECT_EQ(checked, 99 + 299 + 1199 + 2);
  const auto& c = driver.counts();
  EXPECT_EQ(c.intervals, samples.size() - 1);
  EXPECT_EQ(c.intervals_interpolated, 40u);
  EXPECT_EQ(c.gaps_bridged, 1u);
  EXPECT_EQ(c.gaps_not_bridged, 2u);
  EXPECT_EQ(c.longest_interval_ns, 1200 * kMs);
  EXPECT_EQ(c.glove_lost, 1u);
  EXPECT_EQ(world.time_ns(), 2000 * kMs);
}

TEST(ReplayDriver, PastTheLastSampleTheHandHoldsItAndTheGloveIsLostAfterTheTimeout) {
  physics::World world(cockpit());
  const hand::HandModel& hand = world.scene().hands[0];
  ReplayDriver driver(world, hand);
  auto step = [&] { world.step(); };
  for (const auto& s : runs(hand, {{0, 50}}))
    driver.feed(s, step);
  driver.step_until(1050 * kMs, step);
  EXPECT_TRUE(driver.shown().tracking) << "1 s after the last sample: not yet";
  driver.step_until(1051 * kMs, step);
  EXPECT_FALSE(driver.shown().tracking);
  EXPECT_EQ(driver.shown().sample_time_ns, 50 * kMs);
  EXPECT_EQ(driver.counts().glove_lost, 1u);
}

TEST(ReplayDriver, ARestartedSourceStartsAtTheWorldsPresentWithNoIntervalFromTheOld) {
  physics::World world(cockpit());
  const hand::HandModel& hand = world.scene().hands[0];
  ReplayDriver driver(world, hand);
  auto step = [&] { world.step(); };
  for (const auto& s : runs(hand, {{0, 100}}))
    driver.feed(s, step, 7 + s.t_ns);
  EXPECT_EQ(driver.shown().source_stamp_ns, 7 + 100 * kMs);
  driver.restart();
  // the new source's timeline starts far away; its first sample is the hand at once
  hand::GloveSample s = truth(hand, 5'000 * kMs);
  driver.feed(s, step);
  EXPECT_EQ(world.time_ns(), 100 * kMs);
  const Eigen::Isometry3d X_GH = hand::X_GH_from_sample(hand, s);
  EXPECT_LT((world.state().hands[0].to.X_GH.translation() - X_GH.translation()).norm(), 1e-12);
  EXPECT_EQ(driver.counts().intervals, 10u);
}

// A lockstep glove driver stays ahead of its world: the feed always holds samples the world has
// not reached. Each step takes them in order up to the one at its end and no further, and what
// was taken is let go although the queue never runs dry.
TEST(HandFeed, ASourceThatStaysAheadIsTakenInOrderAndItsStoreDoesNotGrow) {
  physics::World world(cockpit());
  const hand::HandModel& hand = world.scene().hands[0];
  ReplayDriver driver(world, hand);
  HandFeed feed;
  const int64_t step_ns = std::llround(world.scene().step_s * 1e9);
  constexpr std::size_t kLead = 100;
  int64_t next_t_ns = 0;
  for (std::size_t k = 0; k < kLead; ++k, next_t_ns += step_ns) feed.queue(truth(hand, next_t_ns));
  std::size_t most_stored = 0;
  for (int n = 0; n < 5000; ++n) {
    feed.queue(truth(hand, next_t_ns));
    next_t_ns += step_ns;
    const int64_t end_ns = world.time_ns() + step_ns;
    feed.take_until(driver, end_ns, world.time_ns());
    ASSERT_EQ(driver.newest_world_ns(), end_ns) << "step " << n;
    ASSERT_EQ(feed.queued_count(), kLead - 1) << "step " << n;
    driver.input_for_step_ending(end_ns);
    world.step();
    const Eigen::Isometry3d X_GH = hand::X_GH_from_sample(hand, truth(hand, world.time_ns()));
    ASSERT_LT((world.state().hands[0].to.X_GH.translation() - X_GH.translation()).norm(), 1e-9)
        << "step " << n;
    most_stored = std::max(most_stored, feed.stored_count());
  }
  EXPECT_LE(most_stored, 2 * kLead + 64) << "the samples taken were kept";
}

TEST(ReplayDriver, AMaxGapLongerThanTheGloveTimeoutIsRefused) {
  physics::World world(cockpit());
  InputTiming timing;
  timing.max_gap_ns = 1100 * kMs;
  EXPECT_THROW(ReplayDriver(world, world.scene().hands[0], timing), std::invalid_argument);
}

}  // namespace
}  // namespace vcockpit::physics_io
