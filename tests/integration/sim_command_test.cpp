// The instructor's sim commands over loopback DDS (cockpit/sim_command, answered on
// cockpit/sim_ack): freeze stops the world's time while the glove keeps arriving, and unfreeze
// goes on from the frozen time with the objects where they were; a reset puts the objects and
// controls back (to the start, or to a named checkpoint) while time goes on, and lets go of a
// held object; a checkpoint that does not exist is refused with its name; a glove driver that
// reached the end of its log waits, and starts over on a restart with its time going on; a
// replay restarted while the physics is frozen waits at its start until time goes on.

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "common/clock.hpp"
#include "dds/dds_options.hpp"
#include "dds/dds_participant.hpp"
#include "physics_node/config/scene_config.hpp"
#include "tests/support/process.hpp"
#include "tests/support/process_test.hpp"
#include "tests/support/test_env.hpp"

namespace vcockpit::test {
namespace {

constexpr int64_t kWait_ns = 15'000'000'000;
const char* kGraspLog = "/config/glove_logs/reach_grasp_lift_release.csv";
// the hand turns the panel's knobs, far from the cup on the console
const char* kKnobsLog = "/config/glove_logs/panel_knobs.csv";

// A test's instructor: sends sim commands and waits for their acknowledgements.
struct Instructor {
  explicit Instructor(DdsParticipant& participant)
      : commands(participant.make_writer<cockpit::SimCommand>("command")),
        acks(participant.make_reader<cockpit::SimAck>("event")) {}

  bool matched(int readers) { return commands.wait_for_matched(readers, kWait_ns); }

  // Sends `kind` and returns the acknowledgement from `node` (accepted() false if none came).
  cockpit::SimAck send(cockpit::SimCommandKind kind, const std::string& node,
                       const std::string& checkpoint = "") {
    cockpit::SimCommand command;
    command.seq(seq);
    command.kind(kind);
    command.checkpoint(checkpoint);
    command.source("sim_command_test");
    commands.write(command);
    cockpit::SimAck ack;
    const int64_t deadline = monotonic_now_ns() + kWait_ns;
    while (monotonic_now_ns() < deadline) {
      acks.wait_for_data(100'000'000);
      while (acks.take(ack))
        if (ack.command_seq() == seq && ack.node_name() == node) {
          ++seq;
          return ack;
        }
    }
    ++seq;
    ADD_FAILURE() << "no acknowledgement from " << node << " for command kind " << kind;
    return {};
  }

  Writer<cockpit::SimCommand> commands;
  Reader<cockpit::SimAck> acks;
  uint64_t seq = 0;
};

// The newest hand_state and object_state of one object, as they arrive.
struct WorldWatch {
  explicit WorldWatch(DdsParticipant& participant, uint32_t object)
      : hands(participant.make_reader<cockpit::HandState>("stream")),
        objects(participant.make_reader<cockpit::ObjectState>("state")),
        object_id(object) {}

  // Takes what arrived for `ns`; returns the largest hand sim time seen in that while (-1: none).
  int64_t watch(int64_t ns) {
    int64_t newest = -1;
    const int64_t until = monotonic_now_ns() + ns;
    while (monotonic_now_ns() < until) {
      hands.wait_for_data(20'000'000);
      while (hands.take(hand)) newest = std::max(newest, hand.sim_time_ns());
      while (objects.take(object))
        if (object.object_id() == object_id) {
          p_object = {object.X_GO().position_m().x(), object.X_GO().position_m().y(),
                      object.X_GO().position_m().z()};
          held_by = object.held_by_hand_id();
        }
    }
    return newest;
  }

  Reader<cockpit::HandState> hands;
  Reader<cockpit::ObjectState> objects;
  uint32_t object_id;
  cockpit::HandState hand;
  cockpit::ObjectState object;
  Eigen::Vector3d p_object = Eigen::Vector3d::Constant(NAN);
  int32_t held_by = -1;
};

class SimCommandTest : public ProcessTest {};

TEST_F(SimCommandTest, FreezeStopsTimeWhileTheGloveArrivesAndUnfreezeGoesOnFromThere) {
  const physics::Scene scene = load_scene(config_path("cockpit.yaml"));
  const int cup = scene.find_object("cup");
  ChildProcess node = start("physics_node", {}, "node.log");
  ChildProcess glove = start("glove_driver", {"--source", "replay", "--log", source_dir() + kKnobsLog,
                                              "--loop"},
                             "glove.log");
  DdsParticipant participant(resolve_dds_options(DdsFlags{}), "sim_command_test");
  Instructor instructor(participant);
  WorldWatch world(participant, static_cast<uint32_t>(cup));
  auto statuses = participant.make_reader<cockpit::NodeStatus>("state");
  ASSERT_TRUE(instructor.matched(2)) << text("node.log") << text("glove.log");
  int64_t t_ns = -1;
  for (int i = 0; i < 50 && t_ns < 300'000'000; ++i) t_ns = std::max(t_ns, world.watch(100'000'000));
  ASSERT_GE(t_ns, 300'000'000) << "the world runs: " << text("node.log");

  const cockpit::SimAck frozen = instructor.send(cockpit::FREEZE, "physics_node");
  EXPECT_TRUE(frozen.accepted());
  EXPECT_TRUE(frozen.frozen());
  EXPECT_NE(std::string(frozen.detail()).find("frozen at"), std::string::npos) << frozen.detail();
  world.watch(200'000'000);  // what was on its way
  const Eigen::Vector3d cup_frozen = world.p_object;
  cockpit::NodeStatus status;
  while (statuses.take(status)) {  // from before the freeze
  }
  // the glove keeps arriving (node_status received grows), the world's time stands still
  uint64_t received_first = 0, received_last = 0;
  int64_t newest_ns = -1;
  for (int i = 0; i < 25; ++i) {
    newest_ns = std::max(newest_ns, world.watch(100'000'000));
    while (statuses.take(status)) {
      if (status.node_name() != "physics_node") continue;
      if (received_first == 0) received_first = status.received();
      received_last = status.received();
      EXPECT_EQ(std::string(status.detail()), "frozen");
    }
  }
  EXPECT_GT(received_last, received_first + 100) << "samples kept arriving while frozen";
  EXPECT_LE(newest_ns, frozen.sim_time_ns()) << "no time passed while frozen";
  EXPECT_LT((world.p_object - cup_frozen).norm(), 1e-9) << "nothing moved while frozen";

  const cockpit::SimAck going = instructor.send(cockpit::UNFREEZE, "physics_node");
  EXPECT_TRUE(going.accepted());
  EXPECT_FALSE(going.frozen());
  EXPECT_EQ(going.sim_time_ns(), frozen.sim_time_ns()) << "time goes on from where it stopped";
  const int64_t after_ns = world.watch(300'000'000);
  EXPECT_GT(after_ns, frozen.sim_time_ns()) << "time runs again";
  // 300 ms of wall time later, not the 2.5 s frozen plus those: no catching up
  EXPECT_LT(after_ns - frozen.sim_time_ns(), 2000 * 1'000'000LL);
  // the cup (resting on the console, the hand far from it) did not jump
  EXPECT_LT((world.p_object - cup_frozen).norm(), 0.002);
  EXPECT_EQ(node.stop(), 0) << text("node.log");
  EXPECT_EQ(glove.stop(), 0) << text("glove.log");
  EXPECT_NE(text("node.log").find("sim command from 'sim_command_test': frozen at"), std::string::npos);
}

TEST_F(SimCommandTest, ResetPutsObjectsAndControlsBackToTheStartOrACheckpoint) {
  const physics::Scene scene = load_scene(config_path("cockpit.yaml"));
  const int cup = scene.find_object("cup");
  const int lights = scene.find_control("landing_lights");
  ASSERT_GE(lights, 0);
  const Eigen::Vector3d cup_start = scene.objects[static_cast<std::size_t>(cup)].X_GO.translation();
  ChildProcess node = start("physics_node", {}, "node.log");
  DdsParticipant participant(resolve_dds_options(DdsFlags{}), "sim_command_test");
  Instructor instructor(participant);
  WorldWatch world(participant, static_cast<uint32_t>(cup));
  auto controls = participant.make_writer<cockpit::ControlCommand>("command");
  auto control_states = participant.make_reader<cockpit::ControlState>("state");
  auto grasps = participant.make_reader<cockpit::GraspEvent>("event");
  ASSERT_TRUE(instructor.matched(1)) << text("node.log");
  ASSERT_TRUE(controls.wait_for_matched(1, kWait_ns));
  auto lights_position = [&] {
    cockpit::ControlState state;
    int position = -1;
    for (int i = 0; i < 30; ++i) {
      control_states.wait_for_data(50'000'000);
      while (control_states.take(state))
        if (state.control_id() == static_cast<uint32_t>(lights)) position = static_cast<int>(state.position());
    }
    return position;
  };
  auto set_lights = [&](uint32_t position) {
    cockpit::ControlCommand command;
    command.control_id(static_cast<uint32_t>(lights));
    command.position(position);
    command.source("sim_command_test");
    controls.write(command);
    return lights_position();
  };
  // the lights on, kept as a checkpoint; then off again
  EXPECT_EQ(set_lights(2), 2);
  EXPECT_TRUE(instructor.send(cockpit::SAVE_CHECKPOINT, "physics_node", "lights on").accepted());
  EXPECT_EQ(set_lights(0), 0);
  const cockpit::SimAck back = instructor.send(cockpit::RESET_TO_CHECKPOINT, "physics_node", "lights on");
  EXPECT_TRUE(back.accepted()) << back.detail();
  EXPECT_EQ(lights_position(), 2) << "the checkpoint's position";
  const cockpit::SimAck missing = instructor.send(cockpit::RESET_TO_CHECKPOINT, "physics_node", "nope");
  EXPECT_FALSE(missing.accepted());
  EXPECT_EQ(std::string(missing.detail()), "no checkpoint 'nope'");

  // the glove grasps and lifts the cup; a reset to the start lets go of it and puts it back
  ChildProcess glove = start("glove_driver", {"--source", "replay", "--log", source_dir() + kGraspLog},
                             "glove.log");
  bool lifted = false;
  for (int i = 0; i < 150 && !lifted; ++i) {
    world.watch(100'000'000);
    lifted = world.held_by >= 0 && world.p_object.z() > cup_start.z() + 0.03;
  }
  ASSERT_TRUE(lifted) << text("node.log");
  const int64_t before_ns = world.hand.sim_time_ns();
  const cockpit::SimAck reset = instructor.send(cockpit::RESET_TO_START, "physics_node");
  EXPECT_TRUE(reset.accepted());
  EXPECT_GE(reset.sim_time_ns(), before_ns) << "time goes on";
  world.watch(100'000'000);
  EXPECT_LT((world.p_object - cup_start).norm(), 0.005) << "the cup back where it started";
  EXPECT_EQ(lights_position(), 0) << "the lights back off";
  cockpit::GraspEvent event;
  bool let_go = false;
  for (int i = 0; i < 20 && !let_go; ++i) {
    grasps.wait_for_data(50'000'000);
    while (grasps.take(event))
      let_go = let_go || (event.kind() == cockpit::RELEASE && std::string(event.reason()) == "scene reset");
  }
  EXPECT_TRUE(let_go) << "a RELEASE 'scene reset'";
  EXPECT_EQ(glove.stop(), 0);
  EXPECT_EQ(node.stop(), 0) << text("node.log");
}

TEST_F(SimCommandTest, AGloveDriverAtTheEndOfItsLogWaitsAndStartsOverOnARestart) {
  DdsParticipant participant(resolve_dds_options(DdsFlags{}), "sim_command_test");
  auto samples = participant.make_reader<cockpit::HandSample>("stream");
  Instructor instructor(participant);
  // the last second of the log, then the driver waits at its end
  ChildProcess glove = start("glove_driver", {"--source", "replay", "--log", source_dir() + kGraspLog,
                                              "--start-offset", "7.5", "--hold-at-end"},
                             "glove.log");
  ASSERT_TRUE(instructor.matched(1)) << text("glove.log");
  cockpit::HandSample sample;
  int64_t last_ns = -1;
  double x_last = 0;
  for (const int64_t deadline = monotonic_now_ns() + kWait_ns; monotonic_now_ns() < deadline;) {
    samples.wait_for_data(50'000'000);
    while (samples.take(sample)) {
      last_ns = sample.sample_time_ns();
      x_last = sample.X_MT().position_m().x();
    }
    if (text("glove.log").find("waiting for a restart") != std::string::npos) break;
  }
  ASSERT_NE(text("glove.log").find("waiting for a restart"), std::string::npos) << text("glove.log");
  ASSERT_GT(last_ns, 0);
  while (samples.take(sample)) last_ns = sample.sample_time_ns();
  EXPECT_EQ(glove.wait(500'000'000), -1) << "still running at its end";

  const cockpit::SimAck ack = instructor.send(cockpit::RESTART_REPLAY, "glove_driver");
  EXPECT_TRUE(ack.accepted()) << ack.detail();
  EXPECT_EQ(ack.sim_time_ns(), -1);
  bool resumed = false;
  for (int i = 0; i < 40 && !resumed; ++i) {
    samples.wait_for_data(50'000'000);
    while (samples.take(sample)) {
      if (resumed) continue;
      resumed = true;
      EXPECT_GT(sample.sample_time_ns(), last_ns) << "its time goes on";
      EXPECT_LT(sample.sample_time_ns() - last_ns, 100'000'000) << "one interval on, not more";
      EXPECT_NE(sample.X_MT().position_m().x(), x_last) << "from the start of the played part";
    }
  }
  EXPECT_TRUE(resumed) << text("glove.log");
  EXPECT_EQ(glove.stop(), 0) << text("glove.log");
}

// An instructor's rerun: freeze, restart replay, unfreeze. The replay waits at its first sample
// (given again and again, its time going on) while the physics is frozen, and plays from there
// when time goes on; started at once, the pilot's first actions played to a frozen world were
// lost when the instructor was slow to unfreeze.
TEST_F(SimCommandTest, AReplayRestartedWhileFrozenWaitsAtItsStartUntilTimeGoesOn) {
  ChildProcess node = start("physics_node", {}, "node.log");
  ChildProcess glove = start("glove_driver", {"--source", "replay", "--log", source_dir() + kGraspLog},
                             "glove.log");
  DdsParticipant participant(resolve_dds_options(DdsFlags{}), "sim_command_test");
  auto samples = participant.make_reader<cockpit::HandSample>("stream");
  Instructor instructor(participant);
  ASSERT_TRUE(instructor.matched(2)) << text("node.log") << text("glove.log");
  cockpit::HandSample sample;
  int received = 0;
  for (const int64_t deadline = monotonic_now_ns() + kWait_ns; received < 300 && monotonic_now_ns() < deadline;) {
    samples.wait_for_data(50'000'000);
    while (samples.take(sample)) ++received;
  }
  ASSERT_GE(received, 300) << "the replay plays: " << text("glove.log");

  const cockpit::SimAck frozen = instructor.send(cockpit::FREEZE, "physics_node");
  ASSERT_TRUE(frozen.frozen()) << frozen.detail();
  const cockpit::SimAck restarted = instructor.send(cockpit::RESTART_REPLAY, "glove_driver");
  ASSERT_TRUE(restarted.accepted()) << restarted.detail();
  // a second of frozen time: what was in flight before the restart, then the first sample over
  // and over, one sample interval apart
  std::vector<cockpit::HandSample> while_frozen;
  for (const int64_t until = monotonic_now_ns() + 1'000'000'000; monotonic_now_ns() < until;) {
    samples.wait_for_data(20'000'000);
    while (samples.take(sample)) while_frozen.push_back(sample);
  }
  ASSERT_GE(while_frozen.size(), 100u) << "it keeps giving samples: " << text("glove.log");
  const cockpit::HandSample held = while_frozen.back();
  const auto same_pose = [](const cockpit::HandSample& a, const cockpit::HandSample& b) {
    return a.X_MT().position_m().x() == b.X_MT().position_m().x() &&
           a.X_MT().position_m().y() == b.X_MT().position_m().y() &&
           a.joint_angles_rad() == b.joint_angles_rad();
  };
  std::size_t first_held = while_frozen.size() - 1;
  while (first_held > 0 && same_pose(while_frozen[first_held - 1], held)) --first_held;
  EXPECT_GE(while_frozen.size() - first_held, 100u)
      << "the first sample again for most of the frozen second, not the log playing on";
  for (std::size_t i = first_held + 1; i < while_frozen.size(); ++i) {
    const int64_t step_ns = while_frozen[i].sample_time_ns() - while_frozen[i - 1].sample_time_ns();
    ASSERT_GT(step_ns, 0) << "its time goes on at " << i;
    ASSERT_LT(step_ns, 100'000'000) << "one interval on at " << i;
  }
  EXPECT_NE(text("glove.log").find("the replay waits at its start"), std::string::npos) << text("glove.log");

  const cockpit::SimAck going = instructor.send(cockpit::UNFREEZE, "physics_node");
  EXPECT_FALSE(going.frozen());
  bool played = false;
  int64_t last_held_ns = held.sample_time_ns();
  for (const int64_t until = monotonic_now_ns() + 2'000'000'000; !played && monotonic_now_ns() < until;) {
    samples.wait_for_data(20'000'000);
    while (!played && samples.take(sample)) {
      if (same_pose(sample, held)) {
        last_held_ns = sample.sample_time_ns();
        continue;
      }
      played = true;
      EXPECT_GT(sample.sample_time_ns(), last_held_ns);
      EXPECT_LT(sample.sample_time_ns() - last_held_ns, 100'000'000) << "the log's second sample next";
    }
  }
  EXPECT_TRUE(played) << "the replay plays on after the unfreeze: " << text("glove.log");
  EXPECT_NE(text("glove.log").find("time goes on: the replay plays from its start"), std::string::npos)
      << text("glove.log");
  EXPECT_EQ(glove.stop(), 0) << text("glove.log");
  EXPECT_EQ(node.stop(), 0) << text("node.log");
}

}  // namespace
}  // namespace vcockpit::test
