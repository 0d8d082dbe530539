// glove_driver as a real process over loopback DDS: a lockstep replay of a 5,000-sample log at
// full speed arrives complete and value-identical; record -> replay -> record round-trips to an
// identical log; an interrupted recording still leaves a valid log; bad flags are clear errors.

#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <thread>

#include "dds/dds_options.hpp"
#include "dds/dds_participant.hpp"
#include "glove_driver/glove/joints_input.hpp"
#include "idl/topics/pose_convert.hpp"
#include "hand/glove_log.hpp"
#include "hand/tracking/joints_log.hpp"
#include "hand/tracking/leapjs_import.hpp"
#include "idl/topics/hand_sample_convert.hpp"
#include "hand/sample_validator.hpp"
#include "hand/config/hand_yaml.hpp"
#include "tests/support/hand_sample_pattern.hpp"
#include "tests/support/process.hpp"
#include "tests/support/process_test.hpp"
#include "tests/support/test_env.hpp"

namespace vcockpit::test {
namespace {

class GloveDriverTest : public ProcessTest {
 protected:
  std::string glove_driver() const { return bin_dir() + "/glove_driver"; }
  hand::HandModel hand_ = load_hand_model(source_dir() + "/config/hand.yaml");
};

TEST_F(GloveDriverTest, LockstepReplayOfFiveThousandSamplesAtFullSpeedIsCompleteAndIdentical) {
  constexpr int kCount = 5000;
  const std::string dir = make_temp_dir("glove_driver_replay");
  // a log with every field varying; sample 10 has a joint beyond its limit (clamped, counted)
  std::vector<hand::GloveSample> samples;
  for (int i = 0; i < kCount; ++i) {
    const auto pattern = hand_sample_pattern(static_cast<uint64_t>(i));
    hand::GloveSample s = from_hand_sample(pattern);
    s.t_ns = 1'000'000LL * i + 17;
    s.joints_rad = hand_.rest_pose();
    for (int j = 0; j < hand::kJointCount; ++j) {
      const auto& r = hand_.joints[j];
      s.joints_rad[j] = r.min_rad + (r.max_rad - r.min_rad) * pattern.joint_angles_rad()[j];
    }
    samples.push_back(s);
  }
  samples[10].joints_rad[static_cast<int>(hand::Joint::kIndexMcp)] = 3.0;
  const std::string log = dir + "/pattern.csv";
  hand::write_glove_log(log, samples, false, {"source: glove_driver_test"});

  ChildProcess sub({bin_dir() + "/test_hand_sample_sub", "--count", std::to_string(kCount),
                    "--out", dir + "/received.bin", "--timeout-s", "60", "--status-out",
                    dir + "/status.txt"},
                   env_, dir + "/sub.log");
  const auto start = std::chrono::steady_clock::now();
  ChildProcess driver({glove_driver(), "--source", "replay", "--log", log, "--lockstep", "--rate",
                       "0"},
                      env_, dir + "/driver.log");
  EXPECT_EQ(driver.wait(90 * kSecond), 0) << read_text(dir + "/driver.log");
  const double elapsed_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(sub.wait(30 * kSecond), 0) << read_text(dir + "/sub.log");
  std::printf("lockstep replay of %d samples took %.2f s (log spans %.1f s)\n", kCount, elapsed_s,
              kCount * 1e-3);

  // what arrived is what the log holds (after the documented clamp), in order, none missing
  const auto records = read_records(dir + "/received.bin");
  ASSERT_EQ(records.size(), static_cast<std::size_t>(kCount));
  hand::SampleValidator validator(hand_);
  for (int i = 0; i < kCount; ++i) {
    hand::GloveSample expected = samples[i];
    ASSERT_TRUE(validator.accept(expected));
    ASSERT_EQ(records[i], serialize(to_hand_sample(expected, 0, i, 0))) << "sample " << i;
  }
  const std::string status = read_text(dir + "/status.txt");
  EXPECT_NE(status.find("published=5000"), std::string::npos) << status;
  EXPECT_NE(status.find("clamped=1"), std::string::npos) << status;
  EXPECT_NE(status.find("rejected=0"), std::string::npos) << status;
  // its last line counts the clamp it warned about while loading (it used to say "clamped 0")
  const std::string driver_log = read_text(dir + "/driver.log");
  EXPECT_NE(driver_log.find("joint value(s) beyond the limits were clamped"), std::string::npos);
  EXPECT_NE(driver_log.find("published 5000 samples"), std::string::npos) << driver_log;
  EXPECT_NE(driver_log.find("clamped 1, missing columns 0, intervals 4999"), std::string::npos)
      << driver_log;
}

TEST_F(GloveDriverTest, RecordReplayRecordRoundTripsToAnIdenticalLog) {
  const std::string dir = make_temp_dir("glove_driver_roundtrip");
  const std::string script = source_dir() + "/config/gestures/reach_grasp_lift_release.yaml";
  const std::string first = dir + "/first.csv";
  const std::string second = dir + "/second.csv";
  {
    ChildProcess recorder({glove_driver(), "--record", first, "--lockstep", "--idle-timeout", "1"},
                          env_, dir + "/record1.log");
    ChildProcess synthetic({glove_driver(), "--source", "synthetic", "--script", script,
                            "--lockstep", "--rate", "0"},
                           env_, dir + "/synthetic.log");
    ASSERT_EQ(synthetic.wait(60 * kSecond), 0) << read_text(dir + "/synthetic.log");
    ASSERT_EQ(recorder.wait(30 * kSecond), 0) << read_text(dir + "/record1.log");
  }
  const auto first_log = hand::read_glove_log(first, hand_);
  EXPECT_GT(first_log.samples.size(), 1000u);
  {
    ChildProcess recorder(
        {glove_driver(), "--record", second, "--lockstep", "--count",
         std::to_string(first_log.samples.size())},
        env_, dir + "/record2.log");
    ChildProcess replay({glove_driver(), "--source", "replay", "--log", first, "--lockstep",
                         "--rate", "0"},
                        env_, dir + "/replay.log");
    ASSERT_EQ(replay.wait(60 * kSecond), 0) << read_text(dir + "/replay.log");
    ASSERT_EQ(recorder.wait(30 * kSecond), 0) << read_text(dir + "/record2.log");
  }
  const std::string a = read_text(first);
  const std::string b = read_text(second);
  EXPECT_EQ(a.size(), b.size());
  EXPECT_TRUE(a == b) << "the re-recorded log differs from the first recording";
}

TEST_F(GloveDriverTest, InterruptedRecordingLeavesAValidLogOrNone) {
  const std::string dir = make_temp_dir("glove_driver_interrupt");
  const std::string log = source_dir() + "/config/glove_logs/open_hand_sweep.csv";
  const std::string clean = dir + "/clean.csv";
  const std::string killed = dir + "/killed.csv";
  ChildProcess replay({glove_driver(), "--source", "replay", "--log", log, "--loop"}, env_,
                      dir + "/replay.log");
  ChildProcess rec_clean({glove_driver(), "--record", clean}, env_, dir + "/clean.log");
  ChildProcess rec_killed({glove_driver(), "--record", killed}, env_, dir + "/killed.log");
  // Under the sanitizers the recorders take over a second to start and match (under TSan
  // beside the renderer's tests, 16 samples after 1.5 s): they get 4 s there.
  std::this_thread::sleep_for(std::chrono::milliseconds(sanitized() ? 4000 : 1500));
  rec_clean.signal(SIGINT);
  rec_killed.signal(SIGKILL);
  expect_clean_shm_ = false;
  EXPECT_EQ(rec_clean.wait(5 * kSecond), 0) << read_text(dir + "/clean.log");
  EXPECT_EQ(rec_killed.wait(5 * kSecond), 128 + SIGKILL);
  EXPECT_EQ(replay.stop(5 * kSecond), 0) << read_text(dir + "/replay.log");

  const auto recorded = hand::read_glove_log(clean, hand_);  // throws if corrupt
  EXPECT_GT(recorded.samples.size(), 100u);
  EXPECT_FALSE(std::filesystem::exists(clean + ".partial"));
  EXPECT_FALSE(std::filesystem::exists(killed)) << "a killed recorder must not leave a log";
  std::filesystem::remove(killed + ".partial");
}

TEST_F(GloveDriverTest, BadFlagsAndInputsAreClearErrors) {
  const std::string dir = make_temp_dir("glove_driver_flags");
  auto run = [&](std::vector<std::string> args) {
    args.insert(args.begin(), glove_driver());
    std::filesystem::remove(dir + "/out.log");
    ChildProcess p(args, env_, dir + "/out.log");
    const int code = p.wait(20 * kSecond);
    return std::make_pair(code, read_text(dir + "/out.log"));
  };
  auto [code1, out1] = run({"--source", "replay"});
  EXPECT_NE(code1, 0);
  EXPECT_NE(out1.find("--log"), std::string::npos) << out1;

  auto [code2, out2] = run({"--source", "replay", "--log", "/nonexistent.csv"});
  EXPECT_NE(code2, 0);
  EXPECT_NE(out2.find("/nonexistent.csv"), std::string::npos) << out2;

  auto [code3, out3] = run({"--source", "teleport"});
  EXPECT_NE(code3, 0);
  EXPECT_NE(out3.find("teleport"), std::string::npos) << out3;

  const std::string bad_log = dir + "/bad.csv";
  std::ofstream(bad_log) << "t_s,x_m,y_m,z_m,qw,qx,qy,qz\n0,0,0,0,1,0,0,0\n0.01,0,0,x,1,0,0,0\n";
  auto [code4, out4] = run({"--source", "replay", "--log", bad_log});
  EXPECT_NE(code4, 0);
  EXPECT_NE(out4.find("bad.csv:3: column 'z_m'"), std::string::npos) << out4;

  auto [code5, out5] = run({"--source", "replay", "--log", bad_log, "--domain", "999"});
  EXPECT_NE(code5, 0);
  EXPECT_NE(out5.find("--domain"), std::string::npos) << out5;

  // a hand-joints log of both hands needs --side (a driver per hand); a glove log is not one
  const std::string claps = dir + "/claps.csv";
  hand::tracking::write_joints_log(
      claps, hand::tracking::JointsSpace::kXr,
      hand::tracking::import_leapjs(source_dir() + "/tests/data/real/leap/three-claps.json").frames, {});
  auto [code6, out6] = run({"--source", "joints", "--log", claps});
  EXPECT_NE(code6, 0);
  EXPECT_NE(out6.find("both hands: give --side"), std::string::npos) << out6;
  auto [code7, out7] = run({"--source", "joints", "--log", bad_log});
  EXPECT_NE(code7, 0);
  EXPECT_NE(out7.find("bad.csv:1: not a hand joints log"), std::string::npos) << out7;
}

// --source joints: the real Leap "grab", imported, retargeted by the driver on a hand calibrated
// on it, published in lockstep and recorded: every frame arrives, as the library retargets it.
TEST_F(GloveDriverTest, AHandJointsLogIsRetargetedAndPublishedFrameByFrame) {
  const std::string dir = make_temp_dir("glove_driver_joints");
  const auto in = hand::tracking::import_leapjs(source_dir() + "/tests/data/real/leap/grab.json");
  const std::string joints = dir + "/grab_joints.csv";
  hand::tracking::write_joints_log(joints, hand::tracking::JointsSpace::kXr, in.frames, {});
  const std::string recorded = dir + "/recorded.csv";
  {
    ChildProcess recorder({glove_driver(), "--record", recorded, "--lockstep", "--count",
                           std::to_string(in.frames.size())},
                          env_, dir + "/record.log");
    ChildProcess driver({glove_driver(), "--source", "joints", "--log", joints, "--calibrate",
                         "--palm-at", "0.36", "-0.35", "0.84", "--lockstep", "--rate", "0"},
                        env_, dir + "/driver.log");
    ASSERT_EQ(driver.wait(60 * kSecond), 0) << read_text(dir + "/driver.log");
    ASSERT_EQ(recorder.wait(30 * kSecond), 0) << read_text(dir + "/record.log");
  }
  EXPECT_NE(read_text(dir + "/driver.log").find("374 samples of the right hand retargeted on the hand calibrated on it"),
            std::string::npos)
      << read_text(dir + "/driver.log");
  glove::JointsInputOptions options;
  options.calibrate = true;
  const glove::JointsInput expected = glove::joints_input(joints, hand_, options);
  const hand::GloveLog got = hand::read_glove_log(recorded, expected.hand);
  ASSERT_EQ(got.samples.size(), expected.log.samples.size());
  for (std::size_t i = 0; i < got.samples.size(); ++i) {
    const hand::GloveSample& a = got.samples[i];
    const hand::GloveSample& b = expected.log.samples[i];
    ASSERT_LT((a.p_MT_m - b.p_MT_m).norm(), 1e-9) << i;
    ASSERT_LT(a.q_MT.angularDistance(b.q_MT), 1e-9) << i;
    for (int j = 0; j < hand::kJointCount; ++j)
      ASSERT_NEAR(a.joints_rad[static_cast<std::size_t>(j)], b.joints_rad[static_cast<std::size_t>(j)], 1e-9) << i;
  }
}

// ... and beside each sample, on cockpit/tracked_joints, the tracker's joints it came from (in the
// world, as placed): from the moment the reader matched, every one, to the last frame.
TEST_F(GloveDriverTest, TheTrackersJointsGoOutWithEachRetargetedSample) {
  const std::string dir = make_temp_dir("glove_driver_tracked_joints");
  const auto in = hand::tracking::import_leapjs(source_dir() + "/tests/data/real/leap/grab.json");
  const std::string joints = dir + "/grab_joints.csv";
  hand::tracking::write_joints_log(joints, hand::tracking::JointsSpace::kXr, in.frames, {});
  glove::JointsInputOptions options;
  const glove::JointsInput expected = glove::joints_input(joints, hand_, options);

  DdsParticipant participant(resolve_dds_options(DdsFlags{}), "glove_driver_test");
  auto reader = participant.make_reader<cockpit::TrackedJoints>("reliable");
  ChildProcess recorder({glove_driver(), "--record", dir + "/recorded.csv", "--lockstep", "--count",
                         std::to_string(in.frames.size())},
                        env_, dir + "/record.log");
  ChildProcess driver({glove_driver(), "--source", "joints", "--log", joints, "--lockstep"}, env_,
                      dir + "/driver.log");
  std::vector<cockpit::TrackedJoints> got;
  cockpit::TrackedJoints message;
  // (the lockstep run ends with the log's last frame; under a sanitizer on a loaded machine it
  // has taken 32 s, so the bound is generous: it only ends a run that hangs)
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (std::chrono::steady_clock::now() < deadline &&
         (got.empty() || got.back().sample_time_ns() != expected.log.samples.back().t_ns)) {
    reader.wait_for_data(100'000'000);
    while (reader.take(message)) got.push_back(message);
  }
  ASSERT_EQ(driver.wait(60 * kSecond), 0) << read_text(dir + "/driver.log");
  ASSERT_EQ(recorder.wait(30 * kSecond), 0) << read_text(dir + "/record.log");
  ASSERT_FALSE(got.empty()) << "no tracked joints arrived";
  std::printf("%zu of %zu frames' joints received (from the match on)\n", got.size(), in.frames.size());
  ASSERT_EQ(got.back().sample_time_ns(), expected.log.samples.back().t_ns)
      << "the log's last frame never arrived";
  // a contiguous run of the log's frames, ending at its last
  ASSERT_LE(got.size(), expected.log.samples.size());
  const std::size_t first = expected.log.samples.size() - got.size();
  for (std::size_t k = 0; k < got.size(); ++k) {
    const std::size_t i = first + k;
    ASSERT_EQ(got[k].sample_time_ns(), expected.log.samples[i].t_ns) << k;
    EXPECT_EQ(got[k].hand_id(), 0u);
    for (std::size_t j = 0; j < 26; ++j) {
      const auto& joint = expected.frames_G[i].joints[j];
      ASSERT_EQ(got[k].valid()[j], joint.valid) << i << " " << j;
      if (joint.valid) {
        ASSERT_LT((to_eigen(got[k].p_G_m()[j]) - joint.p_m).norm(), 1e-12) << i << " " << j;
      }
    }
  }
}

}  // namespace
}  // namespace vcockpit::test
