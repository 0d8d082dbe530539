#include "tests/scenario/real_grip/real_grip_run.hpp"

#include <algorithm>
#include <cstdlib>
#include <cstdio>
#include <stdexcept>

#include "hand/glove_log.hpp"
#include "hand/sample_validator.hpp"
#include "physics_node/config/scene_config.hpp"
#include "physics_node/io/replay_driver.hpp"
#include "physics_node/physics/broadphase.hpp"

namespace vcockpit::real_grip {

RealGripRun replay_real_grip(const std::string& scene_path, const std::string& log_path,
                             const std::string& object_name, const std::string& support_name) {
  physics::World world(load_scene(scene_path));
  const physics::Scene& scene = world.scene();
  const int object = scene.find_object(object_name);
  const int support = scene.find_object(support_name);
  if (object < 0 || support < 0)
    throw std::invalid_argument(scene_path + ": no object '" + object_name + "' or '" + support_name + "'");
  const hand::HandModel& hand = scene.hands.at(0);
  const auto log = hand::read_glove_log(log_path, hand);
  const auto& o = scene.objects[static_cast<std::size_t>(object)];
  const double support_top_z =
      physics::shape_aabb(scene.objects[static_cast<std::size_t>(support)].shape,
                          scene.objects[static_cast<std::size_t>(support)].X_GO)
          .hi.z();

  RealGripRun run;
  // VCOCKPIT_REAL_GRIP_TRACE=1: the object's pose every 10 ms on stderr (finding out why a run fails)
  const bool trace = std::getenv("VCOCKPIT_REAL_GRIP_TRACE") != nullptr;
  physics_io::ReplayDriver driver(world, hand);
  const auto step = [&] {
    world.step();
    const double t_s = static_cast<double>(world.time_ns()) * 1e-9;
    for (const auto& e : world.step_events()) {
      if (e.object != object) continue;
      char line[96];
      std::snprintf(line, sizeof line, "%.3f %s %s\n", t_s, e.grasp ? "GRASP" : "RELEASE",
                    physics::grasp_reason_name(e.reason));
      run.events += line;
      if (e.grasp) {
        ++run.grasps;
        if (run.grasp_s < 0.0) run.grasp_s = t_s;
      } else {
        ++run.releases;
        if (run.grasp_s >= 0.0 && run.release_s < 0.0) {
          run.release_s = t_s;
          run.release_reason = e.reason;
        }
      }
    }
    const physics::BodyState& body = world.bodies()[static_cast<std::size_t>(object)];
    if (run.release_s < 0.0 || t_s <= run.release_s + 0.3) {
      const double lowest_z = physics::shape_aabb(o.shape, body.X_GO).lo.z();
      run.deepest_below_support_m = std::max(run.deepest_below_support_m, support_top_z - lowest_z);
    }
    if (trace && world.time_ns() % 10'000'000 == 0) {
      const Eigen::Vector3d p = body.X_GO.translation();
      const physics::HandState& hs = world.state().hands[0];
      const Eigen::Vector3d proxy = hs.X_GH.translation(), tracked = hs.to.X_GH.translation();
      std::fprintf(stderr, "%.3f %s p %.4f %.4f %.4f v %.3f %.3f %.3f proxy %.4f %.4f %.4f tracked %.4f %.4f %.4f\n",
                   t_s, body.held() ? "held" : "free", p.x(), p.y(), p.z(), body.v_G.x(), body.v_G.y(),
                   body.v_G.z(), proxy.x(), proxy.y(), proxy.z(), tracked.x(), tracked.y(), tracked.z());
      for (const Eigen::Vector3d& n : hs.blocking_out_G)
        std::fprintf(stderr, "    blocking %.2f %.2f %.2f\n", n.x(), n.y(), n.z());
    }
    if (!body.held()) {
      const double horizontal_mps = body.v_G.head<2>().norm();
      if (horizontal_mps > run.fastest_free_horizontal_mps) {
        run.fastest_free_horizontal_mps = horizontal_mps;
        run.fastest_free_at_s = t_s;
      }
    }
    run.deepest_link_in_object_m = std::max(run.deepest_link_in_object_m, world.hand_penetration().max_m);
    run.deepest_link_in_static_m =
        std::max(run.deepest_link_in_static_m, world.hand_penetration().static_max_m);
  };
  // the checks the offline runner and a live node make (joint values past the hand's range clamped)
  hand::SampleValidator validator(hand);
  for (hand::GloveSample sample : log.samples)
    if (validator.accept(sample)) driver.feed(sample, step);
  // and a moment more, for what was let go to come to rest
  for (int i = 0; i < 500; ++i) step();
  run.end_s = static_cast<double>(world.time_ns()) * 1e-9;
  return run;
}

}  // namespace vcockpit::real_grip
