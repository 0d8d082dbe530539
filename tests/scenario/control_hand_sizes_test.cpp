// The control gestures (config/gestures/panel_switches, panel_knobs, pedestal_levers.yaml) played
// by a 5th-percentile woman's hand and a 95th-percentile man's (config/hand_small.yaml,
// hand_large.yaml) through the physics as the offline runner plays a log: each gives the same
// control changes, in the same order and with the same causes, as the bundled log recorded with
// the 50th-percentile hand. The scripts place the hand by fingertip or grip point, not by the
// wrist, so that they fit every hand; this is where that is checked.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "hand/config/hand_yaml.hpp"
#include "hand/sample_validator.hpp"
#include "physics_node/config/scene_config.hpp"
#include "physics_node/io/replay_driver.hpp"
#include "tests/scenario/grasp_matrix/grasp_scenario.hpp"
#include "tests/support/test_files.hpp"

namespace vcockpit::test {
namespace {

// "control from->to (cause)" per change, in order
std::string changes_of(physics::World& world, const std::vector<hand::GloveSample>& samples) {
  std::string text;
  const physics::Scene& scene = world.scene();
  auto step = [&] {
    world.step();
    for (const auto& e : world.control_events()) {
      const physics::ControlSpec& c = scene.controls[static_cast<std::size_t>(e.control)];
      text += c.name + " " + c.positions[static_cast<std::size_t>(e.from)].name + "->" +
              c.positions[static_cast<std::size_t>(e.to)].name + " (" +
              physics::control_cause_name(e.cause) + ")\n";
    }
  };
  physics_io::ReplayDriver driver(world, scene.hands[0]);
  hand::SampleValidator validator(scene.hands[0]);
  for (hand::GloveSample sample : samples) {
    if (validator.accept(sample)) driver.feed(sample, step);
  }
  return text;
}

std::string with_hand(const std::string& script, const std::string& hand_file) {
  physics::Scene scene = load_scene(source_dir() + "/config/cockpit.yaml");
  scene.hands = {load_hand_model(source_dir() + "/config/" + hand_file)};
  const hand::HandModel hand = scene.hands[0];
  physics::World world(std::move(scene));
  return changes_of(world, script_samples(source_dir() + "/config/gestures/" + script + ".yaml", hand));
}

class ControlGestureHandSizes : public ::testing::TestWithParam<const char*> {};

TEST_P(ControlGestureHandSizes, SmallAndLargeHandsMakeTheSameChangesAsTheMediumOne) {
  const std::string script = GetParam();
  const std::string medium = with_hand(script, "hand.yaml");
  ASSERT_FALSE(medium.empty()) << script;
  EXPECT_EQ(with_hand(script, "hand_small.yaml"), medium) << script << ", 5th percentile";
  EXPECT_EQ(with_hand(script, "hand_large.yaml"), medium) << script << ", 95th percentile";
}

INSTANTIATE_TEST_SUITE_P(Scripts, ControlGestureHandSizes,
                         ::testing::Values("panel_switches", "panel_knobs", "pedestal_levers"));

}  // namespace
}  // namespace vcockpit::test
