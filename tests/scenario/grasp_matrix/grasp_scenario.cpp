#include "tests/scenario/grasp_matrix/grasp_scenario.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "glove_driver/glove/gesture_script.hpp"
#include "hand/config/hand_yaml.hpp"
#include "hand/sample_validator.hpp"
#include "physics_node/config/scene_config.hpp"
#include "physics_node/io/grasp_event_text.hpp"
#include "physics_node/io/replay_driver.hpp"

namespace vcockpit::test {
namespace {

constexpr int64_t kCheckEvery_ns = 10'000'000;  // the offline runner's output step
constexpr int64_t kSettle_ns = 1'000'000'000;   // after the log: the object comes to rest

}  // namespace

ScenarioResult run_grasp_scenario(const std::string& source_dir, const GraspCase& grasp_case,
                                  const std::string& hand_yaml, const degrade::DegradeSpec& spec,
                                  const std::function<void(const physics::World&)>& observe) {
  physics::Scene scene = load_scene(source_dir + "/config/cockpit.yaml");
  scene.hands = {load_hand_model(source_dir + "/config/" + hand_yaml)};
  const int object = scene.find_object(grasp_case.object);
  if (object < 0) throw std::invalid_argument("no object '" + grasp_case.object + "'");
  const hand::HandModel hand = scene.hands[0];
  const auto rows = degrade::degrade(
      script_samples(source_dir + "/config/gestures/" + grasp_case.script, hand), hand, spec);

  physics::World world(std::move(scene));
  const double start_z_m = world.bodies()[object].X_GO.translation().z();
  HandStaticClearance clearance(world.scene(), hand);
  ScenarioResult r;
  auto step = [&] {
    world.step();
    for (const auto& e : world.step_events()) {
      char line[256];
      std::snprintf(line, sizeof line, "%.3f s %s %s: %s\n", static_cast<double>(e.t_ns) * 1e-9,
                    e.grasp ? "GRASP" : "RELEASE", world.scene().objects[e.object].name.c_str(),
                    physics_io::grasp_event_text(e).c_str());
      r.events += line;
      if (e.object != object) {
        ++r.other_events;
      } else if (e.grasp) {
        if (r.grasps++ == 0) r.first_grasp_ns = e.t_ns;
      } else {
        if (r.releases++ == 0) r.first_release_ns = e.t_ns;
      }
    }
    if (r.grasps == 0) {
      r.max_speed_before_grasp_mps =
          std::max(r.max_speed_before_grasp_mps, world.bodies()[object].v_G.norm());
    }
    const physics::BodyState& body = world.bodies()[object];
    if (body.held_by != physics::kNotHeld) {
      r.max_lift_held_m = std::max(r.max_lift_held_m, body.X_GO.translation().z() - start_z_m);
    }
    if (observe) observe(world);
    if (world.hand_active() && world.time_ns() % kCheckEvery_ns == 0) {
      const Penetration p = clearance.deepest(world.X_GL());
      if (p.depth_m > r.deepest_static.depth_m) {
        r.deepest_static = p;
        r.deepest_static_ns = world.time_ns();
      }
    }
  };
  physics_io::ReplayDriver driver(world, hand);
  // the checks the offline runner and a live node make: joint values past the hand's range are
  // clamped to it (without this the proxy took a thumb 2 deg past its limit, and bending it back
  // into range pushed it 2.7 mm into the held cup)
  hand::SampleValidator validator(hand);
  for (const auto& row : rows) {
    if (!row.valid) continue;  // the log reader skips dropout rows
    hand::GloveSample sample = row.sample;
    if (!validator.accept(sample)) continue;
    driver.feed(sample, step);
    ++r.samples_fed;
  }
  driver.step_until(world.time_ns() + kSettle_ns, step);
  r.final_p_G = world.bodies()[object].X_GO.translation();
  r.place_error_m = (r.final_p_G - grasp_case.place_G).norm();
  return r;
}

}  // namespace vcockpit::test
