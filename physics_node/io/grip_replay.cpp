#include "physics_node/io/grip_replay.hpp"

#include <algorithm>
#include <cstdio>
#include <stdexcept>

#include "hand/sample_validator.hpp"
#include "physics_node/io/replay_driver.hpp"
#include "physics_node/physics/broadphase.hpp"
#include "physics_node/physics/world.hpp"

namespace vcockpit::physics_io {

GripReplay replay_grip(const physics::Scene& scene_in,
                       const std::vector<hand::GloveSample>& samples, int object, int support,
                       const GripReplayOptions& options) {
  const auto count = static_cast<int>(scene_in.objects.size());
  if (object < 0 || object >= count || support < 0 || support >= count)
    throw std::invalid_argument("replay_grip: no object " + std::to_string(object) +
                                " or support " + std::to_string(support));
  if (scene_in.hands.empty()) throw std::invalid_argument("replay_grip: the scene has no hand");
  physics::World world(scene_in);
  const physics::Scene& scene = world.scene();
  const hand::HandModel& hand = scene.hands.at(0);
  const auto& o = scene.objects[static_cast<std::size_t>(object)];
  const auto& s = scene.objects[static_cast<std::size_t>(support)];
  const double support_top_z = physics::shape_aabb(s.shape, s.X_GO).hi.z();

  GripReplay run;
  bool stop = false;
  ReplayDriver driver(world, hand);
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
    if (run.release_s < 0.0 || t_s <= run.release_s + options.settle_s) {
      const double below_m = support_top_z - physics::shape_aabb(o.shape, body.X_GO).lo.z();
      if (below_m > run.deepest_below_support_m) {
        run.deepest_below_support_m = below_m;
        run.deepest_below_support_at_s = t_s;
      }
    }
    if (options.trace && world.time_ns() % 10'000'000 == 0) {
      const Eigen::Vector3d p = body.X_GO.translation();
      const physics::HandState& hs = world.state().hands[0];
      const Eigen::Vector3d proxy = hs.X_GH.translation(), tracked = hs.to.X_GH.translation();
      std::fprintf(stderr,
                   "%.3f %s p %.4f %.4f %.4f v %.3f %.3f %.3f proxy %.4f %.4f %.4f tracked %.4f "
                   "%.4f %.4f\n",
                   t_s, body.held() ? "held" : "free", p.x(), p.y(), p.z(), body.v_G.x(),
                   body.v_G.y(), body.v_G.z(), proxy.x(), proxy.y(), proxy.z(), tracked.x(),
                   tracked.y(), tracked.z());
      for (const Eigen::Vector3d& n : hs.blocking_out_G)
        std::fprintf(stderr, "    blocking %.2f %.2f %.2f\n", n.x(), n.y(), n.z());
      // the hand's contacts on the object and the stable-grasp test on them
      std::vector<physics::HandContact> on_object;
      std::string links;
      const int first_hand_body = static_cast<int>(scene.objects.size());
      for (const auto& a : world.contacts()) {
        if (a.contact.body_a != object || a.contact.body_b < first_hand_body) continue;
        physics::HandContact hc;
        hc.link =
            static_cast<physics::Link>((a.contact.body_b - first_hand_body) % hand::kLinkCount);
        hc.p_G = a.contact.p_G;
        hc.n_G = -a.contact.n_G;
        hc.F_G = -a.F_on_b_G;
        on_object.push_back(hc);
        char text[128];
        std::snprintf(text, sizeof text, " %s %.2fmm %.2fN",
                      std::string(hand::link_name(hc.link)).c_str(), a.contact.depth_m * 1e3,
                      a.normal_N);
        links += text;
      }
      const physics::GraspCheck check =
          physics::evaluate_grasp(on_object.data(), on_object.size(), body.X_GO.translation(),
                                  o.mass_kg, scene.gravity_mps2, scene.grasp, body.held());
      std::fprintf(stderr, "    grasp test: %s, F %.2f N, M %.3f N m, opposition %.0f deg |%s\n",
                   physics::grasp_reason_name(check.verdict), check.residual_force_N,
                   check.residual_torque_Nm, check.best_opposition_deg, links.c_str());
    }
    if (!body.held()) {
      const double horizontal_mps = body.v_G.head<2>().norm();
      if (horizontal_mps > run.fastest_free_horizontal_mps) {
        run.fastest_free_horizontal_mps = horizontal_mps;
        run.fastest_free_at_s = t_s;
      }
    }
    if (world.hand_penetration().max_m > run.deepest_link_in_object_m) {
      run.deepest_link_in_object_m = world.hand_penetration().max_m;
      run.deepest_link_in_object_at_s = t_s;
    }
    run.deepest_link_in_static_m =
        std::max(run.deepest_link_in_static_m, world.hand_penetration().static_max_m);
  };
  const auto asked_to_stop = [&] {
    if (!stop && options.stop)
      stop = options.stop(run, static_cast<double>(world.time_ns()) * 1e-9);
    run.stopped = stop;
    return stop;
  };
  // the checks the offline runner and a live node make (joint values past the hand's range
  // clamped)
  hand::SampleValidator validator(hand);
  for (hand::GloveSample sample : samples) {
    if (!validator.accept(sample)) continue;
    driver.feed(sample, step);
    run.t0_ns = driver.source_time_at_world_zero();
    run.last_sample_s = static_cast<double>(driver.newest_world_ns()) * 1e-9;
    if (asked_to_stop()) break;
  }
  // and a moment more, for what was let go to come to rest
  for (int i = 0; i < options.tail_steps && !stop; ++i) {
    step();
    if (i % 10 == 9 && asked_to_stop()) break;
  }
  run.end_s = static_cast<double>(world.time_ns()) * 1e-9;
  return run;
}

}  // namespace vcockpit::physics_io
