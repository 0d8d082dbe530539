// Sleeping (physics/sleep.hpp): objects that come to rest fall asleep as islands, cost no contact
// while they sleep (no narrowphase, no solve for them), stay exactly where they were, and
// wake, their whole island with them, when something that moves touches them: a falling ball,
// the hand. A scene can turn it off, and then nothing ever sleeps.

#include "physics_node/physics/sleep.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "hand/glove_log.hpp"
#include "physics_node/config/scene_config.hpp"
#include "physics_node/io/hand_input.hpp"
#include "physics_node/physics/world.hpp"
#include "tests/support/scene_builder.hpp"

namespace vcockpit::physics {
namespace {

std::string source_dir() {
  const char* dir = std::getenv("VCOCKPIT_SOURCE_DIR");
  return dir ? dir : ".";
}

bool same_bits(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return std::memcmp(a.matrix().data(), b.matrix().data(), sizeof(double) * 16) == 0;
}

int asleep_count(const World& world) {
  int n = 0;
  for (const BodyState& b : world.bodies()) n += b.asleep ? 1 : 0;
  return n;
}

int dynamic_count(const World& world) {
  int n = 0;
  for (const ObjectSpec& o : world.scene().objects) n += o.dynamic ? 1 : 0;
  return n;
}

// Steps until every dynamic object sleeps or `limit_s` of simulated time has passed; the time
// it took (s), or -1.
double step_until_all_asleep(World& world, double limit_s) {
  const int dynamic = dynamic_count(world);
  while (world.time_ns() < std::llround(limit_s * 1e9)) {
    world.step();
    if (asleep_count(world) == dynamic) return static_cast<double>(world.time_ns()) * 1e-9;
  }
  return -1.0;
}

// A floor and a column of ten 5 cm cubes of 100 g, each resting on the one below.
Scene stack_of_ten() {
  Scene scene;
  scene.objects.push_back(test::floor_box(test::material(1e5)));
  const Shape cube = Shape::box({0.05, 0.05, 0.05});
  for (int i = 0; i < 10; ++i)
    scene.objects.push_back(test::dynamic_object("box_" + std::to_string(i), cube, 0.1,
                                                 test::at(0.0, 0.0, 0.025 + 0.05 * i),
                                                 test::material(1e5)));
  return scene;
}

TEST(Sleep, ABoxDroppedOnTheFloorComesToRestSleepsAndCostsNothing) {
  Scene scene;
  scene.objects.push_back(test::floor_box(test::material(1e5)));
  scene.objects.push_back(test::dynamic_object("box", Shape::box({0.1, 0.1, 0.1}), 0.5,
                                               test::at(0.0, 0.0, 0.10, 3.0, 2.0, 0.0),
                                               test::material(1e5)));
  World world(scene);
  world.step();
  EXPECT_FALSE(world.bodies()[1].asleep);
  const double slept_s = step_until_all_asleep(world, 3.0);
  ASSERT_GT(slept_s, 0.0) << "never fell asleep";
  // no sooner than it has been still for time_s after the drop and its bounce
  EXPECT_GE(slept_s, scene.sleep.time_s + 0.1);
  std::printf("the dropped box fell asleep at %.3f s\n", slept_s);
  const BodyState asleep = world.bodies()[1];
  EXPECT_EQ(asleep.v_G, Eigen::Vector3d::Zero());
  EXPECT_EQ(asleep.w_G, Eigen::Vector3d::Zero());
  EXPECT_NEAR(asleep.X_GO.translation().z(), 0.05, 1e-3);  // resting on its face
  for (int i = 0; i < 500; ++i) {
    world.step();
    ASSERT_TRUE(world.bodies()[1].asleep);
    ASSERT_TRUE(same_bits(world.bodies()[1].X_GO, asleep.X_GO)) << "a sleeping body moved";
    ASSERT_TRUE(world.contacts().empty()) << "a sleeping body's contacts were computed";
  }
}

TEST(Sleep, AStackOfTenBoxesComesToRestAndSleepsAsOneIsland) {
  World world(stack_of_ten());
  world.step();
  EXPECT_FALSE(world.contacts().empty());  // awake, the stack's contacts are computed
  const double slept_s = step_until_all_asleep(world, 5.0);
  ASSERT_GT(slept_s, 0.0) << asleep_count(world) << " of 10 asleep after 5 s";
  std::printf("the stack fell asleep at %.3f s\n", slept_s);
  for (int i = 1; i <= 10; ++i) {
    const BodyState& b = world.bodies()[i];
    EXPECT_EQ(b.island, 1) << "box " << i - 1 << " is not in the bottom box's island";
    // still a column: each box on the one below, sunk by at most the contacts' depths
    EXPECT_NEAR(b.X_GO.translation().z(), 0.025 + 0.05 * (i - 1), 1e-3 * i) << "box " << i - 1;
    EXPECT_NEAR(b.X_GO.translation().head<2>().norm(), 0.0, 1e-3) << "box " << i - 1;
  }
}

TEST(Sleep, ABallDroppedOnASleepingStackWakesTheWholeIsland) {
  Scene scene = stack_of_ten();
  // a ball far to the side, resting until the test drops it on the stack
  scene.objects.push_back(test::dynamic_object("ball", Shape::sphere(0.02), 0.2,
                                               test::at(1.0, 0.0, 0.02), test::material(1e5)));
  const int ball = static_cast<int>(scene.objects.size()) - 1;
  World world(scene);
  ASSERT_GT(step_until_all_asleep(world, 5.0), 0.0);
  // the ball 5 cm over the top box, awake and falling
  WorldState s = world.state();
  s.bodies[ball].X_GO.translation() = Eigen::Vector3d(0.0, 0.0, 0.5 + 0.02 + 0.05);
  s.bodies[ball].wake();
  world.restore(s);
  int steps = 0;
  while (world.bodies()[10].asleep && steps < 300) {
    world.step();
    ++steps;
  }
  ASSERT_LT(steps, 300) << "the ball never woke the top box";
  // about sqrt(2 * 0.05 / 9.81) = 0.1 s of fall
  EXPECT_NEAR(steps * 1e-3, 0.101, 0.01);
  for (int i = 1; i <= 10; ++i) EXPECT_FALSE(world.bodies()[i].asleep) << "box " << i - 1;
  // the stack takes the ball and, still, sleeps again with it
  const double again_s = step_until_all_asleep(world, 10.0);
  ASSERT_GT(again_s, 0.0);
  EXPECT_NEAR(world.bodies()[ball].X_GO.translation().head<2>().norm(), 0.0, 0.03);
  EXPECT_EQ(world.bodies()[ball].island, 1) << "the ball rests on the stack: one island";
}

TEST(Sleep, ABoxOnALongerSlopeThatFrictionHoldsSleepsAndWakesWithoutSliding) {
  Scene scene;
  scene.objects.push_back(test::floor_box(test::material(1e5)));
  // a 10 degree ramp (mu_s 0.6 holds up to 31 degrees) and a box resting on it
  const double slope_rad = 10.0 * M_PI / 180.0;
  scene.objects.push_back(test::static_box("ramp", {1.0, 0.5, 0.02}, test::at(0, 0, 0.2, 0, -10.0, 0),
                                           test::material(1e5)));
  const Eigen::Vector3d up(std::sin(slope_rad), 0.0, std::cos(slope_rad));
  Eigen::Isometry3d X_GB = test::at(0, 0, 0.2, 0, -10.0, 0);
  X_GB.translation() += (0.01 + 0.025) * up;
  scene.objects.push_back(test::dynamic_object("box", Shape::box({0.05, 0.05, 0.05}), 0.1, X_GB,
                                               test::material(1e5)));
  scene.objects.push_back(test::dynamic_object("ball", Shape::sphere(0.02), 0.2,
                                               test::at(1.0, 1.0, 0.02), test::material(1e5)));
  World world(scene);
  ASSERT_GT(step_until_all_asleep(world, 3.0), 0.0);
  const Eigen::Vector3d slept_at = world.bodies()[2].X_GO.translation();
  // a ball dropped beside it onto the ramp wakes it (both on the ramp: the ball's contact
  // is with the ramp, so it must touch the box to wake it: dropped onto its top)
  WorldState s = world.state();
  s.bodies[3].X_GO.translation() = slept_at + Eigen::Vector3d(0.0, 0.0, 0.025 + 0.02 + 0.01);
  s.bodies[3].wake();
  world.restore(s);
  for (int i = 0; i < 200 && world.bodies()[2].asleep; ++i) world.step();
  ASSERT_FALSE(world.bodies()[2].asleep);
  for (int i = 0; i < 500; ++i) world.step();
  // woken with fresh friction anchors, it gives way by their stretch at most, and holds
  const Eigen::Vector3d moved = world.bodies()[2].X_GO.translation() - slept_at;
  EXPECT_LT(moved.norm(), 2e-3) << "moved " << moved.transpose() * 1e3 << " mm";
}

TEST(Sleep, TurnedOffNothingEverSleeps) {
  Scene scene = stack_of_ten();
  scene.sleep.enabled = false;
  World world(scene);
  EXPECT_LT(step_until_all_asleep(world, 2.0), 0.0);
  EXPECT_EQ(asleep_count(world), 0);
  EXPECT_FALSE(world.contacts().empty());
}

// A heap: 60 boxes and balls in three layers of a 5 x 4 grid 7 cm apart, each layer set 1 cm
// over the one below and off it by half a cell, each object a little off its place and turned,
// so that they fall onto each other. It settles, sleeps, and then costs no contact at all.
// (Dropped from tens of centimetres, such a heap pushes some objects through the floor,
// sleeping or not: a fault of the penalty contacts under a stack's impacts, not of sleeping.)
TEST(Sleep, AHeapOfMixedObjectsSettlesAndSleeps) {
  Scene scene;
  scene.objects.push_back(test::floor_box(test::material(1e5)));
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> jitter(-0.005, 0.005);
  for (int i = 0; i < 60; ++i) {
    const int layer = i / 20;
    const Shape shape = (i + layer) % 2 == 0 ? Shape::box({0.04, 0.05, 0.03}) : Shape::sphere(0.02);
    const double half = 0.035 * (layer % 2);
    const double x = 0.07 * (i % 5 - 2) + half + jitter(rng);
    const double y = 0.07 * ((i / 5) % 4 - 1.5) + half + jitter(rng);
    const double z = 0.03 + 0.05 * layer;
    scene.objects.push_back(test::dynamic_object("o" + std::to_string(i), shape, 0.05,
                                                 test::at(x, y, z, 10.0 * i, 7.0 * i, 13.0 * i),
                                                 test::material(1e5)));
  }
  World world(scene);
  // (a ball knocked off the heap rolls on until its rolling resistance stops it: seconds)
  const double slept_s = step_until_all_asleep(world, 20.0);
  if (slept_s < 0.0) {
    for (std::size_t i = 0; i < world.bodies().size(); ++i) {
      const BodyState& b = world.bodies()[i];
      if (!b.asleep && world.scene().objects[i].dynamic)
        std::printf("awake %zu: v %.4f w %.4f still %.3f z %.3f\n", i, b.v_G.norm(), b.w_G.norm(),
                    b.still_s, b.X_GO.translation().z());
    }
  }
  ASSERT_GT(slept_s, 0.0) << asleep_count(world) << " of 60 asleep after 20 s";
  std::printf("the heap fell asleep at %.3f s\n", slept_s);
  world.step();
  EXPECT_TRUE(world.contacts().empty());
  for (std::size_t i = 1; i < world.bodies().size(); ++i)
    EXPECT_GT(world.bodies()[i].X_GO.translation().z(), 0.0) << "object " << i << " under the floor";
}

// The default cockpit and its bundled log: the cup on the console sleeps until the hand
// reaches it, wakes as the fingers touch it, and is grasped as before.
TEST(Sleep, TheCupSleepsOnTheConsoleUntilTheHandTakesIt) {
  const Scene scene = load_scene(source_dir() + "/config/cockpit.yaml");
  const std::vector<hand::GloveSample> samples =
      hand::read_glove_log(source_dir() + "/config/glove_logs/reach_grasp_lift_release.csv",
                           scene.hands[0])
          .samples;
  const int cup = scene.find_object("cup");
  World world(scene);
  std::size_t next = 0;
  bool slept = false, grasped = false, awake_at_grasp = false;
  double woke_s = -1.0;
  while (world.time_ns() < 3'500'000'000 && !grasped) {
    while (next < samples.size() && samples[next].t_ns - samples.front().t_ns <= world.time_ns())
      world.set_hand_input(physics_io::hand_input_from_glove(scene.hands[0], samples[next++]));
    const bool was_asleep = world.bodies()[cup].asleep;
    world.step();
    slept = slept || world.bodies()[cup].asleep;
    if (was_asleep && !world.bodies()[cup].asleep) woke_s = static_cast<double>(world.time_ns()) * 1e-9;
    for (const GraspEvent& e : world.step_events())
      if (e.grasp && e.object == cup) {
        grasped = true;
        awake_at_grasp = !was_asleep;
        std::printf("the cup woke at %.3f s and was grasped at %.3f s\n", woke_s,
                    static_cast<double>(e.t_ns) * 1e-9);
      }
  }
  EXPECT_TRUE(slept) << "the cup never slept on the console";
  ASSERT_TRUE(grasped);
  EXPECT_TRUE(awake_at_grasp);
}

TEST(SleepTracker, WakingOneBodyWakesItsIslandOnly) {
  std::vector<BodyState> bodies(5);
  for (int i : {1, 2, 4}) {
    bodies[i].asleep = true;
    bodies[i].island = 1;
  }
  bodies[3].asleep = true;
  bodies[3].island = 3;
  EXPECT_EQ(SleepTracker::wake_island(2, bodies), 3);
  EXPECT_FALSE(bodies[1].asleep || bodies[2].asleep || bodies[4].asleep);
  EXPECT_TRUE(bodies[3].asleep);
  EXPECT_EQ(SleepTracker::wake_island(2, bodies), 0);  // already awake
  SleepTracker::wake_all(bodies);
  EXPECT_FALSE(bodies[3].asleep);
}

}  // namespace
}  // namespace vcockpit::physics
