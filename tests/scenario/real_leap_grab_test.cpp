// A real hand recording (tests/data/real/README.md: a Leap Motion "grab", Apache-2.0) replayed
// offline on its scene, a 60 g bar on a pedestal where the recorded fist closes. The recorded
// thumb reaches 18 mm into the table and the pedestal, the fingers close 4 cm past the bar: only
// a proxy hand that keeps its links out of the panels and stops its fingers at the bar grasps it.
// What a user expects of a real recording:
//   - a GRASP of the bar while the fist closes, held for at least the minimum hold;
//   - the bar never faster than 0.5 m/s until it is let go (never flung);
//   - no link of the drawn hand more than 1 mm inside a static object, at any step.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <string>

#include "hand/glove_log.hpp"
#include "hand/sample_validator.hpp"
#include "physics_node/config/scene_config.hpp"
#include "physics_node/io/replay_driver.hpp"

namespace vcockpit {
namespace {

std::string source_dir() { return std::getenv("VCOCKPIT_SOURCE_DIR"); }

TEST(RealLeapGrab, TheClosingFistGraspsTheBarWithoutFlingingItOrSinkingIntoTheTable) {
  physics::World world(load_scene(source_dir() + "/tests/data/real/leap_grab_scene.yaml"));
  const hand::HandModel& hand = world.scene().hands[0];
  const auto log = hand::read_glove_log(source_dir() + "/tests/data/real/leap_grab.csv", hand);
  const int bar = world.scene().find_object("bar");
  ASSERT_GE(bar, 0);

  double grasp_s = -1.0;
  double release_s = -1.0;
  double fastest_before_release_mps = 0.0;
  double fastest_at_s = 0.0;
  bool fastest_held = false;
  double deepest_static_m = 0.0;
  physics_io::ReplayDriver driver(world, hand);
  auto step = [&] {
    world.step();
    const double t_s = static_cast<double>(world.time_ns()) * 1e-9;
    for (const auto& e : world.step_events()) {
      if (e.object != bar) continue;
      if (e.grasp && grasp_s < 0.0) grasp_s = t_s;
      if (!e.grasp && grasp_s >= 0.0 && release_s < 0.0) release_s = t_s;
    }
    if (release_s < 0.0 && world.bodies()[bar].v_G.norm() > fastest_before_release_mps) {
      fastest_before_release_mps = world.bodies()[bar].v_G.norm();
      fastest_at_s = t_s;
      fastest_held = world.bodies()[bar].held_by != physics::kNotHeld;
    }
    deepest_static_m = std::max(deepest_static_m, world.hand_penetration().static_max_m);
  };
  // the checks the offline runner and a live node make (joint values past the hand's range clamped)
  hand::SampleValidator validator(hand);
  for (hand::GloveSample sample : log.samples)
    if (validator.accept(sample)) driver.feed(sample, step);

  ASSERT_GE(grasp_s, 0.0) << "the closing fist never grasped the bar";
  const double held_s = (release_s < 0.0 ? static_cast<double>(world.time_ns()) * 1e-9 : release_s) - grasp_s;
  EXPECT_GE(held_s, world.scene().grasp.min_hold_s) << "grasp at " << grasp_s << " s";
  EXPECT_LT(fastest_before_release_mps, 0.5) << "grasp at " << grasp_s << " s, release at " << release_s << " s";
  EXPECT_LE(deepest_static_m, 1e-3);
  std::printf("GRASP %.3f s, RELEASE %.3f s, peak %.3f m/s before release (at %.3f s, %s), "
              "deepest link in a panel %.2f mm\n",
              grasp_s, release_s, fastest_before_release_mps, fastest_at_s,
              fastest_held ? "held" : "free", deepest_static_m * 1e3);
}

}  // namespace
}  // namespace vcockpit
