// The world's state (world_state.hpp): two worlds stepping the same inputs stay bit-identical
// (equal hashes), a world restored to a state continues exactly as the original (through a grasp
// and a release), and the hash sees a body move by one ulp.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "glove_driver/glove/glove_log.hpp"
#include "physics_node/config/scene_config.hpp"
#include "physics_node/io/hand_input.hpp"
#include "physics_node/physics/world.hpp"
#include "physics_node/physics/world_state_hash.hpp"

namespace vcockpit::physics {
namespace {

std::string source_dir() {
  const char* dir = std::getenv("VCOCKPIT_SOURCE_DIR");
  return dir ? dir : ".";
}

// The default cockpit and its bundled grasping log: the cup is grasped at 2.63 s, lifted and
// released at 6.48 s.
struct Cockpit {
  Scene scene = load_scene(source_dir() + "/config/cockpit.yaml");
  std::vector<glove::GloveSample> samples =
      glove::read_glove_log(source_dir() + "/config/glove_logs/reach_grasp_lift_release.csv",
                            *scene.hand)
          .samples;
  int cup = scene.find_object("cup");
};

// Feeds a world the log's samples up to its time, as the offline runner does.
struct GloveFeed {
  const std::vector<glove::GloveSample>* samples;
  std::size_t next = 0;

  void feed(World& world) {
    const int64_t t0 = samples->front().t_ns;
    while (next < samples->size() && (*samples)[next].t_ns - t0 <= world.time_ns())
      world.set_hand_input(physics_io::hand_input_from_glove(*world.scene().hand, (*samples)[next++]));
  }
  void run_until(World& world, double t_s) {
    while (world.time_ns() < std::llround(t_s * 1e9)) {
      world.step();
      feed(world);
    }
  }
};

bool same_bits(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return std::memcmp(a.matrix().data(), b.matrix().data(), sizeof(double) * 16) == 0;
}

TEST(WorldState, TwoWorldsSteppingTheSameInputsHaveEqualHashes) {
  const Cockpit cockpit;
  World a(cockpit.scene), b(cockpit.scene);
  GloveFeed feed_a{&cockpit.samples}, feed_b{&cockpit.samples};
  feed_a.feed(a);
  feed_b.feed(b);
  EXPECT_EQ(hash_world_state(a.state()), hash_world_state(b.state()));
  for (int i = 0; i < 3000; ++i) {  // through the grasp at 2.63 s
    a.step();
    b.step();
    feed_a.feed(a);
    feed_b.feed(b);
    ASSERT_EQ(hash_world_state(a.state()), hash_world_state(b.state())) << "step " << i;
  }
  EXPECT_NE(a.bodies()[cockpit.cup].held_by, kNotHeld) << "the cup is held by now";
}

TEST(WorldState, RestoredWorldContinuesBitIdenticallyThroughGraspAndRelease) {
  const Cockpit cockpit;
  World original(cockpit.scene);
  GloveFeed feed{&cockpit.samples};
  feed.feed(original);
  feed.run_until(original, 4.0);  // the cup held, lifted
  ASSERT_NE(original.bodies()[cockpit.cup].held_by, kNotHeld);
  const WorldState saved = original.state();

  World restored(cockpit.scene);
  restored.restore(saved);
  GloveFeed restored_feed = feed;
  EXPECT_EQ(hash_world_state(restored.state()), hash_world_state(saved));
  EXPECT_TRUE(restored.step_events().empty());
  EXPECT_TRUE(restored.contacts().empty());

  int events = 0;
  while (original.time_ns() < 7'500'000'000) {  // past the release at 6.48 s
    original.step();
    restored.step();
    ASSERT_EQ(hash_world_state(original.state()), hash_world_state(restored.state()))
        << "at " << original.time_ns() * 1e-9 << " s";
    ASSERT_EQ(original.step_events().size(), restored.step_events().size());
    events += static_cast<int>(original.step_events().size());
    feed.feed(original);
    restored_feed.feed(restored);
  }
  EXPECT_EQ(events, 1) << "the release";
  EXPECT_EQ(restored.bodies()[cockpit.cup].held_by, kNotHeld);
  for (std::size_t i = 0; i < original.bodies().size(); ++i)
    EXPECT_TRUE(same_bits(original.bodies()[i].X_GO, restored.bodies()[i].X_GO)) << "object " << i;
}

TEST(WorldState, RestoringAWorldReplaysItsOwnFuture) {
  const Cockpit cockpit;
  World world(cockpit.scene);
  GloveFeed feed{&cockpit.samples};
  feed.feed(world);
  feed.run_until(world, 2.5);  // the hand closing on the cup: contacts and stick anchors
  const WorldState saved = world.state();
  const GloveFeed saved_feed = feed;
  EXPECT_FALSE(saved.anchors.empty()) << "the fingers touch the cup";
  feed.run_until(world, 3.0);
  const uint64_t first = hash_world_state(world.state());

  world.restore(saved);
  feed = saved_feed;
  feed.run_until(world, 3.0);
  EXPECT_EQ(hash_world_state(world.state()), first);
}

TEST(WorldState, HashChangesWhenABodyMovesByOneUlp) {
  const Cockpit cockpit;
  World world(cockpit.scene);
  WorldState state = world.state();
  const uint64_t before = hash_world_state(state);
  EXPECT_EQ(hash_world_state(state), before) << "a function of the state only";
  double& x_m = state.bodies[cockpit.cup].X_GO.translation().x();
  x_m = std::nextafter(x_m, std::numeric_limits<double>::infinity());
  EXPECT_NE(hash_world_state(state), before);

  world.step();  // the cup settles a little on the console
  EXPECT_NE(hash_world_state(world.state()), before);
}

TEST(WorldState, HashSeesEveryPart) {
  const Cockpit cockpit;
  World world(cockpit.scene);
  const WorldState base = world.state();
  const uint64_t h = hash_world_state(base);
  auto changed = [&](auto&& edit) {
    WorldState s = base;
    edit(s);
    return hash_world_state(s) != h;
  };
  EXPECT_TRUE(changed([](WorldState& s) { s.time_ns += 1; }));
  EXPECT_TRUE(changed([](WorldState& s) { s.steps += 1; }));
  EXPECT_TRUE(changed([&](WorldState& s) { s.bodies[cockpit.cup].w_G.z() = 1e-300; }));
  EXPECT_TRUE(changed([&](WorldState& s) { s.bodies[cockpit.cup].held_by = 0; }));
  EXPECT_TRUE(changed([](WorldState& s) { s.hand_active = true; }));
  EXPECT_TRUE(changed([](WorldState& s) { s.hand_to.q_rad[5] = 0.1; }));
  EXPECT_TRUE(changed([](WorldState& s) { s.hand_from.tracking = false; }));
  EXPECT_TRUE(changed([](WorldState& s) { s.X_GL[3].translation().y() = 0.5; }));
  EXPECT_TRUE(changed([&](WorldState& s) { s.grasp[cockpit.cup].released_at_ns = 0; }));
  EXPECT_TRUE(changed([&](WorldState& s) { s.grasp[cockpit.cup].history[1].translation().z() = 1; }));
  EXPECT_TRUE(changed([](WorldState& s) { s.anchors.push_back(StickAnchor{}); }));
}

}  // namespace
}  // namespace vcockpit::physics
