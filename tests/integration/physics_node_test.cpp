// physics_node as a real process over loopback DDS: a lockstep replay gives the offline runner's
// result; real time holds 1 kHz and the hand follows the samples (interpolated between them, a
// small delay behind); a killed glove driver releases
// the held object ("glove lost") and a restarted one resumes tracking; invalid samples are
// rejected and counted while the node keeps running; a crafted log's faults are counted the same
// by the glove driver, the lockstep node and the offline runner; each bundled control log in
// lockstep writes the offline runner's trajectories.csv, events.jsonl and control_frames.csv byte
// for byte.

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <csignal>
#include <fstream>
#include <sstream>
#include <thread>
#include <vector>

#include "common/clock.hpp"
#include "hand/glove_log.hpp"
#include "physics_node/config/scene_config.hpp"
#include "physics_node/io/hand_input.hpp"
#include "physics_node/io/offline_runner.hpp"
#include "physics_node/io/sample_interpolation.hpp"
#include "tests/support/crafted_glove_log.hpp"
#include "tests/support/monitor_log.hpp"
#include "tests/support/process.hpp"
#include "tests/support/process_test.hpp"
#include "tests/support/test_env.hpp"

namespace vcockpit::test {
namespace {

std::string grasp_log() { return source_dir() + "/config/glove_logs/reach_grasp_lift_release.csv"; }
std::string sweep_log() { return source_dir() + "/config/glove_logs/open_hand_sweep.csv"; }

class PhysicsNodeTest : public ProcessTest {};

TEST_F(PhysicsNodeTest, LockstepReplayGivesTheOfflineRunnersResult) {
  physics_io::OfflineOptions offline;
  offline.scene_path = source_dir() + "/config/cockpit.yaml";
  offline.log_paths = {grasp_log()};
  offline.out_dir = dir_ + "/offline";
  const auto summary = physics_io::run_offline(load_scene(offline.scene_path), offline);
  ASSERT_EQ(summary.grasps, 1);

  ChildProcess node = start("physics_node", {"--lockstep"}, "node.log");
  ChildProcess monitor = start("test_cockpit_monitor", {"--out", dir_ + "/monitor.txt"}, "monitor.log");
  ChildProcess driver = start("glove_driver", {"--source", "replay", "--log", grasp_log(),
                                               "--lockstep", "--rate", "0"},
                              "driver.log");
  ASSERT_EQ(driver.wait(60 * kSecond), 0) << text("driver.log");
  // the node publishes once it has caught up with the last sample (8.5 s into the log)
  EXPECT_TRUE(wait_for_line(dir_ + "/monitor.txt", "sim_time_ns=8500000000 ", 120 * kSecond))
      << text("node.log");
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  EXPECT_EQ(monitor.stop(), 0);
  EXPECT_EQ(node.stop(), 0) << text("node.log");

  const MonitorLog seen = MonitorLog::read(dir_ + "/monitor.txt");
  const MonitorLog offline_events = MonitorLog::from_events_jsonl(offline.out_dir + "/events.jsonl");
  ASSERT_EQ(seen.events.size(), 2u) << text("node.log");
  ASSERT_EQ(offline_events.events.size(), 2u);
  for (int i = 0; i < 2; ++i) {
    EXPECT_EQ(seen.events[i].kind, offline_events.events[i].kind);
    EXPECT_EQ(seen.events[i].t_ns, offline_events.events[i].t_ns);
    EXPECT_EQ(seen.events[i].reason, offline_events.events[i].reason);
  }
  // final poses: the offline summary's doubles, to within 2e-9
  const auto final_offline = read_final_poses(offline.out_dir + "/summary.json");
  physics::Scene scene = load_scene(offline.scene_path);
  ASSERT_FALSE(final_offline.empty());
  for (const auto& [name, p] : final_offline) {
    const int id = scene.find_object(name);
    ASSERT_TRUE(seen.objects.count(id)) << name;
    const auto& o = seen.objects.at(id);
    EXPECT_NEAR(o.position.x(), p.x(), 2e-9) << name;
    EXPECT_NEAR(o.position.y(), p.y(), 2e-9) << name;
    EXPECT_NEAR(o.position.z(), p.z(), 2e-9) << name;
    EXPECT_EQ(o.sim_time_ns, 8'500'000'000) << name;
  }
}

// Each bundled control log (config/glove_logs/panel_*.csv, pedestal_levers.csv) replayed over DDS
// to a lockstep node with --out: its trajectories.csv and events.jsonl are the offline runner's,
// byte for byte (the control events in them are pinned by tests/scenario/control_logs_test).
TEST_F(PhysicsNodeTest, EachControlLogInLockstepWritesTheOfflineRunnersFilesByteForByte) {
  // under the sanitizers the node steps a few times slower than real time: the shortest log only
  const std::vector<const char*> logs =
      sanitized() ? std::vector<const char*>{"panel_knobs"}
                  : std::vector<const char*>{"panel_switches", "panel_knobs", "pedestal_levers"};
  for (const char* name : logs) {
    SCOPED_TRACE(name);
    const std::string log = source_dir() + "/config/glove_logs/" + name + ".csv";
    physics_io::OfflineOptions offline;
    offline.scene_path = source_dir() + "/config/cockpit.yaml";
    offline.log_paths = {log};
    offline.out_dir = dir_ + "/offline_" + name;
    const auto summary = physics_io::run_offline(load_scene(offline.scene_path), offline);
    ASSERT_GT(summary.control_events, 0);
    const std::string end = "sim_time_ns=" + std::to_string(std::llround(summary.simulated_s * 1e9)) + " ";

    const std::string out = dir_ + "/lockstep_" + name;
    const std::string monitor_file = dir_ + "/monitor_" + name + ".txt";
    ChildProcess node = start("physics_node", {"--lockstep", "--out", out}, std::string("node_") + name + ".log");
    ChildProcess monitor = start("test_cockpit_monitor", {"--out", monitor_file}, "monitor.log");
    ChildProcess driver = start("glove_driver", {"--source", "replay", "--log", log, "--lockstep",
                                                 "--rate", "0"},
                                "driver.log");
    ASSERT_EQ(driver.wait(120 * kSecond), 0) << text("driver.log");
    EXPECT_TRUE(wait_for_line(monitor_file, end, 120 * kSecond)) << text(std::string("node_") + name + ".log");
    EXPECT_EQ(monitor.stop(), 0);
    ASSERT_EQ(node.stop(), 0) << text(std::string("node_") + name + ".log");
    for (const char* file : {"events.jsonl", "trajectories.csv", "control_frames.csv"}) {
      const std::string lockstep = read_text(out + "/" + file);
      EXPECT_FALSE(lockstep.empty()) << file;
      EXPECT_TRUE(lockstep == read_text(offline.out_dir + "/" + file))
          << file << " differs from the offline runner's";
    }
  }
}

// Two glove drivers, one per hand (the bundled handover), and a lockstep node that waits for
// both (--lockstep-hands right,left): the same events and trajectories as the offline runner
// with the two logs, byte for byte; hand_state arrives for both hand ids.
TEST_F(PhysicsNodeTest, TwoGloveDriversInLockstepGiveTheOfflineRunnersHandoverByteForByte) {
  const std::string right = source_dir() + "/config/glove_logs/handover_right.csv";
  const std::string left = source_dir() + "/config/glove_logs/handover_left.csv";
  physics_io::OfflineOptions offline;
  offline.scene_path = source_dir() + "/config/cockpit.yaml";
  offline.log_paths = {right, left};
  offline.out_dir = dir_ + "/offline_handover";
  const auto summary = physics_io::run_offline(load_scene(offline.scene_path), offline);
  ASSERT_EQ(summary.grasps, 2);
  const std::string end = "sim_time_ns=" + std::to_string(std::llround(summary.simulated_s * 1e9)) + " ";

  const std::string out = dir_ + "/lockstep_handover";
  const std::string monitor_file = dir_ + "/monitor_handover.txt";
  ChildProcess node = start("physics_node", {"--lockstep", "--lockstep-hands", "right,left", "--out", out},
                            "node_handover.log");
  ChildProcess monitor = start("test_cockpit_monitor", {"--out", monitor_file}, "monitor.log");
  ChildProcess right_driver = start("glove_driver", {"--source", "replay", "--log", right, "--lockstep",
                                                     "--rate", "0"},
                                    "driver_right.log");
  ChildProcess left_driver = start("glove_driver", {"--source", "replay", "--log", left, "--lockstep",
                                                    "--rate", "0", "--node-name", "glove_driver_left"},
                                   "driver_left.log");
  ASSERT_EQ(right_driver.wait(120 * kSecond), 0) << text("driver_right.log");
  ASSERT_EQ(left_driver.wait(120 * kSecond), 0) << text("driver_left.log");
  EXPECT_TRUE(wait_for_line(monitor_file, end, 120 * kSecond)) << text("node_handover.log");
  EXPECT_EQ(monitor.stop(), 0);
  ASSERT_EQ(node.stop(), 0) << text("node_handover.log");
  for (const char* file : {"events.jsonl", "trajectories.csv"}) {
    const std::string lockstep = read_text(out + "/" + file);
    EXPECT_FALSE(lockstep.empty()) << file;
    EXPECT_TRUE(lockstep == read_text(offline.out_dir + "/" + file))
        << file << " differs from the offline runner's";
  }
  const std::string seen = read_text(monitor_file);
  EXPECT_NE(seen.find("hand id=0 "), std::string::npos) << "hand_state of the right hand";
  EXPECT_NE(seen.find("hand id=1 "), std::string::npos) << "hand_state of the left hand";
  const std::string node_log = text("node_handover.log");
  // every sample of each log reached its own hand
  ASSERT_EQ(summary.hands.size(), 2u);
  for (const auto& hand : summary.hands) {
    const std::string line = std::string(hand.hand_id == 1 ? "left" : "right") + " hand: " +
                             std::to_string(hand.input.accepted) + " samples";
    EXPECT_NE(node_log.find(line), std::string::npos) << line << "\n" << node_log;
  }
}

// A log with clamped values, a missing column, a gap bridged and two not (one past the glove
// timeout): the glove driver and the lockstep physics node count it as the offline runner does.
TEST_F(PhysicsNodeTest, EveryNodeCountsACraftedLogsFaultsAsTheOfflineRunnerDoes) {
  CraftedGloveLog craft;
  craft.run(0, 100, 3);
  craft.run(200, 300);
  craft.run(600, 700);
  craft.run(1900, 2000);  // after 1.2 s: the glove lost from 1.7 s (1 s timeout)
  const std::string log = dir_ + "/crafted.csv";
  std::ofstream(log) << craft.text();
  physics_io::OfflineOptions offline;
  offline.scene_path = source_dir() + "/config/cockpit.yaml";
  offline.log_paths = {log};
  offline.out_dir = dir_ + "/offline";
  physics_io::run_offline(load_scene(offline.scene_path), offline);
  std::ifstream summary_file(offline.out_dir + "/summary.json");
  const auto input = nlohmann::json::parse(summary_file).at("input");

  ChildProcess node = start("physics_node", {"--lockstep"}, "node.log");
  ChildProcess monitor = start("test_cockpit_monitor", {"--out", dir_ + "/monitor.txt"}, "monitor.log");
  ChildProcess driver =
      // at the log's own pace (2 s), not as fast as it can: a driver done in 13 ms exits before
      // the monitor has discovered its status writer, and its final report reaches nobody
      start("glove_driver", {"--source", "replay", "--log", log, "--lockstep", "--rate", "1"},
            "driver.log");
  ASSERT_EQ(driver.wait(60 * kSecond), 0) << text("driver.log");
  // a physics status after the world reached the last sample (2 s): every interval counted
  EXPECT_TRUE(wait_for_line(dir_ + "/monitor.txt", "status node=physics_node", 10 * kSecond,
                            "sim_time_ns=2000000000 "))
      << text("node.log");
  EXPECT_EQ(monitor.stop(), 0);
  EXPECT_EQ(node.stop(), 0) << text("node.log");

  const MonitorLog seen = MonitorLog::read(dir_ + "/monitor.txt");
  SeenStatus physics, glove;
  for (const auto& s : seen.statuses) (s.node == "physics_node" ? physics : glove) = s;
  ASSERT_EQ(glove.node, "glove_driver");
  // the driver read the log: its clamps and missing column; it moves no hand
  EXPECT_EQ(glove.clamped, 3u);
  EXPECT_EQ(glove.missing, 1u);
  EXPECT_EQ(glove.intervals, input.at("intervals").get<uint64_t>());
  EXPECT_EQ(glove.bridged, input.at("gaps_bridged").get<uint64_t>());
  EXPECT_EQ(glove.unbridged, input.at("gaps_not_bridged").get<uint64_t>());
  EXPECT_EQ(glove.interpolated, 0u);
  EXPECT_NEAR(glove.longest_s, 1.2, 1e-6);
  EXPECT_NE(text("driver.log").find("clamped 3, missing columns 1,"), std::string::npos)
      << "the driver's last line states the clamps it warned about: " << text("driver.log");
  // the physics node got clamped, complete samples: it counts the intervals as offline does
  EXPECT_EQ(physics.clamped, 0u);
  EXPECT_EQ(physics.missing, 0u) << "a HandSample carries all 22 joints";
  EXPECT_EQ(physics.intervals, input.at("intervals").get<uint64_t>());
  EXPECT_EQ(physics.interpolated, input.at("intervals_interpolated").get<uint64_t>());
  EXPECT_EQ(physics.bridged, 1u);
  EXPECT_EQ(physics.unbridged, 2u);
  EXPECT_EQ(physics.lost, input.at("glove_lost").get<uint64_t>());
  EXPECT_EQ(physics.lost, 1u);
  EXPECT_EQ(input.at("clamped"), 3);
  EXPECT_EQ(input.at("missing_columns"), 1);
}

TEST_F(PhysicsNodeTest, RealTimeHoldsOneKilohertzAndTheHandFollowsTheSamples) {
  ChildProcess node = start("physics_node", {}, "node.log");
  ChildProcess monitor = start("test_cockpit_monitor", {"--out", dir_ + "/monitor.txt"}, "monitor.log");
  ChildProcess driver =
      start("glove_driver", {"--source", "replay", "--log", sweep_log(), "--loop"}, "driver.log");
  // ten seconds of streaming from the node's first status: how long the node takes to start
  // (a sanitized one loads the cockpit's models for 3 s) is not part of what this test measures
  ASSERT_TRUE(wait_for_line(dir_ + "/monitor.txt", "status node=physics_node", 60 * kSecond))
      << text("node.log");
  std::this_thread::sleep_for(std::chrono::seconds(10));
  EXPECT_EQ(driver.stop(), 0);
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  EXPECT_EQ(monitor.stop(), 0);
  EXPECT_EQ(node.stop(), 0) << text("node.log");

  const MonitorLog seen = MonitorLog::read(dir_ + "/monitor.txt");
  // the statuses of full seconds with the glove streaming
  std::vector<double> rates;
  uint64_t late = 0;
  for (const auto& s : seen.statuses) {
    if (s.node != "physics_node" || !s.alive) continue;
    rates.push_back(s.rate_hz);
    late = s.late;
  }
  ASSERT_GE(rates.size(), 8u) << "expected a status a second while streaming";
  double sum = 0;
  for (std::size_t i = 1; i < rates.size(); ++i) sum += rates[i];  // the first may be partial
  const double mean_hz = sum / static_cast<double>(rates.size() - 1);
  std::printf("physics step rate %.2f Hz over %zu s, late steps %llu\n", mean_hz, rates.size() - 1,
              static_cast<unsigned long long>(late));
  // the pacing never runs ahead of the clock, and it steps on (the rate itself is a figure:
  // bench/, and a loaded machine makes steps late, which the node counts)
  EXPECT_LE(mean_hz, 1020.0);
  EXPECT_GT(mean_hz, sanitized() ? 50.0 : 250.0);

  // every hand_state shows the wrist at the source time it names: the log interpolated there
  physics::Scene scene = load_scene(source_dir() + "/config/cockpit.yaml");
  const auto log = hand::read_glove_log(sweep_log(), scene.hands[0]);
  const int64_t t0 = log.samples.front().t_ns;
  const int64_t pass_ns = log.samples.back().t_ns - t0 + 1'000'000;
  auto looped = [&](int64_t pass, std::size_t i) {  // sample i of pass `pass` as replayed
    hand::GloveSample s = log.samples[i % log.samples.size()];
    s.t_ns += (pass + static_cast<int64_t>(i / log.samples.size())) * pass_ns;
    return s;
  };
  int tracked = 0, exact = 0, off = 0;
  for (const auto& h : seen.hands) {
    if (!h.tracking) continue;
    const int64_t pass = (h.sample_time_ns - t0) / pass_ns;
    const auto index = static_cast<std::size_t>((h.sample_time_ns - t0) % pass_ns / 1'000'000);
    ASSERT_LT(index, log.samples.size());
    const auto shown = physics_io::interpolate_sample(looped(pass, index), looped(pass, index + 1),
                                                      h.sample_time_ns);
    const auto expected = physics_io::hand_input_from_glove(scene.hands[0], shown);
    const double error_m = (h.position - expected.X_GH.translation()).norm();
    // a sample lost on the best-effort stream is interpolated across: within a micrometre. A node
    // that falls behind (the sanitizers, or a busy machine: a late step) resynchronises with a
    // jump of the input, and the drawn proxy hand catches up at its maximum speed: those few
    // states are off, counted below, and printed.
    if (error_m >= 1e-6 && ++off <= 10)  // the first few; the count follows
      std::printf("seq %llu drawn %.2e m off (catching up)\n",
                  static_cast<unsigned long long>(h.seq), error_m);
    exact += error_m < 1e-9 ? 1 : 0;
    ++tracked;
  }
  std::printf("%d of %d tracked hand states exact, %d more than a micrometre off\n", exact,
              tracked, off);
  EXPECT_GT(tracked, sanitized() ? 50 : 500) << "about 90 hand states a second for 10 s";
  // under the sanitizers (-O1, 5-15x slower) the node cannot step 1 kHz (CI's TSan run: 219 Hz)
  // and resynchronises over and over: 87 % exact here, 68 % on CI's busy machine; an
  // interpolation gone wrong leaves next to none exact
  EXPECT_GE(exact, tracked * (sanitized() ? 25 : 98) / 100)
      << "all but the states next to a lost sample (or a resynchronisation) are exact";
}

TEST_F(PhysicsNodeTest, KilledGloveDriverReleasesWithGloveLostAndARestartResumesTracking) {
  expect_clean_shm_ = false;  // kill -9 leaves the driver's segments; the test cleans them
  ChildProcess node = start("physics_node", {}, "node.log");
  ChildProcess monitor = start("test_cockpit_monitor", {"--out", dir_ + "/monitor.txt"}, "monitor.log");
  // Under the sanitizers the real-time node steps 200-300 times a second and resynchronises
  // every 100 steps behind, skipping 0.1 s of the glove each time: at full speed that skipped
  // the whole closing of the hand once (CI's TSan run, no grasp). At a quarter of the speed a
  // skip is 25 ms of the recording, which the proxy hand catches up with.
  ChildProcess driver = start("glove_driver",
                              {"--source", "replay", "--log", grasp_log(), "--rate",
                               sanitized() ? "0.25" : "1"},
                              "driver.log");
  const std::string monitor_path = dir_ + "/monitor.txt";
  // the grasp comes 2.6 s into the recording
  ASSERT_TRUE(wait_for_line(monitor_path, "kind=grasp", (sanitized() ? 40 : 20) * kSecond))
      << text("node.log");
  std::this_thread::sleep_for(std::chrono::milliseconds(500));  // lifting it
  driver.signal(SIGKILL);
  EXPECT_EQ(driver.wait(5 * kSecond), 128 + SIGKILL);
  ASSERT_TRUE(wait_for_line(monitor_path, "reason=glove lost", 5 * kSecond)) << text("node.log");
  EXPECT_TRUE(node.running()) << "the node must keep running";
  // the hand holds its pose, shown as not tracking, while the status reports the glove lost
  EXPECT_TRUE(wait_for_line(monitor_path, "tracking=0", 2 * kSecond));
  EXPECT_TRUE(wait_for_line(monitor_path, "alive=0", 2 * kSecond, "reason=glove lost"));
  const int64_t restarted_ns = monotonic_now_ns();
  ChildProcess again = start("glove_driver", {"--source", "replay", "--log", sweep_log()}, "driver2.log");
  ASSERT_TRUE(wait_for_line(monitor_path, "node=physics_node state=1", 5 * kSecond,
                            /*after_line=*/"reason=glove lost"))
      << text("node.log");
  // a tracked hand state made of the new driver's samples (stamped after it started): how long
  // the driver takes to start and match is no part of it (0.3 s here, more under the sanitizers)
  bool resumed = false;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(sanitized() ? 30 : 10);
  while (!resumed && std::chrono::steady_clock::now() < deadline) {
    for (const SeenHand& h : MonitorLog::read(monitor_path).hands)
      resumed = resumed || (h.tracking && h.source_stamp_ns > restarted_ns);
    if (!resumed) std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  EXPECT_TRUE(resumed) << "tracking resumed\n" << text("driver2.log") << text("node.log");
  EXPECT_EQ(again.stop(), 0);
  EXPECT_EQ(monitor.stop(), 0);
  EXPECT_EQ(node.stop(), 0) << text("node.log");
}

TEST_F(PhysicsNodeTest, NanAndStaleSamplesAreRejectedAndCounted) {
  ChildProcess node = start("physics_node", {}, "node.log");
  ChildProcess monitor = start("test_cockpit_monitor", {"--out", dir_ + "/monitor.txt"}, "monitor.log");
  ChildProcess pub = start("test_hand_sample_pub", {"--profile", "stream", "--count", "2000",
                                                    "--all-valid", "--nan-at", "500", "--stale-at",
                                                    "900"},
                           "pub.log");
  EXPECT_EQ(pub.wait(30 * kSecond), 0) << text("pub.log");
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));  // a status after the last sample
  EXPECT_TRUE(node.running()) << "the node must keep running";
  EXPECT_EQ(monitor.stop(), 0);
  EXPECT_EQ(node.stop(), 0) << text("node.log");
  const MonitorLog seen = MonitorLog::read(dir_ + "/monitor.txt");
  ASSERT_FALSE(seen.statuses.empty());
  const auto& last = seen.statuses.back();
  EXPECT_EQ(last.nonfinite, 1u);
  EXPECT_EQ(last.stale, 1u);
  EXPECT_EQ(last.rejected, 2u);
  EXPECT_GT(last.received, 1500u);  // best effort: nearly all of the other 1,998 arrive
}

}  // namespace
}  // namespace vcockpit::test
