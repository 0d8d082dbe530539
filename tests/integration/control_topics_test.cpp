// The physics node's control topics over loopback DDS: control_info describes every control of
// the default cockpit; a control_command sets a control, which the node reports as a COMMANDED
// control_event and a new control_state; a command for a position the control does not have is
// refused and named in the log, and the node keeps running.

#include <gtest/gtest.h>

#include <set>
#include <string>

#include "common/dds_options.hpp"
#include "common/dds_participant.hpp"
#include "physics_node/config/scene_config.hpp"
#include "tests/support/monitor_log.hpp"
#include "tests/support/process.hpp"
#include "tests/support/process_test.hpp"
#include "tests/support/test_env.hpp"

namespace vcockpit::test {
namespace {

constexpr int64_t kWait_ns = 10'000'000'000;

class ControlTopicsTest : public ProcessTest {};

TEST_F(ControlTopicsTest, ACommandSetsAControlAndIsReportedAsCommanded) {
  const physics::Scene scene = load_scene(source_dir() + "/config/cockpit.yaml");
  const int landing = scene.find_control("landing_lights");
  ASSERT_GE(landing, 0);
  ChildProcess node = start("physics_node", {}, "node.log");

  DdsParticipant participant(resolve_dds_options(DdsFlags{}), "control_topics_test");
  auto infos = participant.make_reader<cockpit::ControlInfo>("state");
  auto states = participant.make_reader<cockpit::ControlState>("state");
  auto events = participant.make_reader<cockpit::ControlEvent>("event");
  auto commands = participant.make_writer<cockpit::ControlCommand>("event");
  ASSERT_TRUE(infos.wait_for_matched(1, kWait_ns)) << text("node.log");
  ASSERT_TRUE(events.wait_for_matched(1, kWait_ns));
  ASSERT_TRUE(commands.wait_for_matched(1, kWait_ns));

  // every control described, with its positions (transient local: sent before we joined)
  std::set<uint32_t> described;
  cockpit::ControlInfo info;
  for (int tries = 0; tries < 100 && described.size() < scene.controls.size(); ++tries) {
    infos.wait_for_data(100'000'000);
    while (infos.take(info)) {
      described.insert(info.control_id());
      const physics::ControlSpec& c = scene.controls.at(info.control_id());
      EXPECT_EQ(info.name(), c.name);
      EXPECT_EQ(info.position_count(), c.positions.size());
      EXPECT_EQ(info.object_id(), static_cast<uint32_t>(c.body));
      std::string names;
      for (const auto& p : c.positions) names += p.name + "|";
      EXPECT_EQ(info.position_names(), names);
      EXPECT_EQ(info.position_coordinates()[1], c.positions[1].q);
      EXPECT_EQ(info.lit_position(), c.lit_when) << "members after the names arrive whole";
    }
  }
  EXPECT_EQ(described.size(), scene.controls.size());

  cockpit::ControlCommand command;
  command.seq(0);
  command.control_id(static_cast<uint32_t>(landing));
  command.position(2);  // "on"
  command.source("control_topics_test");
  commands.write(command);
  bool reported = false;
  cockpit::ControlEvent event;
  for (int tries = 0; tries < 100 && !reported; ++tries) {
    events.wait_for_data(100'000'000);
    while (events.take(event)) {
      if (event.control_id() != static_cast<uint32_t>(landing)) continue;
      EXPECT_EQ(event.from_position(), 0u);
      EXPECT_EQ(event.to_position(), 2u);
      EXPECT_EQ(event.cause(), cockpit::COMMANDED);
      EXPECT_EQ(event.hand_id(), -1);
      reported = true;
    }
  }
  EXPECT_TRUE(reported) << text("node.log");
  bool state_seen = false;
  cockpit::ControlState state;
  for (int tries = 0; tries < 50 && !state_seen; ++tries) {
    states.wait_for_data(100'000'000);
    while (states.take(state))
      if (state.control_id() == static_cast<uint32_t>(landing) && state.position() == 2u) {
        state_seen = true;
        // (set there, then held by its detent: the bat's weight sags it a few hundredths of a
        // degree)
        EXPECT_NEAR(state.coordinate(), scene.controls[landing].positions[2].q, 0.01);
      }
  }
  EXPECT_TRUE(state_seen);

  command.seq(1);
  command.position(7);  // it has 3
  commands.write(command);
  EXPECT_TRUE(wait_for_line(dir_ + "/node.log", "refused: control", kWait_ns)) << text("node.log");
  EXPECT_EQ(node.stop(), 0) << text("node.log");
}

}  // namespace
}  // namespace vcockpit::test
