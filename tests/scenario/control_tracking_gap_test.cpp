// Controls held through a tracking gap: the glove stops sending mid-move for longer than the
// interpolation bridges (the hand holds its last sample), then comes back with the hand already
// turned on. The proxy's wrist catches up at its maximum speed on its own path, not round the
// control's joint, so for a while the tracked fingers posed on it are off the knob or handle they
// still hold. The grip must hold through that: the same control changes as without the gap, and
// each control let go when the hand lets go of it, as without the gap
// (config/gestures/panel_knobs.yaml, pedestal_levers.yaml).

#include <gtest/gtest.h>

#include <algorithm>
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

struct Release {
  std::string object;
  double t_s = 0.0;
};

struct ControlRun {
  std::string changes;  // "control from->to (cause)" per change, in order
  std::vector<Release> releases;
  double lag_after_gap_m = 0.0;  // the proxy's widest lag behind the tracked hand after the gap
};

// `script` (config/gestures/) played by the medium hand, without the samples stamped in
// [gap_from_s, gap_to_s)
ControlRun run_control_script(const std::string& script, double gap_from_s, double gap_to_s) {
  physics::Scene scene_spec = load_scene(source_dir() + "/config/cockpit.yaml");
  scene_spec.hands = {load_hand_model(source_dir() + "/config/hand.yaml")};
  const hand::HandModel hand = scene_spec.hands[0];
  physics::World world(std::move(scene_spec));
  const physics::Scene& scene = world.scene();
  ControlRun run;
  auto step = [&] {
    world.step();
    for (const auto& e : world.control_events()) {
      const physics::ControlSpec& c = scene.controls[static_cast<std::size_t>(e.control)];
      run.changes += c.name + " " + c.positions[static_cast<std::size_t>(e.from)].name + "->" +
                     c.positions[static_cast<std::size_t>(e.to)].name + " (" +
                     physics::control_cause_name(e.cause) + ")\n";
    }
    for (const physics::GraspEvent& e : world.step_events()) {
      if (!e.grasp)
        run.releases.push_back({scene.objects[static_cast<std::size_t>(e.object)].name,
                                static_cast<double>(e.t_ns) * 1e-9});
    }
    const double t_s = static_cast<double>(world.time_ns()) * 1e-9;
    if (gap_to_s > gap_from_s && t_s >= gap_to_s && t_s < gap_to_s + 0.2)
      run.lag_after_gap_m = std::max(run.lag_after_gap_m, world.tracked_offset_m());
  };
  physics_io::ReplayDriver driver(world, scene.hands[0]);
  hand::SampleValidator validator(scene.hands[0]);
  const auto samples = script_samples(source_dir() + "/config/gestures/" + script + ".yaml", hand);
  for (hand::GloveSample sample : samples) {
    const double t_s = static_cast<double>(sample.t_ns - samples.front().t_ns) * 1e-9;
    if (t_s >= gap_from_s && t_s < gap_to_s) continue;
    if (validator.accept(sample)) driver.feed(sample, step);
  }
  return run;
}

void expect_same_releases(const ControlRun& gap, const ControlRun& plain) {
  ASSERT_EQ(gap.releases.size(), plain.releases.size());
  for (std::size_t i = 0; i < gap.releases.size(); ++i) {
    EXPECT_EQ(gap.releases[i].object, plain.releases[i].object) << i;
    EXPECT_NEAR(gap.releases[i].t_s, plain.releases[i].t_s, 0.1) << i;
  }
}

TEST(ControlTrackingGap, AKnobTurnedThroughAGapIsHeldUntilTheHandOpens) {
  const ControlRun plain = run_control_script("panel_knobs", 0.0, 0.0);
  ASSERT_NE(plain.changes.find("nav_mode vor->gps (grasped)"), std::string::npos) << plain.changes;
  ASSERT_EQ(plain.releases.size(), 3u);  // the selector, and the heading knob's two twists
  // the selector's second twist runs 3.40-4.00 s; the glove is silent from just after it starts
  // until after it ends (0.6 s, under the 1 s glove timeout), so the hand comes back turned 28
  // deg about the knob's axis
  const ControlRun gap = run_control_script("panel_knobs", 3.45, 4.05);
  EXPECT_GT(gap.lag_after_gap_m, 0.01) << "the gap left the proxy behind the tracked hand";
  EXPECT_EQ(gap.changes, plain.changes);
  // the selector is let go once, as the hand opens (4.30-4.70 s); the heading knob twice
  expect_same_releases(gap, plain);
  ASSERT_FALSE(gap.releases.empty());
  EXPECT_EQ(gap.releases[0].object, "nav_mode");
  EXPECT_GE(gap.releases[0].t_s, 4.30);
  EXPECT_LE(gap.releases[0].t_s, 4.75);
}

// A lever through a gap too. Its handle, held close to the wrist, keeps the tracked fingers posed
// on the catching-up wrist within reach (this case holds on the first test alone); the second
// test's joint motion for an off-axis handle is checked in control_model_test.
TEST(ControlTrackingGap, AThrottlePushedThroughAGapIsHeldUntilTheHandOpens) {
  const ControlRun plain = run_control_script("pedestal_levers", 0.0, 0.0);
  ASSERT_NE(plain.changes.find("throttle idle->full (grasped)"), std::string::npos) << plain.changes;
  // the push from idle to full runs 9.40-11.00 s; the glove is silent for 0.6 s in the middle
  const ControlRun gap = run_control_script("pedestal_levers", 9.80, 10.40);
  EXPECT_GT(gap.lag_after_gap_m, 0.01) << "the gap left the proxy behind the tracked hand";
  EXPECT_EQ(gap.changes, plain.changes);
  expect_same_releases(gap, plain);
}

}  // namespace
}  // namespace vcockpit::test
