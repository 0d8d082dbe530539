// systems_node as a real process over loopback DDS: in a lockstep rig (physics node, glove driver,
// systems node) flying the bundled procedures it writes the files and the score systems_node
// --offline writes from the offline physics run, byte for byte; killed with SIGKILL during a gear transit and restarted with --resume, the
// transit ends when it would have without the kill; bad files and flags are refused by name.

#include <gtest/gtest.h>

#include <cmath>
#include <csignal>
#include <fstream>
#include <map>
#include <string>
#include <thread>
#include <vector>

#include "dds/dds_options.hpp"
#include "dds/dds_participant.hpp"
#include "idl/topics/systems_topics.hpp"
#include "physics_node/config/scene_config.hpp"
#include "physics_node/io/offline_runner.hpp"
#include "tests/support/process.hpp"
#include "tests/support/process_test.hpp"
#include "tests/support/test_env.hpp"

namespace vcockpit::test {
namespace {

class SystemsNodeTest : public ProcessTest {};

// Waits until the systems node's cockpit/node_status says it has taken `frames` control frames
// (its `received`; sent once a second).
bool wait_for_frames_taken(Reader<cockpit::NodeStatus>& statuses, uint64_t frames, int64_t timeout_ns) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::nanoseconds(timeout_ns);
  cockpit::NodeStatus s;
  while (std::chrono::steady_clock::now() < deadline) {
    while (statuses.take(s))
      if (s.node_name().to_string() == "systems_node" && s.received() >= frames) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return false;
}

// Plays the physics' start: every control's info written, and `frame` set to every control in
// its first position but the avionics master, on. Returns the gear lever's index (-1: none).
int publish_control_infos(const physics::Scene& scene, Writer<cockpit::ControlInfo>& infos,
                          cockpit::ControlFrame& frame) {
  int gear = -1;
  for (std::size_t c = 0; c < scene.controls.size(); ++c) {
    const physics::ControlSpec& spec = scene.controls[c];
    cockpit::ControlInfo info;
    info.control_id(static_cast<uint32_t>(c));
    info.name(spec.name);
    info.joint(spec.joint == physics::JointKind::kRevolute ? cockpit::REVOLUTE : cockpit::PRISMATIC);
    std::string names;
    for (const physics::ControlPosition& p : spec.positions) names += p.name + "|";
    info.position_names(names);
    info.position_count(static_cast<uint32_t>(spec.positions.size()));
    infos.write(info);
    const int position = spec.name == "avionics_master" ? 1 : 0;
    if (spec.name == "gear") gear = static_cast<int>(c);
    frame.position().push_back(position);
    frame.coordinate().push_back(spec.positions[static_cast<std::size_t>(position)].q);
  }
  return gear;
}

// The test in the physics node's place: the cockpit's control infos written, and on the same
// participant a writer of control frames and a reader of the systems' events.
struct PhysicsStandIn {
  physics::Scene scene = load_scene(config_path("cockpit.yaml"));
  DdsParticipant participant{resolve_dds_options(DdsFlags{}), "systems_node_test"};
  Writer<cockpit::ControlInfo> infos = participant.make_writer<cockpit::ControlInfo>("state");
  Writer<cockpit::ControlFrame> frames = participant.make_writer<cockpit::ControlFrame>("control_frames");
  Reader<cockpit::SystemsEvent> events = participant.make_reader<cockpit::SystemsEvent>("event");
  cockpit::ControlFrame first_frame;  // as publish_control_infos sets it
  int gear = publish_control_infos(scene, infos, first_frame);
};

// One bundled log in a lockstep rig and offline; `failures` for both, `expected` the pinned
// score (tests/data/procedures/) or "" when none is pinned.
struct RigCase {
  std::string log;
  std::vector<std::string> failures;
  std::string expected;
};

TEST_F(SystemsNodeTest, LockstepRigWritesTheOfflineSystemsFilesAndScoreByteForByte) {
  const std::string lesson = source_dir() + "/config/lessons/default.yaml";
  // each bundled procedure log (the right one with the instructor's failure at 50 s); under the
  // sanitizers, whose physics steps a few times slower, the 15.7 s knob log only
  const std::vector<RigCase> cases =
      sanitized() ? std::vector<RigCase>{{"panel_knobs", {}, ""}}
                  : std::vector<RigCase>{{"procedures_right", {"50:gear_unsafe_left"}, "right_gear_unsafe"},
                                         {"procedures_errors_right", {}, "errors"}};
  for (const RigCase& c : cases) {
    SCOPED_TRACE(c.log);
    const std::string log = source_dir() + "/config/glove_logs/" + c.log + ".csv";
    physics_io::OfflineOptions offline;
    offline.scene_path = source_dir() + "/config/cockpit.yaml";
    offline.log_paths = {log};
    offline.out_dir = dir_ + "/offline_" + c.log;
    const auto summary = physics_io::run_offline(load_scene(offline.scene_path), offline);
    const int64_t end_ns = std::llround(summary.simulated_s * 1e9);
    std::vector<std::string> extra = {"--lesson", lesson};
    for (const std::string& f : c.failures) extra.insert(extra.end(), {"--failure-at", f});
    std::vector<std::string> args = {"--offline", "--control-frames", offline.out_dir + "/control_frames.csv",
                                     "--out", dir_ + "/offline_systems_" + c.log};
    args.insert(args.end(), extra.begin(), extra.end());
    ChildProcess replay = start("systems_node", args, "offline_systems.log");
    ASSERT_EQ(replay.wait(60 * kSecond), 0) << text("offline_systems.log");

    DdsParticipant participant(resolve_dds_options(DdsFlags{}), "systems_node_test");
    auto statuses = participant.make_reader<cockpit::NodeStatus>("state");
    std::vector<std::string> rig_args = {"--out", dir_ + "/rig_systems_" + c.log};
    rig_args.insert(rig_args.end(), extra.begin(), extra.end());
    ChildProcess systems = start("systems_node", rig_args, "systems.log");
    ChildProcess node = start("physics_node", {"--lockstep", "--wait-frame-readers", "1"}, "node.log");
    ChildProcess driver = start("glove_driver", {"--source", "replay", "--log", log, "--lockstep",
                                                 "--rate", "0"},
                                "driver.log");
    ASSERT_EQ(driver.wait(240 * kSecond), 0) << text("driver.log");
    // one frame every 10 ms of the run, from 10 ms to its end
    EXPECT_TRUE(wait_for_frames_taken(statuses, static_cast<uint64_t>(end_ns / 10'000'000), 240 * kSecond))
        << text("systems.log");
    EXPECT_EQ(systems.stop(), 0) << text("systems.log");
    EXPECT_EQ(node.stop(), 0) << text("node.log");

    for (const char* file : {"systems_events.jsonl", "systems.csv", "systems_summary.json",
                             "procedures.json", "procedure_events.jsonl"}) {
      const std::string rig = read_text(dir_ + "/rig_systems_" + c.log + "/" + file);
      // (the knob log changes no reported system: the avionics master stays off)
      if (!(c.log == "panel_knobs" && std::string(file) == "systems_events.jsonl")) {
        EXPECT_FALSE(rig.empty()) << file;
      }
      EXPECT_TRUE(rig == read_text(dir_ + "/offline_systems_" + c.log + "/" + file))
          << file << " differs from systems_node --offline's";
    }
    // the score the bundled log is pinned to (tests/scenario/procedure_logs_test)
    if (!c.expected.empty()) {
      EXPECT_EQ(read_text(dir_ + "/rig_systems_" + c.log + "/procedures.json"),
                read_text(source_dir() + "/tests/data/procedures/" + c.expected + ".json"));
    }
    if (c.log == "procedures_right") {
      const std::string events = read_text(dir_ + "/rig_systems_" + c.log + "/systems_events.jsonl");
      // the avionics master pushed on at 1.59 s (the log's), and the failure at 50 s
      EXPECT_NE(events.find("{\"t_ns\": 1590000000, \"t_s\": 1.590, \"event\": \"change\", "
                            "\"system\": \"bus\", \"from\": 0, \"to\": 1}"),
                std::string::npos)
          << events;
      EXPECT_NE(events.find("\"t_ns\": 50000000000, \"t_s\": 50.000, \"event\": \"failure_inserted\", "
                            "\"failure\": \"gear_unsafe_left\""),
                std::string::npos)
          << events;
    }
  }
}

// The test plays the physics: it publishes every control's info and a frame every 10 ms of
// simulated time (five times faster than real time), the avionics master on and the gear lever
// up at 1 s. The systems node is killed 3 s into the simulated time, during the 6.5-7.5 s
// transits, and restarted with --resume while frames go on.
TEST_F(SystemsNodeTest, KilledDuringAGearTransitResumesWhereItWas) {
  PhysicsStandIn stand_in;
  ASSERT_GE(stand_in.gear, 0);
  const std::size_t gear = static_cast<std::size_t>(stand_in.gear);
  cockpit::ControlFrame frame = stand_in.first_frame;
  const std::string checkpoint = dir_ + "/state/systems.ckpt";
  const std::vector<std::string> args = {"--checkpoint", checkpoint, "--checkpoint-every", "0.5"};
  auto systems = std::make_unique<ChildProcess>(start("systems_node", args, "systems1.log"));
  ASSERT_TRUE(stand_in.frames.wait_for_matched(1, 30 * kSecond)) << text("systems1.log");

  uint64_t seq = 0;
  const auto publish_until = [&](int64_t end_ns) {
    while (frame.sim_time_ns() < end_ns) {
      frame.sim_time_ns(frame.sim_time_ns() + 10'000'000);
      frame.seq(++seq);
      frame.position()[gear] = frame.sim_time_ns() >= kSecond ? 1 : 0;  // up
      stand_in.frames.write(frame);
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
  };
  publish_until(2 * kSecond);
  // frames no physics node would send: refused and counted, and the node goes on
  cockpit::ControlFrame bad = frame;
  bad.sim_time_ns(frame.sim_time_ns() + 10'000'000);
  bad.position().pop_back();
  bad.coordinate().pop_back();
  stand_in.frames.write(bad);
  bad = frame;
  bad.sim_time_ns(frame.sim_time_ns() + 10'000'000);
  bad.coordinate()[0] = std::nan("");
  stand_in.frames.write(bad);
  bad.coordinate()[0] = 0.0;
  bad.position()[0] = 7;
  stand_in.frames.write(bad);
  publish_until(3 * kSecond);
  // the last checkpoint is at most 0.5 s old: wait for one past 2.5 s, then kill
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  bool saved = false;
  while (!saved && std::chrono::steady_clock::now() < deadline) {
    std::ifstream in(checkpoint);
    std::string line;
    while (std::getline(in, line))
      if (line.rfind("time_ns ", 0) == 0 && std::stoll(line.substr(8)) >= 2'500'000'000) saved = true;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ASSERT_TRUE(saved) << text("systems1.log");
  EXPECT_NE(text("systems1.log").find("a control frame refused"), std::string::npos) << text("systems1.log");
  systems->signal(SIGKILL);
  EXPECT_EQ(systems->wait(10 * kSecond), 128 + SIGKILL);
  expect_clean_shm_ = false;  // a killed process leaves its DDS files
  publish_until(3'200'000'000);  // the physics goes on while it is down
  std::vector<std::string> resume_args = args;
  resume_args.push_back("--resume");
  systems = std::make_unique<ChildProcess>(start("systems_node", resume_args, "systems2.log"));
  ASSERT_TRUE(stand_in.frames.wait_for_matched(1, 30 * kSecond));
  publish_until(9 * kSecond);

  // each leg's "up" once, at 1 s plus its transit time, to the step
  std::map<std::string, std::vector<int64_t>> up_at;
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  cockpit::SystemsEvent e;
  while (up_at.size() < 3 && std::chrono::steady_clock::now() < until) {
    while (stand_in.events.take(e))
      if (e.kind() == cockpit::SYSTEM_CHANGED && e.to_text().to_string() == "up")
        up_at[e.name().to_string()].push_back(e.sim_time_ns());
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  EXPECT_EQ(up_at["gear_nose"], std::vector<int64_t>{7'500'000'000}) << text("systems2.log");
  EXPECT_EQ(up_at["gear_left"], std::vector<int64_t>{8'000'000'000});
  EXPECT_EQ(up_at["gear_right"], std::vector<int64_t>{8'500'000'000});
  EXPECT_NE(text("systems2.log").find("resumed from"), std::string::npos) << text("systems2.log");
  EXPECT_EQ(systems->stop(), 0);
}

// A burst of control frames written while the systems node is stopped (a loaded machine stalls
// a reader so): every frame arrives once it goes on, and a 0.3 s flick of the gear lever
// in its middle is stepped on at its own frames' times. With the frames' history as deep as the
// other events' (100), the writer dropped frames: the systems stepped over the gaps with later
// frames' controls, and the gear moved a step early (a CI run lost a 0.85 s switch pulse so).
TEST_F(SystemsNodeTest, ABurstOfFramesReachesItWholeWithAShortFlickInIt) {
  PhysicsStandIn stand_in;
  ASSERT_GE(stand_in.gear, 0);
  const std::size_t gear = static_cast<std::size_t>(stand_in.gear);
  cockpit::ControlFrame frame = stand_in.first_frame;
  auto statuses = stand_in.participant.make_reader<cockpit::NodeStatus>("state");
  auto systems = std::make_unique<ChildProcess>(start("systems_node", {}, "systems.log"));
  ASSERT_TRUE(stand_in.frames.wait_for_matched(1, 30 * kSecond)) << text("systems.log");
  // the first frame alone, taken (the node bound to the controls); then, while the node is
  // stopped (a stalled reader), 1,499 more of 10 ms; the lever up from 5.00 s to 5.30 s only
  frame.sim_time_ns(10'000'000);
  frame.seq(1);
  stand_in.frames.write(frame);
  ASSERT_TRUE(wait_for_frames_taken(statuses, 1, 30 * kSecond)) << text("systems.log");
  systems->signal(SIGSTOP);
  for (uint64_t seq = 2; seq <= 1500; ++seq) {
    frame.sim_time_ns(static_cast<int64_t>(seq) * 10'000'000);
    frame.seq(seq);
    const bool up = frame.sim_time_ns() >= 5 * kSecond && frame.sim_time_ns() < 5'300'000'000;
    frame.position()[gear] = up ? 1 : 0;
    stand_in.frames.write(frame);
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  systems->signal(SIGCONT);
  // the gear starts up as the lever goes up at 5 s, and back down as it comes down at 5.3 s
  std::vector<int64_t> retracting_at, extending_at;
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  cockpit::SystemsEvent e;
  while (extending_at.empty() && std::chrono::steady_clock::now() < until) {
    while (stand_in.events.take(e)) {
      if (e.kind() != cockpit::SYSTEM_CHANGED || e.name().to_string() != "gear_nose") continue;
      if (e.to_text().to_string() == "retracting") retracting_at.push_back(e.sim_time_ns());
      if (e.to_text().to_string() == "extending") extending_at.push_back(e.sim_time_ns());
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  EXPECT_EQ(retracting_at, std::vector<int64_t>{5 * kSecond}) << text("systems.log");
  EXPECT_EQ(extending_at, std::vector<int64_t>{5'300'000'000}) << text("systems.log");
  EXPECT_EQ(systems->stop(), 0);
}

TEST_F(SystemsNodeTest, BadFilesAndFlagsAreRefusedByName) {
  const std::string bad_yaml = dir_ + "/bad.yaml";
  std::ofstream(bad_yaml) << "rate_hz: 100\nsystems:\n  - {name: a, logic: \"gear.down &&\"}\n";
  const std::string bad_name = dir_ + "/bad_name.yaml";
  std::ofstream(bad_name) << "systems:\n  - {name: a, logic: \"gear.dwn\"}\n";
  const std::string frames = dir_ + "/frames.csv";
  std::ofstream(frames) << "# vcockpit control frames, version 1\n"
                           "# control: gear prismatic down|up\n"
                           "t_ns,gear.position,gear.q\n"
                           "10000000,0,0\n"
                           "20000000,2,0\n";
  const std::string good_frames = dir_ + "/good_frames.csv";
  std::ofstream(good_frames) << "# vcockpit control frames, version 1\n"
                                "# control: gear prismatic down|up\n"
                                "t_ns,gear.position,gear.q\n"
                                "10000000,0,0\n";
  expect_each_refused("systems_node", {
      {{"--aircraft", bad_yaml, "--offline", "--control-frames", good_frames, "--out", dir_ + "/o"},
       "bad.yaml:3:22: systems[0].logic: at character 13: expected a value"},
      {{"--aircraft", bad_name, "--offline", "--control-frames", good_frames, "--out", dir_ + "/o"},
       "bad_name.yaml:2:22: systems[0].logic: at character 1: control 'gear' has no position 'dwn'"},
      {{"--aircraft", bad_name, "--offline", "--control-frames", frames, "--out", dir_ + "/o"},
       "frames.csv:5: gear.position: '2' is not one of its 2 positions"},
      {{"--offline", "--out", dir_ + "/o"}, "--offline needs --control-frames"},
      {{"--failure-at", "soon:engine_fire"}, "--failure-at 'soon:engine_fire': 'soon' is not a time"},
      {{"--checkpoint-every", "nan"}, "--checkpoint-every"},
  });
  EXPECT_FALSE(std::ifstream(dir_ + "/o/systems_events.jsonl").good());  // nothing half-written
}

}  // namespace
}  // namespace vcockpit::test
