// The world's state (world_state.hpp): two worlds stepping the same inputs stay bit-identical
// (equal hashes), a world restored to a state continues exactly as the original (through a grasp
// and a release), and the hash sees a body move by one ulp. The body check (body_check.hpp): a
// body given an absurd or NaN velocity is caught, named once, counted, and put back at rest
// where it was, and the world goes on with finite states.

#include "physics_node/physics/world.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "hand/glove_log.hpp"
#include "physics_node/config/scene_config.hpp"
#include "physics_node/io/hand_input.hpp"
#include "physics_node/io/world_checkpoint.hpp"
#include "physics_node/physics/world_state_hash.hpp"
#include "tests/support/allocation_counter.hpp"
#include "tests/support/scene_builder.hpp"

namespace vcockpit::physics {
namespace {

std::string source_dir() {
  const char* dir = std::getenv("VCOCKPIT_SOURCE_DIR");
  return dir ? dir : ".";
}

// The default cockpit and its bundled grasping log: the cup is grasped at 3.25 s, lifted and
// released at 6.76 s.
struct Cockpit {
  Scene scene = load_scene(source_dir() + "/config/cockpit.yaml");
  std::vector<hand::GloveSample> samples =
      hand::read_glove_log(source_dir() + "/config/glove_logs/reach_grasp_lift_release.csv",
                            scene.hands[0])
          .samples;
  int cup = scene.find_object("cup");
};

// Feeds a world the log's samples up to its time, as the offline runner does.
struct GloveFeed {
  const std::vector<hand::GloveSample>* samples;
  std::size_t next = 0;

  void feed(World& world) {
    const int64_t t0 = samples->front().t_ns;
    while (next < samples->size() && (*samples)[next].t_ns - t0 <= world.time_ns())
      world.set_hand_input(
          physics_io::hand_input_from_glove(world.scene().hands[0], (*samples)[next++]));
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
  for (int i = 0; i < 3500; ++i) {  // through the grasp at 3.25 s
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
  while (original.time_ns() < 7'500'000'000) {  // past the release at 6.76 s
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
  feed.run_until(world, 2.6);  // the hand closing on the cup: contacts and stick anchors
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

// The same from a state with sleeping bodies (at 2.5 s the cup and the loose objects sleep on the
// console; the fingers wake the cup at 2.57 s): they wake and go on as in the original.
TEST(WorldState, RestoringAWorldWithSleepersReplaysItsOwnFuture) {
  const Cockpit cockpit;
  World world(cockpit.scene);
  GloveFeed feed{&cockpit.samples};
  feed.feed(world);
  feed.run_until(world, 2.5);
  const WorldState saved = world.state();
  const GloveFeed saved_feed = feed;
  ASSERT_TRUE(saved.bodies[cockpit.cup].asleep);
  feed.run_until(world, 3.0);
  ASSERT_FALSE(world.bodies()[cockpit.cup].asleep);
  const uint64_t first = hash_world_state(world.state());

  World other(cockpit.scene);  // another world: nothing of the first's scratch
  other.restore(saved);
  feed = saved_feed;
  feed.run_until(other, 3.0);
  EXPECT_EQ(hash_world_state(other.state()), first);
}

// An instructor's reset (World::reset_objects): the objects and controls go back to the saved
// state while time goes on and the hand stays where its glove is; the held cup is let go with a
// "scene reset" release, and a control put back reports a commanded change.
TEST(WorldReset, ObjectsAndControlsGoBackTimeGoesOnHeldObjectsAreLetGo) {
  const Cockpit cockpit;
  World world(cockpit.scene);
  const WorldState start = world.state();
  GloveFeed feed{&cockpit.samples};
  feed.feed(world);
  feed.run_until(world, 4.0);  // the cup held and lifted
  ASSERT_NE(world.bodies()[cockpit.cup].held_by, kNotHeld);
  const int lights = cockpit.scene.find_control("landing_lights");
  ASSERT_GE(lights, 0);
  const int lights_start = world.state().controls[static_cast<std::size_t>(lights)].position;
  ASSERT_TRUE(world.command_control(lights, lights_start == 0 ? 2 : 0));
  world.step();
  feed.feed(world);
  const int lights_moved = world.state().controls[static_cast<std::size_t>(lights)].position;
  ASSERT_NE(lights_moved, lights_start);
  const int64_t t_ns = world.time_ns();
  const uint64_t steps = world.step_count();
  const Eigen::Isometry3d X_GH = world.X_GH();

  world.reset_objects(start);
  EXPECT_EQ(world.time_ns(), t_ns) << "time goes on";
  EXPECT_EQ(world.step_count(), steps);
  EXPECT_TRUE(same_bits(world.X_GH(), X_GH)) << "the hand stays where its glove is";
  for (std::size_t i = 0; i < start.bodies.size(); ++i) {
    EXPECT_TRUE(same_bits(world.bodies()[i].X_GO, start.bodies[i].X_GO)) << "object " << i;
    EXPECT_EQ(world.bodies()[i].held_by, kNotHeld);
  }
  ASSERT_EQ(world.step_events().size(), 1u);
  EXPECT_FALSE(world.step_events()[0].grasp);
  EXPECT_EQ(world.step_events()[0].object, cockpit.cup);
  EXPECT_EQ(world.step_events()[0].reason, GraspReason::kReset);
  EXPECT_EQ(world.state().controls[static_cast<std::size_t>(lights)].position, lights_start);
  bool reported = false;
  for (const ControlEvent& e : world.control_events())
    reported = reported || (e.control == lights && e.from == lights_moved && e.to == lights_start &&
                            e.cause == ControlCause::kCommanded);
  EXPECT_TRUE(reported) << "the control's change back is reported";

  // the world goes on from there: the cup, put back on the console under a hand above it,
  // stays put and nobody holds it
  const Eigen::Vector3d cup_start = start.bodies[static_cast<std::size_t>(cockpit.cup)].X_GO.translation();
  for (int i = 0; i < 200; ++i) world.step();
  EXPECT_GT(world.time_ns(), t_ns);
  EXPECT_LT((world.bodies()[cockpit.cup].X_GO.translation() - cup_start).norm(), 0.01);
}

TEST(WorldReset, ToACheckpointPutsBackItsObjectsFree) {
  const Cockpit cockpit;
  World world(cockpit.scene);
  GloveFeed feed{&cockpit.samples};
  feed.feed(world);
  feed.run_until(world, 4.0);  // the cup held, lifted
  const WorldState checkpoint = world.state();
  const Eigen::Isometry3d cup_then = checkpoint.bodies[static_cast<std::size_t>(cockpit.cup)].X_GO;
  feed.run_until(world, 7.5);  // set down and released
  ASSERT_EQ(world.bodies()[cockpit.cup].held_by, kNotHeld);
  World start(cockpit.scene);
  world.reset_objects(start.state());
  EXPECT_TRUE(same_bits(world.bodies()[cockpit.cup].X_GO, start.bodies()[cockpit.cup].X_GO));
  world.reset_objects(checkpoint);
  EXPECT_TRUE(same_bits(world.bodies()[cockpit.cup].X_GO, cup_then));
  EXPECT_EQ(world.bodies()[cockpit.cup].held_by, kNotHeld) << "where it was held, but free";
  EXPECT_TRUE(world.step_events().empty()) << "nothing was held at the reset";
  for (int i = 0; i < 50; ++i) world.step();
  EXPECT_LT(world.bodies()[cockpit.cup].X_GO.translation().z(), cup_then.translation().z() - 0.005)
      << "it falls";
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
  EXPECT_TRUE(changed([&](WorldState& s) { s.bodies[cockpit.cup].holders = 1; }));
  EXPECT_TRUE(changed([&](WorldState& s) { s.bodies[cockpit.cup].asleep = true; }));
  EXPECT_TRUE(changed([&](WorldState& s) { s.bodies[cockpit.cup].still_s = 0.001; }));
  EXPECT_TRUE(changed([&](WorldState& s) { s.bodies[cockpit.cup].island = 3; }));
  EXPECT_TRUE(changed([](WorldState& s) { s.hands[0].active = true; }));
  EXPECT_TRUE(changed([](WorldState& s) { s.hands[0].to.q_rad[5] = 0.1; }));
  EXPECT_TRUE(changed([](WorldState& s) { s.hands[0].from.tracking = false; }));
  EXPECT_TRUE(changed([](WorldState& s) { s.hands[0].X_GL[3].translation().y() = 0.5; }));
  EXPECT_TRUE(changed([](WorldState& s) { s.hands[0].finger_pull_G.x() = 1e-3; }));
  EXPECT_TRUE(changed([&](WorldState& s) { s.hands[0].grasp[cockpit.cup].released_at_ns = 0; }));
  EXPECT_TRUE(
      changed([&](WorldState& s) { s.hands[0].grasp[cockpit.cup].history[1].translation().z() = 1; }));
  EXPECT_TRUE(changed([](WorldState& s) { s.anchors.push_back(StickAnchor{}); }));
}

// A floor with two 10 cm boxes resting on it, far apart: "runaway" and "steady".
Scene two_boxes() {
  Scene scene;
  scene.objects.push_back(test::floor_box(test::material(1e5)));
  const Shape cube = Shape::box({0.1, 0.1, 0.1});
  scene.objects.push_back(
      test::dynamic_object("runaway", cube, 0.5, test::at(0.0, 0.0, 0.05), test::material(1e5)));
  scene.objects.push_back(
      test::dynamic_object("steady", cube, 0.5, test::at(1.0, 0.0, 0.05), test::material(1e5)));
  return scene;
}

bool all_finite(const World& world) {
  for (const BodyState& b : world.bodies())
    if (!b.X_GO.matrix().allFinite() || !b.v_G.allFinite() || !b.w_G.allFinite()) return false;
  return true;
}

TEST(BodyCheck, AbsurdSpeedIsCaughtNamedOnceAndPutBackAtRest) {
  Scene scene = two_boxes();
  const int runaway = scene.find_object("runaway");
  scene.objects[runaway].v_G = {1e300, 0.0, 0.0};  // m/s
  World world(scene);
  const Eigen::Isometry3d start = world.bodies()[runaway].X_GO;

  world.step();
  ASSERT_EQ(world.step_faults().size(), 1u);
  const BodyFault& f = world.step_faults()[0];
  EXPECT_EQ(f.object, runaway);
  EXPECT_EQ(world.scene().objects[f.object].name, "runaway");
  EXPECT_EQ(f.what, BodyFaultKind::kTooFast);
  EXPECT_EQ(f.first_t_ns, world.time_ns());
  const BodyState& body = world.bodies()[runaway];
  EXPECT_TRUE(same_bits(body.X_GO, start)) << "back where it was at the step's start";
  EXPECT_EQ(body.v_G, Eigen::Vector3d::Zero());
  EXPECT_EQ(body.w_G, Eigen::Vector3d::Zero());

  for (int i = 0; i < 500; ++i) {
    world.step();
    ASSERT_TRUE(all_finite(world)) << "step " << i;
    ASSERT_TRUE(world.step_faults().empty()) << "reported once";
  }
  ASSERT_EQ(world.body_faults().size(), 1u);
  EXPECT_EQ(world.body_faults()[0].object, runaway);
  EXPECT_EQ(world.body_faults()[0].count, 1u);
  // both boxes rest on the floor, centroids 5 cm up less m g / k_eff
  for (int object : {runaway, scene.find_object("steady")}) {
    EXPECT_NEAR(world.bodies()[object].X_GO.translation().z(), 0.05, 1e-3);
    EXPECT_LT(world.bodies()[object].v_G.norm(), 1e-3);
  }
}

TEST(BodyCheck, NanVelocityIsCaughtAndTheWorldGoesOn) {
  const Scene scene = two_boxes();
  const int runaway = scene.find_object("runaway");
  World world(scene);
  for (int i = 0; i < 100; ++i)
    world.step();
  ASSERT_TRUE(world.body_faults().empty());
  WorldState bad = world.state();
  bad.bodies[runaway].v_G.x() = std::numeric_limits<double>::quiet_NaN();
  world.restore(bad);

  world.step();
  ASSERT_EQ(world.step_faults().size(), 1u);
  EXPECT_EQ(world.step_faults()[0].object, runaway);
  EXPECT_EQ(world.step_faults()[0].what, BodyFaultKind::kNonFinite);
  EXPECT_TRUE(same_bits(world.bodies()[runaway].X_GO, bad.bodies[runaway].X_GO));
  EXPECT_EQ(world.bodies()[runaway].v_G, Eigen::Vector3d::Zero());
  for (int i = 0; i < 500; ++i) {
    world.step();
    ASSERT_TRUE(all_finite(world)) << "step " << i;
    ASSERT_TRUE(world.step_faults().empty());
  }
  ASSERT_EQ(world.body_faults().size(), 1u);
  EXPECT_EQ(world.body_faults()[0].count, 1u);

  // broken again later: counted, not reported again
  bad = world.state();
  bad.bodies[runaway].w_G.z() = std::numeric_limits<double>::infinity();
  world.restore(bad);
  world.step();
  EXPECT_TRUE(world.step_faults().empty());
  ASSERT_EQ(world.body_faults().size(), 1u);
  EXPECT_EQ(world.body_faults()[0].count, 2u);
  EXPECT_EQ(world.body_faults()[0].what, BodyFaultKind::kNonFinite) << "the first fault's kind";
  EXPECT_TRUE(all_finite(world));
}

TEST(BodyCheck, BrokenStartFallsBackToTheInitialPose) {
  const Scene scene = two_boxes();
  const int runaway = scene.find_object("runaway");
  World world(scene);
  WorldState bad = world.state();
  bad.bodies[runaway].X_GO.translation().x() = std::numeric_limits<double>::quiet_NaN();
  world.restore(bad);
  world.step();
  ASSERT_EQ(world.step_faults().size(), 1u);
  EXPECT_TRUE(same_bits(world.bodies()[runaway].X_GO, scene.objects[runaway].X_GO));
}

TEST(BodyCheck, LimitsOnSpeedSpinAndDistance) {
  const SanityLimits limits;  // 100 m/s, 1000 rad/s, 1 km
  BodyState b;
  EXPECT_EQ(check_body(b, limits), BodyFaultKind::kNone);
  b.v_G = {99.0, 0.0, 0.0};
  b.w_G = {0.0, 999.0, 0.0};
  b.X_GO.translation() = Eigen::Vector3d(0.0, 0.0, 999.0);
  EXPECT_EQ(check_body(b, limits), BodyFaultKind::kNone);
  b.v_G.x() = 101.0;
  EXPECT_EQ(check_body(b, limits), BodyFaultKind::kTooFast);
  b.v_G.x() = 1e200;  // |v|^2 overflows: still too fast, not missed
  EXPECT_EQ(check_body(b, limits), BodyFaultKind::kTooFast);
  b.v_G.x() = 0.0;
  b.w_G.y() = 1001.0;
  EXPECT_EQ(check_body(b, limits), BodyFaultKind::kSpinning);
  b.w_G.y() = 0.0;
  b.X_GO.translation().z() = 1001.0;
  EXPECT_EQ(check_body(b, limits), BodyFaultKind::kTooFar);
  b.X_GO.linear()(1, 1) = -std::numeric_limits<double>::infinity();
  EXPECT_EQ(check_body(b, limits), BodyFaultKind::kNonFinite);
}

TEST(WorldStep, AllocatesNothingOnceWarm) {
  // round bodies resting on a box floor take the face test, never FCL (whose narrowphase
  // allocates): so the rest of the step, stages, state and checks included, is counted
  Scene scene;
  scene.objects.push_back(test::floor_box(test::material(1e5)));
  scene.objects.push_back(test::dynamic_object("cup", Shape::cylinder(0.035, 0.1), 0.2,
                                               test::at(0.0, 0.0, 0.05), test::material(3e4)));
  scene.objects.push_back(test::dynamic_object("pen", Shape::capsule(0.005, 0.12), 0.02,
                                               test::at(0.3, 0.0, 0.005, 0, 90, 0),
                                               test::material(3e4)));
  World world(scene);
  for (int i = 0; i < 300; ++i)
    world.step();
  ASSERT_FALSE(world.contacts().empty());
  test::g_allocations = 0;
  test::g_count_allocations = true;
  static void* volatile sink = nullptr;  // control: the counter sees an allocation
  sink = ::operator new(16);
  test::g_count_allocations = false;
  ::operator delete(sink);
  ASSERT_EQ(test::g_allocations.load(), 1);
  const auto allocations_in_100_steps = [&] {
    test::g_allocations = 0;
    test::g_count_allocations = true;
    for (int i = 0; i < 100; ++i)
      world.step();
    test::g_count_allocations = false;
    return test::g_allocations.load();
  };
  EXPECT_EQ(allocations_in_100_steps(), 0);
  // and asleep (sleep.hpp): both come to rest and sleep, and steps with sleepers allocate nothing
  for (int i = 0; i < 1500 && !(world.bodies()[1].asleep && world.bodies()[2].asleep); ++i)
    world.step();
  ASSERT_TRUE(world.bodies()[1].asleep && world.bodies()[2].asleep);
  EXPECT_EQ(allocations_in_100_steps(), 0);
  EXPECT_TRUE(world.body_faults().empty());
}

// Checkpoints (physics_io::world_checkpoint): a world saved to bytes and restored from them goes
// on bit-identically; a damaged file, another scene's, or one whose checksum holds but whose
// contents point outside the scene is refused with what is wrong, never half-restored.
// Each stage's timer runs where that stage runs and nowhere else: the proxy goal, the proxy
// hand and the body check have their own (they were once counted in the broadphase, the hand
// kinematics and the integration). A stage that does not run (no proxy without a hand) takes no
// time; the names are the topics' and the summaries' keys, one per stage.
TEST(WorldStep, EachStageIsTimedWhereItRunsAndOnlyThere) {
  std::vector<std::string> names;
  for (int s = 0; s < kStageCount; ++s) names.emplace_back(stage_name(static_cast<Stage>(s)));
  EXPECT_EQ(names, (std::vector<std::string>{"proxy_goal", "hand_kinematics", "broadphase",
                                             "narrowphase", "proxy_hand", "forces", "integrate",
                                             "body_check", "grasp"}));
  World boxes(two_boxes());
  boxes.step();
  EXPECT_FALSE(boxes.has_proxy());
  EXPECT_EQ(boxes.stage_times().ns[static_cast<int>(Stage::kProxyHand)], 0);

  Cockpit cockpit;
  World world(cockpit.scene);
  ASSERT_TRUE(world.has_proxy());
  GloveFeed glove{&cockpit.samples};
  glove.feed(world);
  world.step();
  for (const Stage stage : {Stage::kProxyGoal, Stage::kHandKinematics, Stage::kBroadphase,
                            Stage::kNarrowphase, Stage::kProxyHand, Stage::kForces,
                            Stage::kIntegrate, Stage::kBodyCheck, Stage::kGrasp})
    EXPECT_GT(world.stage_times().ns[static_cast<int>(stage)], 0) << stage_name(stage);
  world.restore(world.state());
  for (int s = 0; s < kStageCount; ++s) EXPECT_EQ(world.stage_times().ns[s], 0) << "observations of the last step";
}

// A run that times one step in three (World::set_stage_timing_every) reads the clocks on steps
// 0, 3, 6, ..., and each such step reports three times what it took (a sum over a run estimates
// the run's); the steps between report nothing. What the world computes does not change.
TEST(WorldStep, OneStepInNIsTimedAndStandsForTheNSteps) {
  Cockpit cockpit;
  World sampled(cockpit.scene);
  World every(cockpit.scene);
  sampled.set_stage_timing_every(3);
  GloveFeed glove_a{&cockpit.samples}, glove_b{&cockpit.samples};
  for (int step = 0; step < 9; ++step) {
    glove_a.feed(sampled);
    glove_b.feed(every);
    sampled.step();
    every.step();
    const StageTimes& t = sampled.stage_times();
    EXPECT_EQ(t.timed, step % 3 == 0) << step;
    int64_t total = 0;
    for (const int64_t ns : t.ns) {
      EXPECT_EQ(ns % 3, 0) << step;
      total += ns;
    }
    if (t.timed)
      EXPECT_GT(total, 0) << step;
    else
      EXPECT_EQ(total, 0) << step;
  }
  EXPECT_EQ(hash_world_state(sampled.state()), hash_world_state(every.state()));
}

namespace checkpoint {

using physics_io::Checkpoint;
using physics_io::CheckpointError;

std::string refusal(std::string_view bytes, const World& fresh) {
  try {
    physics_io::decode_checkpoint(bytes, fresh);
  } catch (const CheckpointError& e) {
    return e.what();
  }
  return "accepted";
}

TEST(WorldCheckpoint, AWorldSavedHeldAndRestoredFromTheBytesGoesOnBitIdentically) {
  const Cockpit cockpit;
  World original(cockpit.scene);
  GloveFeed feed{&cockpit.samples};
  feed.feed(original);
  feed.run_until(original, 4.0);  // the cup held, lifted
  World fresh(cockpit.scene);
  const uint64_t fingerprint = physics_io::scene_fingerprint(fresh);
  const std::string bytes = physics_io::encode_checkpoint({original.state(), true}, fingerprint);
  const Checkpoint read = physics_io::decode_checkpoint(bytes, fresh);
  EXPECT_TRUE(read.frozen);
  World restored(cockpit.scene);
  restored.restore(read.world);
  EXPECT_EQ(hash_world_state(restored.state()), hash_world_state(original.state()));
  GloveFeed restored_feed = feed;
  while (original.time_ns() < 7'000'000'000) {  // through the release at 6.76 s
    original.step();
    restored.step();
    feed.feed(original);
    restored_feed.feed(restored);
  }
  EXPECT_EQ(hash_world_state(restored.state()), hash_world_state(original.state()));
  EXPECT_EQ(restored.bodies()[cockpit.cup].held_by, kNotHeld);
}

TEST(WorldCheckpoint, DamagedForeignOrOutOfSceneCheckpointsAreRefusedWithWhy) {
  const Cockpit cockpit;
  World world(cockpit.scene);
  GloveFeed feed{&cockpit.samples};
  feed.feed(world);
  feed.run_until(world, 2.6);  // fingers on the cup (awake from 2.57 s): stick anchors
  const World fresh(cockpit.scene);
  const uint64_t fingerprint = physics_io::scene_fingerprint(fresh);
  const std::string good = physics_io::encode_checkpoint({world.state(), false}, fingerprint);
  EXPECT_EQ(refusal(good, fresh), "accepted");

  std::string flipped = good;
  flipped[good.size() / 2] ^= 0x10;
  EXPECT_NE(refusal(flipped, fresh).find("checksum"), std::string::npos);
  EXPECT_NE(refusal(good.substr(0, good.size() - 9), fresh).find("checksum"), std::string::npos);
  EXPECT_NE(refusal(good.substr(0, 20), fresh).find("too short"), std::string::npos);
  std::string magic = good;
  magic[0] = 'X';
  EXPECT_NE(refusal(magic, fresh).find("not a checkpoint"), std::string::npos);

  Scene moved = cockpit.scene;
  moved.objects[static_cast<std::size_t>(cockpit.cup)].X_GO.translation().x() += 0.01;
  const World other(moved);
  EXPECT_NE(refusal(good, other).find("another scene"), std::string::npos);

  // well-formed files (checksums good) whose contents a world must not follow
  auto with = [&](auto change) {
    WorldState state = world.state();
    change(state);
    return physics_io::encode_checkpoint({state, false}, fingerprint);
  };
  EXPECT_NE(refusal(with([](WorldState& s) { s.bodies[0].v_G.x() = std::nan(""); }), fresh)
                .find("not finite"),
            std::string::npos);
  ASSERT_FALSE(world.state().controls.empty());
  EXPECT_NE(refusal(with([](WorldState& s) { s.controls[0].position = 99; }), fresh).find("position"),
            std::string::npos);
  EXPECT_NE(refusal(with([](WorldState& s) { s.bodies[0].holders = 0x80; }), fresh).find("held"),
            std::string::npos);
  EXPECT_NE(refusal(with([](WorldState& s) { s.bodies[0].asleep = true; s.bodies[0].island = 0; }), fresh)
                .find("asleep but not free"),
            std::string::npos);  // (object 0, the floor, is static)
  EXPECT_NE(refusal(with([&](WorldState& s) {
                      s.bodies[cockpit.cup].asleep = true;
                      s.bodies[cockpit.cup].island = -1;
                    }),
                    fresh)
                .find("island"),
            std::string::npos);
  ASSERT_FALSE(world.state().anchors.empty());
  EXPECT_NE(refusal(with([](WorldState& s) { s.anchors[0].body_b = 100000; }), fresh).find("anchor"),
            std::string::npos);
  EXPECT_NE(refusal(with([](WorldState& s) { s.hands[0].grasp[0].history_next = 1u << 20; }), fresh)
                .find("ring"),
            std::string::npos);
  EXPECT_NE(refusal(with([](WorldState& s) { s.bodies.pop_back(); }), fresh).find("another scene"),
            std::string::npos);
  EXPECT_NE(refusal(with([](WorldState& s) { s.hands[0].finger_pull_G.z() = 0.5; }), fresh)
                .find("finger pull"),
            std::string::npos);
  const int floor = cockpit.scene.find_object("floor");
  ASSERT_GE(floor, 0);
  ASSERT_FALSE(cockpit.scene.objects[static_cast<std::size_t>(floor)].dynamic);
  EXPECT_NE(refusal(with([&](WorldState& s) {
                      s.bodies[static_cast<std::size_t>(floor)].holders = 1;
                      s.bodies[static_cast<std::size_t>(floor)].held_by = 0;
                    }),
                    fresh)
                .find("static and held"),
            std::string::npos);
  EXPECT_NE(refusal(with([&](WorldState& s) { s.bodies[static_cast<std::size_t>(cockpit.cup)].holders = 1; }),
                    fresh)
                .find("disagree"),
            std::string::npos);
}

TEST(WorldCheckpoint, AFileIsWrittenWholeAndItsErrorsNameIt) {
  const Cockpit cockpit;
  const World fresh(cockpit.scene);
  const std::string dir = ::testing::TempDir() + "world_checkpoint_test";
  std::filesystem::create_directories(dir);
  const std::string path = dir + "/physics.ckpt";
  std::filesystem::remove(path);
  EXPECT_FALSE(physics_io::read_checkpoint_file(path, fresh).has_value()) << "no file: nothing";
  const std::string bytes =
      physics_io::encode_checkpoint({fresh.state(), false}, physics_io::scene_fingerprint(fresh));
  physics_io::write_checkpoint_file(path, bytes);
  EXPECT_FALSE(std::filesystem::exists(path + ".partial"));
  ASSERT_TRUE(physics_io::read_checkpoint_file(path, fresh).has_value());
  std::ofstream(path, std::ios::binary | std::ios::app) << "x";
  try {
    physics_io::read_checkpoint_file(path, fresh);
    ADD_FAILURE() << "a file with a byte too many was read";
  } catch (const CheckpointError& e) {
    EXPECT_NE(std::string(e.what()).find(path + ": "), std::string::npos) << e.what();
  }
}

}  // namespace checkpoint

}  // namespace
}  // namespace vcockpit::physics
