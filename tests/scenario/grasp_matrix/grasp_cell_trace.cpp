// grasp_cell_trace: replays one cell of the grasp matrix and prints what happens to its object,
// a line per interval: the object's height, speed and spin, whether it is held, the stable-grasp
// test on the hand's contacts (eqs. 30-31 and the gesture) and each hand link touching it (depth
// in mm, normal force in N, the normal). For finding out why a cell fails.
//
//   grasp_cell_trace SOURCE_DIR CELL [FROM_S TO_S [EVERY_MS]]
//   e.g. build/tests/grasp_cell_trace . cup_medium_clean 2.0 3.5 5

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <vector>

#include "physics_node/physics/grasp.hpp"
#include "tests/scenario/grasp_matrix/grasp_cells.hpp"
#include "tests/scenario/grasp_matrix/grasp_scenario.hpp"
#include "tests/scenario/grasp_matrix/hand_static_clearance.hpp"

namespace vcockpit::test {
namespace {

const char* short_link(physics::Link link) {
  static const char* kNames[] = {"palm", "T1", "T2", "T3", "I1", "I2", "I3", "M1",
                                 "M2",   "M3", "R1", "R2", "R3", "L1", "L2", "L3"};
  return kNames[static_cast<int>(link)];
}

int run(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: %s SOURCE_DIR CELL [FROM_S TO_S [EVERY_MS]]\n", argv[0]);
    return 2;
  }
  const std::string source_dir = argv[1];
  const Cell cell = find_cell(argv[2]);
  const double from_s = argc > 3 ? std::atof(argv[3]) : 0.0;
  const double to_s = argc > 4 ? std::atof(argv[4]) : 1e9;
  const int64_t every_ns = (argc > 5 ? std::atoll(argv[5]) : 10) * 1'000'000;
  const GraspCase& gc = grasp_case(cell.object);
  int object = -1;
  std::vector<physics::HandContact> hand;
  auto observe = [&](const physics::World& world) {
    if (object < 0) object = world.scene().find_object(cell.object);
    const double t_s = static_cast<double>(world.time_ns()) * 1e-9;
    for (const auto& e : world.step_events()) {
      if (e.object == object)
        std::printf("%7.3f EVENT %s contacts %d F %.2f M %.3f\n", t_s, e.grasp ? "GRASP" : "RELEASE",
                    e.contacts, e.residual_force_N, e.residual_torque_Nm);
    }
    if (t_s < from_s || t_s > to_s || world.time_ns() % every_ns != 0) return;
    const physics::BodyState& b = world.bodies()[object];
    hand.clear();
    std::string links;
    for (const auto& a : world.contacts()) {
      if (a.contact.body_a != object || a.contact.body_b < static_cast<int>(world.scene().objects.size()))
        continue;
      physics::HandContact hc;
      hc.link = static_cast<physics::Link>(a.contact.body_b - world.scene().objects.size());
      hc.p_G = a.contact.p_G;
      hc.n_G = -a.contact.n_G;
      hc.F_G = -a.F_on_b_G;
      hand.push_back(hc);
      char s[128];
      std::snprintf(s, sizeof s, " %s %.2fmm %.2fN (%.2f %.2f %.2f)", short_link(hc.link),
                    a.contact.depth_m * 1e3, a.normal_N, hc.n_G.x(), hc.n_G.y(), hc.n_G.z());
      links += s;
    }
    const auto& o = world.scene().objects[object];
    const physics::GraspCheck check = physics::evaluate_grasp(
        hand.data(), hand.size(), b.X_GO.translation(), o.mass_kg, world.scene().gravity_mps2,
        world.scene().grasp, b.held_by != physics::kNotHeld);
    const Eigen::Vector3d p = b.X_GO.translation();
    const double palm_lag_m =
        (world.tracked_X_GL()[0].translation() - world.X_GL()[0].translation()).norm();
    std::printf("%7.3f p (%.3f %.3f %.3f) |v| %.3f |w| %.2f %s off %.1fmm palm %.1fmm | "
                "%s F %.2f M %.3f opp %.0f |%s\n",
                t_s, p.x(), p.y(), p.z(), b.v_G.norm(), b.w_G.norm(),
                b.held_by != physics::kNotHeld ? "HELD" : "free", world.tracked_offset_m() * 1e3,
                palm_lag_m * 1e3,
                physics::grasp_reason_name(check.verdict), check.residual_force_N,
                check.residual_torque_Nm, check.best_opposition_deg, links.c_str());
    if (std::getenv("TRACE_Q") != nullptr) {  // the thumb's joints (deg): proxy / tracked
      std::printf("        thumb q deg:");
      for (int j = 0; j < 4; ++j)
        std::printf(" %.2f/%.2f", world.state().hands[0].q_rad[j] * 180.0 / M_PI,
                    world.state().hands[0].to.q_rad[j] * 180.0 / M_PI);
      std::printf("\n");
    }
    if (std::getenv("TRACE_TIPS") != nullptr) {
      // each finger's distal link tip in the object's frame: proxy, then tracked
      const auto& model = world.scene().hands[0];
      std::string tips;
      for (int l : {3, 6, 9, 12}) {
        const double len = model.capsules[l].length_m;
        const Eigen::Vector3d a =
            b.X_GO.inverse() * (world.X_GL()[l] * Eigen::Vector3d(len, 0, 0));
        const Eigen::Vector3d c =
            b.X_GO.inverse() * (world.tracked_X_GL()[l] * Eigen::Vector3d(len, 0, 0));
        char s2[160];
        std::snprintf(s2, sizeof s2, " %s p(%.1f %.1f %.1f) t(%.1f %.1f %.1f)",
                      short_link(static_cast<physics::Link>(l)), a.x() * 1e3, a.y() * 1e3,
                      a.z() * 1e3, c.x() * 1e3, c.y() * 1e3, c.z() * 1e3);
        tips += s2;
      }
      // the lowest link of the proxy: what reaches a surface under the hand first
      double lowest_z = 1e9;
      int lowest = 0;
      for (int l = 1; l < hand::kLinkCount; ++l) {
        const double z = capsule_lowest_z(model, l, world.X_GL()[l]);
        if (z < lowest_z) {
          lowest_z = z;
          lowest = l;
        }
      }
      std::string others;
      for (const auto& a : world.contacts()) {
        if (a.contact.body_a == object && a.contact.body_b >= static_cast<int>(world.scene().objects.size()))
          continue;  // printed above
        if (a.contact.body_a != object && a.contact.body_b != object &&
            a.contact.body_b < static_cast<int>(world.scene().objects.size()))
          continue;  // neither the hand nor the object
        char s4[96];
        std::snprintf(s4, sizeof s4, " %d-%d %.2fmm", a.contact.body_a, a.contact.body_b,
                      a.contact.depth_m * 1e3);
        others += s4;
      }
      std::string planes;
      for (const auto& n : world.state().hands[0].blocking_out_G) {
        char s3[64];
        std::snprintf(s3, sizeof s3, " (%.2f %.2f %.2f)", n.x(), n.y(), n.z());
        planes += s3;
      }
      std::printf("        tips mm in O:%s | lowest %s z %.4f | %s blocking%s | others%s\n", tips.c_str(),
                  short_link(static_cast<physics::Link>(lowest)), lowest_z,
                  world.state().hands[0].pushing ? "pushing" : "", planes.c_str(), others.c_str());
    }
  };
  const ScenarioResult r = run_grasp_scenario(source_dir, gc, hand_sizes().at(cell.size),
                                              degradation_spec(cell.degradation), observe);
  std::printf("grasps %d releases %d other %d lift %.3f m err %.4f m v_before %.3f m/s static "
              "%.4f m\n%s",
              r.grasps, r.releases, r.other_events, r.max_lift_held_m, r.place_error_m,
              r.max_speed_before_grasp_mps, r.deepest_static.depth_m, r.events.c_str());
  return 0;
}

}  // namespace
}  // namespace vcockpit::test

int main(int argc, char** argv) {
  try {
    return vcockpit::test::run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "grasp_cell_trace: %s\n", e.what());
    return 1;
  }
}
