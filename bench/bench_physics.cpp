// Physics micro-benchmarks: hand forward kinematics, collision detection (broadphase +
// narrowphase) and one full world step, on the default cockpit with the hand holding the cup and
// on the same cockpit with 10, 100 and 500 loose objects. With MuJoCo 2.2 stepping the same
// scenes in the same run (BM_MujocoStep), so the two can be compared as a ratio.
//
// Every world is brought to its holding state once (bench_scenes.hpp) and kept, so a benchmark's
// fixed iteration count is one run of consecutive steps, each timed on its own (p50/p99/max).

#include <benchmark/benchmark.h>

#include <array>
#include <map>
#include <memory>
#include <string>
#include <tuple>

#include "bench/bench_scenes.hpp"
#include "bench/mujoco_scene.hpp"
#include "bench/step_timing.hpp"
#include "physics_node/physics/collision.hpp"
#include "hand/hand_model.hpp"
#include "physics_node/physics/world.hpp"

namespace vcockpit::bench {
namespace {

// A world at its holding state and the hand input that keeps it there.
struct HeldWorld {
  std::unique_ptr<physics::World> world;
  physics::HandInput hand;
};

physics::Scene scene_with(int loose_objects, bool sleep) {
  physics::Scene scene = loose_objects == 0 ? cockpit_scene() : crowded_cockpit_scene(loose_objects);
  scene.sleep.enabled = sleep;
  return scene;
}

// One per scene (and sleeping or not) for the whole run: the lead-in (4 s of the glove log) is
// paid once.
HeldWorld& held_world(int loose_objects, bool sleep = true) {
  static std::map<std::tuple<int, bool>, HeldWorld> worlds;
  const auto key = std::make_tuple(loose_objects, sleep);
  auto it = worlds.find(key);
  if (it == worlds.end()) {
    HeldWorld held;
    held.world = std::make_unique<physics::World>(scene_with(loose_objects, sleep));
    held.hand = step_to_hold(*held.world);
    it = worlds.emplace(key, std::move(held)).first;
  }
  return it->second;
}

int asleep_count(const physics::World& world) {
  int n = 0;
  for (const auto& b : world.bodies()) n += b.asleep ? 1 : 0;
  return n;
}

void scene_counters(benchmark::State& state, const physics::World& world) {
  int dynamic = 0;
  for (const auto& o : world.scene().objects) dynamic += o.dynamic ? 1 : 0;
  state.counters["dynamic_objects"] = dynamic;
}

void BM_HandForwardKinematics(benchmark::State& state) {
  HeldWorld& held = held_world(0);
  const hand::HandModel& hand = held.world->scene().hands[0];
  hand::JointAngles q = held.hand.q_rad;
  hand::HandLinkPoses poses;
  for (auto _ : state) {
    benchmark::DoNotOptimize(q);
    hand::forward_kinematics(hand, q, poses);
    benchmark::DoNotOptimize(poses);
  }
}
BENCHMARK(BM_HandForwardKinematics);

// Broadphase and narrowphase of one step, on the poses of a world at its holding state.
void BM_Collision(benchmark::State& state) {
  const int loose = static_cast<int>(state.range(0));
  HeldWorld& held = held_world(loose);
  const physics::World& world = *held.world;
  physics::CollisionWorld collision(world.scene());
  std::vector<Eigen::Isometry3d> X_GO;
  for (const auto& b : world.bodies()) X_GO.push_back(b.X_GO);
  std::vector<physics::ContactPoint> contacts;
  StepTiming timing(static_cast<std::size_t>(state.max_iterations));
  for (auto _ : state) {
    timing.time([&] {
      collision.set_poses(X_GO, &world.X_GL());
      collision.find_candidate_pairs();
      collision.compute_contacts(contacts);
    });
  }
  timing.report(state);
  scene_counters(state, world);
  state.counters["pairs"] = static_cast<double>(collision.candidate_pair_count());
  state.counters["contacts"] = static_cast<double>(contacts.size());
}
BENCHMARK(BM_Collision)->Arg(0)->Arg(10)->Arg(100)->Arg(500)->Iterations(2000)
    ->Unit(benchmark::kMicrosecond);

// One full world step (collision, the contacts' solve and the grasp test) with the hand holding
// the cup. range(1): 1 with sleeping (the default), 0 with every object kept awake.
void BM_WorldStep(benchmark::State& state) {
  const int loose = static_cast<int>(state.range(0));
  HeldWorld& held = held_world(loose, state.range(1) != 0);
  physics::World& world = *held.world;
  StepTiming timing(static_cast<std::size_t>(state.max_iterations));
  std::array<int64_t, physics::kStageCount> stage_ns{};
  for (auto _ : state) {
    timing.time([&] {
      world.set_hand_input(held.hand);
      world.step();
    });
    for (int s = 0; s < physics::kStageCount; ++s) stage_ns[s] += world.stage_times().ns[s];
  }
  timing.report(state);
  // where a step's time goes: the world's own stage timers, mean per step
  for (int s = 0; s < physics::kStageCount; ++s) {
    state.counters[std::string(physics::stage_name(static_cast<physics::Stage>(s))) + "_us"] =
        static_cast<double>(stage_ns[s]) * 1e-3 / static_cast<double>(state.iterations());
  }
  scene_counters(state, world);
  state.counters["contacts"] = static_cast<double>(world.contacts().size());
  state.counters["asleep"] = asleep_count(world);
  const int cup = world.scene().find_object("cup");
  state.counters["cup_held"] = world.bodies()[static_cast<std::size_t>(cup)].held_by ==
                                       physics::kNotHeld ? 0 : 1;
}

// MuJoCo stepping the same scene from the same state: the objects where ours are at the holding
// state, the hand's links as mocap bodies where ours are.
void BM_MujocoStep(benchmark::State& state) {
  const int loose = static_cast<int>(state.range(0));
  HeldWorld& held = held_world(loose);
  MujocoWorld mujoco(held.world->scene());
  mujoco.set_hand(held.world->X_GL());
  mujoco.set_object_states(held.world->bodies());  // the held cup welded to the palm
  for (int i = 0; i < 100; ++i) mujoco.step();  // let its soft contacts find their rest
  StepTiming timing(static_cast<std::size_t>(state.max_iterations));
  for (auto _ : state) timing.time([&] { mujoco.step(); });
  timing.report(state);
  scene_counters(state, *held.world);
  state.counters["contacts"] = mujoco.contact_count();
}

// A pile of range(0) objects settled in its bin: with sleeping, stepped once every object sleeps;
// without (range(1) == 0), stepped as long after the drop, every object awake at rest.
void BM_PileStep(benchmark::State& state) {
  const int objects = static_cast<int>(state.range(0));
  const bool sleep = state.range(1) != 0;
  physics::Scene scene = pile_scene(objects);
  scene.sleep.enabled = sleep;
  physics::World world(scene);
  constexpr double kSettle_s = 6.0;  // (the slowest ball stops rolling in 2-3 s)
  while (world.time_ns() < std::llround(kSettle_s * 1e9)) world.step();
  StepTiming timing(static_cast<std::size_t>(state.max_iterations));
  for (auto _ : state) timing.time([&] { world.step(); });
  timing.report(state);
  state.counters["dynamic_objects"] = objects;
  state.counters["asleep"] = asleep_count(world);
  state.counters["contacts"] = static_cast<double>(world.contacts().size());
  double lowest_m = 1.0;
  for (std::size_t i = 0; i < world.bodies().size(); ++i)
    if (world.scene().objects[i].dynamic)
      lowest_m = std::min(lowest_m, world.bodies()[i].X_GO.translation().z());
  state.counters["lowest_z_mm"] = lowest_m * 1e3;  // every object still on the floor
}

// Ours and MuJoCo's, scene by scene, so the JSON has them side by side; ours also with every
// object kept awake (what sleeping saves); and the pile.
void register_steps() {
  // (300: where a 1 kHz loop must still keep real time with every object awake)
  for (const int loose : {0, 10, 100, 300, 500}) {
    const int64_t iterations = loose >= 500 ? 500 : loose >= 100 ? 1000 : 3000;
    benchmark::RegisterBenchmark("BM_WorldStep", BM_WorldStep)
        ->Args({loose, 1})->Iterations(iterations)->Unit(benchmark::kMicrosecond);
    benchmark::RegisterBenchmark("BM_WorldStep", BM_WorldStep)
        ->Args({loose, 0})->Iterations(iterations)->Unit(benchmark::kMicrosecond);
    benchmark::RegisterBenchmark("BM_MujocoStep", BM_MujocoStep)
        ->Arg(loose)->Iterations(iterations)->Unit(benchmark::kMicrosecond);
  }
  for (const int sleep : {1, 0})
    benchmark::RegisterBenchmark("BM_PileStep", BM_PileStep)
        ->Args({200, sleep})->Iterations(500)->Unit(benchmark::kMicrosecond);
}

}  // namespace
}  // namespace vcockpit::bench

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  vcockpit::bench::register_steps();
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
