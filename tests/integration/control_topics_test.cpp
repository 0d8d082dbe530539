// The physics node's control topics over loopback DDS: control_info describes every control of
// the default cockpit; a control_command sets a control, which the node reports as a COMMANDED
// control_event and a new control_state; a command for a position the control does not have is
// refused and named in the log, and the node keeps running; a switch set on lights its
// annunciator in the image generator's frame.

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <set>
#include <string>

#include "dds/dds_options.hpp"
#include "dds/dds_participant.hpp"
#include "image_generator/node/hmd_yaml.hpp"
#include "image_generator/render/camera.hpp"
#include "physics_node/config/scene_config.hpp"
#include "tests/support/monitor_log.hpp"
#include "tests/support/png_read.hpp"
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

// The pilot's only feedback is visual (the paper, 4.4): the fuel pump's annunciator, rendered
// from the design eye, is dull while the switch is off and glows once a command has set it on.
TEST_F(ControlTopicsTest, AnAnnunciatorLightsInTheRenderedFrameWhenItsSwitchIsOn) {
  const physics::Scene scene = load_scene(source_dir() + "/config/cockpit.yaml");
  const int pump = scene.find_control("fuel_pump");
  ASSERT_GE(pump, 0);
  const int light = scene.controls[static_cast<std::size_t>(pump)].light_object;
  ASSERT_GE(light, 0);
  const HmdSetup hmd = load_hmd_config(source_dir() + "/config/hmd.yaml");
  Eigen::Vector2d pixel;
  ASSERT_TRUE(render::project_to_pixel(hmd.hmd, render::Eye::kLeft, hmd.X_GHead,
                                       scene.objects[static_cast<std::size_t>(light)].X_GO.translation(),
                                       pixel));
  ChildProcess node = start("physics_node", {}, "node.log");
  // a few frames, the last one kept: by then the light's control_state has arrived
  auto render_frame = [&](const std::string& name) {
    ChildProcess ig = start("image_generator",
                            {"--frames", "10", "--fps", "30", "--out", dir_ + "/" + name,
                             "--snapshot-every", "9", "--snapshot-layout", "left"},
                            name + ".log");
    EXPECT_EQ(ig.wait(60 * kSecond), 0) << text(name + ".log");
    RgbaImage image;
    EXPECT_TRUE(read_png(dir_ + "/" + name + "/frame_000009_left.png", image)) << text(name + ".log");
    if (image.width == 0) return std::array<int, 4>{};
    return image.at(static_cast<int>(pixel.x()), static_cast<int>(pixel.y()));
  };
  const std::array<int, 4> off = render_frame("off");

  DdsParticipant participant(resolve_dds_options(DdsFlags{}), "control_topics_test");
  auto events = participant.make_reader<cockpit::ControlEvent>("event");
  auto commands = participant.make_writer<cockpit::ControlCommand>("event");
  ASSERT_TRUE(commands.wait_for_matched(1, kWait_ns)) << text("node.log");
  cockpit::ControlCommand command;
  command.control_id(static_cast<uint32_t>(pump));
  command.position(1);  // on
  command.source("control_topics_test");
  commands.write(command);
  bool on = false;
  cockpit::ControlEvent event;
  for (int tries = 0; tries < 100 && !on; ++tries) {
    events.wait_for_data(100'000'000);
    while (events.take(event)) on = on || (event.control_id() == static_cast<uint32_t>(pump) && event.to_position() == 1u);
  }
  ASSERT_TRUE(on) << text("node.log");
  const std::array<int, 4> lit = render_frame("on");
  std::printf("fuel pump annunciator at (%.0f, %.0f): off rgb %d %d %d, on rgb %d %d %d\n",
              pixel.x(), pixel.y(), off[0], off[1], off[2], lit[0], lit[1], lit[2]);
  EXPECT_GT(lit[0] + lit[1] + lit[2], off[0] + off[1] + off[2] + 150) << "lit: far brighter";
  EXPECT_GT(lit[0], lit[2] + 60) << "and amber";
  EXPECT_EQ(node.stop(), 0) << text("node.log");
}

}  // namespace
}  // namespace vcockpit::test
