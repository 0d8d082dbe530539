// `controls:` in a scene file: a valid set of controls loads with its units converted and its
// moving parts added as objects, and every bad value is an error naming file, line and key.

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "physics_node/config/scene_config.hpp"
#include "tests/support/test_files.hpp"
#include "tests/unit/scene_error_cases.hpp"

namespace vcockpit {
namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

const std::string kScene = R"(gravity: [0, 0, -9.81]
step_s: 0.001
objects:
  - name: panel
    kind: static
    shape: {box: [0.02, 0.6, 0.4]}
    pose: {position: [0.8, 0, 1.0]}
controls:
  - name: master_caution
    kind: push_button
    joint: prismatic
    pose: {position: [0.78, 0.1, 1.0], rpy_deg: [0, 90, 0]}
    body: {shape: {box: [0.008, 0.015, 0.015]}, mass: 0.005, color: [0.9, 0.6, 0.1]}
    travel: [0, 0.004]
    spring: {stiffness: 1500, rest: -0.002}
    damping: 2.7
    latch_at: 0.0015
    positions:
      - {name: off, at: 0, enter: [-1, 0.002]}
      - {name: on, at: 0.004, enter: [0.003, 1]}
    lit_when: on
  - name: landing_lights
    kind: toggle
    joint: revolute
    pose: {position: [0.78, 0, 1.0], rpy_deg: [90, 0, 0]}
    body: {shape: {capsule: [0.003, 0.02]}, mass: 0.004, offset: {position: [0, 0.012, 0], rpy_deg: [90, 0, 0]}}
    travel: [-20, 20]
    snap: {strength: 0.05, centre: 10}
    detents: [{at: 0, strength: 0.03, half_width: 8}]
    positions:
      - {name: off, at: -20, enter: [-20, -14]}
      - {name: taxi, at: 0, enter: [-4, 4]}
      - {name: on, at: 20, enter: [14, 20]}
  - name: heading_bug
    kind: rotary
    joint: revolute
    continuous: true
    pose: {position: [0.78, -0.1, 1.0], rpy_deg: [0, 90, 0]}
    body: {shape: {cylinder: [0.01, 0.012]}, mass: 0.01}
    detents: [{at: 0, strength: 0.004, half_width: 5}]
    detent_every: 10
    positions:
      - {name: "0", at: 0, enter: [-4, 4]}
      - {name: "10", at: 10, enter: [6, 14]}
  - name: throttle
    kind: lever
    joint: revolute
    pose: {position: [0.5, -0.3, 0.8], rpy_deg: [-90, 0, 0]}
    body: {shape: {box: [0.03, 0.02, 0.12]}, mass: 0.2, offset: {position: [0, 0.06, 0]}}
    travel: [0, 60]
    friction: 0.05
    detents: [{at: 10, strength: 0.5, half_width: 4}]
    gates: [{at: 10, lift: 0.01}]
    positions:
      - {name: cutoff, at: 0, enter: [0, 3]}
      - {name: idle, at: 10, enter: [8, 12]}
      - {name: full, at: 60, enter: [55, 60]}
)";

TEST(ControlConfig, ControlsLoadWithTheirMovingPartsAsObjects) {
  const std::string path = test::write_test_file("control_config_test", "valid.yaml", kScene);
  const physics::Scene scene = load_scene(path);
  ASSERT_EQ(scene.controls.size(), 4u);
  ASSERT_EQ(scene.objects.size(), 5u);  // the panel and four moving parts
  for (std::size_t i = 0; i < scene.controls.size(); ++i) {
    const physics::ControlSpec& c = scene.controls[i];
    ASSERT_EQ(scene.objects[c.body].control, static_cast<int>(i));
    EXPECT_TRUE(scene.objects[c.body].dynamic);
    EXPECT_EQ(scene.objects[c.body].name, c.name);
  }
  const physics::ControlSpec& button = scene.controls[0];
  EXPECT_TRUE(button.latching);
  EXPECT_EQ(button.lit_when, 1);
  EXPECT_DOUBLE_EQ(button.q_max, 0.004);
  const physics::ControlSpec& toggle = scene.controls[1];
  EXPECT_NEAR(toggle.q_min, -20 * kDeg, 1e-15);
  EXPECT_NEAR(toggle.snap_centre, 10 * kDeg, 1e-15);
  EXPECT_EQ(toggle.positions.size(), 3u);
  EXPECT_EQ(toggle.q_initial, toggle.positions[0].q) << "the first position, unless 'initial'";
  const physics::ControlSpec& knob = scene.controls[2];
  EXPECT_FALSE(knob.limited);
  EXPECT_NEAR(knob.detent_period, 10 * kDeg, 1e-15);
  const physics::ControlSpec& throttle = scene.controls[3];
  ASSERT_EQ(throttle.gates.size(), 1u);
  EXPECT_NEAR(throttle.gates[0].q, 10 * kDeg, 1e-15);
  // the lever's arm: its body 6 cm along the joint frame's y, wherever the joint frame is
  const Eigen::Vector3d arm = scene.objects[throttle.body].X_GO.translation() - throttle.X_GJ.translation();
  EXPECT_NEAR(arm.norm(), 0.06, 1e-12);
}

TEST(ControlConfig, EveryBadControlNamesFileLineAndKey) {
  const std::vector<BadCase> cases = {
      {"unknown_kind", "kind: rotary", "kind: dial", "kind: dial", "controls[2].kind",
       "unknown kind 'dial'"},
      {"button_revolute", "kind: push_button\n    joint: prismatic", "kind: push_button\n    joint: revolute",
       "joint: revolute\n    pose: {position: [0.78, 0.1", "controls[0].joint", "joint prismatic"},
      {"detent_outside_travel", "detents: [{at: 10, strength: 0.5", "detents: [{at: 70, strength: 0.5",
       "detents: [{at: 70", "controls[3].detents[0].at", "outside the travel [0 deg, 60 deg]"},
      {"gate_without_detent", "gates: [{at: 10, lift: 0.01}]", "gates: [{at: 30, lift: 0.01}]",
       "gates: [{at: 30", "controls[3].gates[0].at", "no detent at 30 deg"},
      {"one_position", "      - {name: off, at: -20, enter: [-20, -14]}\n      - {name: taxi, at: 0, enter: [-4, 4]}\n      - {name: on, at: 20, enter: [14, 20]}\n",
       "      - {name: on, at: 20, enter: [14, 20]}\n", "      - {name: on, at: 20", "controls[1].positions",
       "at least 2 positions"},
      {"overlapping_positions", "{name: taxi, at: 0, enter: [-4, 4]}", "{name: taxi, at: 0, enter: [-15, 4]}",
       "{name: taxi", "controls[1].positions[1].enter", "overlaps position 'off'"},
      {"inverted_travel", "travel: [0, 60]", "travel: [60, 0]", "travel: [60, 0]", "controls[3].travel",
       "needs lo < hi"},
      {"continuous_toggle", "    travel: [-20, 20]\n", "    continuous: true\n", "continuous: true",
       "controls[1].continuous", "only a rotary"},
      {"latch_on_a_toggle", "    snap: {strength: 0.05, centre: 10}\n", "    latch_at: 5\n", "latch_at: 5",
       "controls[1].latch_at", "only a push_button latches"},
      {"latch_outside_rearm", "latch_at: 0.0015", "latch_at: 0.0025", "latch_at: 0.0025",
       "controls[0].latch_at", "inside the first position's interval"},
      {"lit_when_unknown", "lit_when: on", "lit_when: bright", "lit_when: bright",
       "controls[0].lit_when", "no position named 'bright'"},
      {"duplicate_name", "name: heading_bug", "name: panel", "name: panel\n    kind: rotary",
       "controls[2].name", "duplicate name 'panel'"},
      {"negative_damping", "damping: 2.7", "damping: -1", "damping: -1", "controls[0].damping",
       "must be >= 0"},
      {"unknown_key", "friction: 0.05", "fricton: 0.05", "fricton: 0.05", "controls[3].fricton",
       "unknown key 'fricton'"},
  };
  for (const BadCase& c : cases)
    expect_error(c, kScene);
}

}  // namespace
}  // namespace vcockpit
