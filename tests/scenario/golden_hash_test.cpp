// Determinism pinned across builds (Box2D's and Jolt's golden state hash): the bundled grasping
// log replayed offline on the default cockpit, and the hash of the final world state compared
// with a number written here. It holds at -O0, -O2 and under the sanitizers because the build
// forbids FMA contraction (-ffp-contract=off) and the step has no clock or unordered iteration.
//
// A change that alters results fails here on purpose: check that the new behaviour is wanted,
// then update the pin (the failure prints the new value) and say so in the commit.

#include <gtest/gtest.h>

#include <cinttypes>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "hand/glove_log.hpp"
#include "physics_node/config/scene_config.hpp"
#include "physics_node/io/replay_driver.hpp"
#include "physics_node/physics/world_state_hash.hpp"

namespace vcockpit {
namespace {

std::string source_dir() { return std::getenv("VCOCKPIT_SOURCE_DIR"); }

struct Replayed {
  uint64_t final_hash = 0;
  uint64_t hash_at_grasp = 0;  // the state right after the GRASP step
  uint64_t steps = 0;
};

// read_between: after every step, read what the state publisher reads (the tracked hand of each
// hand), as the physics node does between its steps.
Replayed replay(const std::string& scene_file, const std::string& log_file, bool read_between = false) {
  physics::World world(load_scene(source_dir() + scene_file));
  const hand::HandModel& hand = world.scene().hands[0];
  const auto log = hand::read_glove_log(source_dir() + log_file, hand);
  Replayed out;
  physics_io::ReplayDriver driver(world, hand);
  auto step = [&] {
    world.step();
    if (read_between) {
      for (int h = 0; h < world.hand_count(); ++h) (void)world.tracked_offset_m(h);
    }
    for (const auto& e : world.step_events())
      if (e.grasp && out.hash_at_grasp == 0) out.hash_at_grasp = physics::hash_world_state(world.state());
  };
  for (const auto& sample : log.samples) driver.feed(sample, step);
  out.final_hash = physics::hash_world_state(world.state());
  out.steps = world.step_count();
  return out;
}

std::string hex(uint64_t h) {
  char text[24];
  std::snprintf(text, sizeof text, "0x%016" PRIx64, h);
  return text;
}

TEST(GoldenHash, BundledGraspLogOnTheDefaultCockpit) {
  const Replayed run =
      replay("/config/cockpit.yaml", "/config/glove_logs/reach_grasp_lift_release.csv");
  EXPECT_EQ(run.steps, 8500u);
  EXPECT_EQ(hex(run.hash_at_grasp), "0xb416cc008437fad5") << "state right after the GRASP step";
  EXPECT_EQ(hex(run.final_hash), "0x19664aca3f8f9ffb") << "final state";
}

TEST(GoldenHash, BundledOpenHandSweep) {
  const Replayed run = replay("/config/cockpit.yaml", "/config/glove_logs/open_hand_sweep.csv");
  EXPECT_EQ(hex(run.final_hash), "0xb0c1cff4022f3e6d") << "final state";
}

// A world read between its steps (the physics node publishes the tracked hand there) steps as
// one that is not: a read caches nothing the next step uses. It once did (a cached tracked hand
// of the step before), and a lockstep node then differed from the offline runner by when it
// happened to publish.
TEST(GoldenHash, ReadingTheTrackedHandBetweenStepsChangesNothing) {
  for (const char* log : {"/config/glove_logs/panel_knobs.csv",
                          "/config/glove_logs/reach_grasp_lift_release.csv"}) {
    SCOPED_TRACE(log);
    const Replayed plain = replay("/config/cockpit.yaml", log);
    const Replayed read = replay("/config/cockpit.yaml", log, true);
    EXPECT_EQ(hex(read.final_hash), hex(plain.final_hash));
    EXPECT_EQ(hex(read.hash_at_grasp), hex(plain.hash_at_grasp));
  }
}

}  // namespace
}  // namespace vcockpit
