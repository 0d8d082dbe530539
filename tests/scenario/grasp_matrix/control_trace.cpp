// control_trace: plays a gesture script through the physics library as the offline runner does
// and prints what happens to one control, a line per interval: its coordinate (deg or mm), speed,
// discrete position, who holds it, and each hand link touching its part (depth, normal force,
// the normal); control and grasp events as they happen. For writing and debugging control
// gestures; not a test.
//
//   control_trace SOURCE_DIR SCRIPT CONTROL [FROM_S TO_S [EVERY_MS]]
//   e.g. build/tests/control_trace . panel_switches.yaml landing_lights 6.5 7.5 5
// HAND=hand_small.yaml (a file in config/) plays it with another hand; TRACE_TIPS=1 adds the
// thumb, index and middle tips in the control's joint frame and the surfaces blocking the hand.

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "hand/config/hand_yaml.hpp"
#include "hand/sample_validator.hpp"
#include "physics_node/config/scene_config.hpp"
#include "physics_node/io/replay_driver.hpp"
#include "tests/scenario/grasp_matrix/grasp_scenario.hpp"
#include "tests/scenario/grasp_matrix/hand_static_clearance.hpp"
#include "tests/support/test_files.hpp"

namespace vcockpit::test {
namespace {

const char* short_link(int link) {
  static const char* kNames[] = {"palm", "T1", "T2", "T3", "I1", "I2", "I3", "M1",
                                 "M2",   "M3", "R1", "R2", "R3", "L1", "L2", "L3"};
  return kNames[link];
}

int run(int argc, char** argv) {
  if (argc < 4) {
    std::fprintf(stderr, "usage: %s SOURCE_DIR SCRIPT CONTROL [FROM_S TO_S [EVERY_MS]]\n", argv[0]);
    return 2;
  }
  const std::string source_dir = argv[1];
  const double from_s = argc > 4 ? std::atof(argv[4]) : 0.0;
  const double to_s = argc > 5 ? std::atof(argv[5]) : 1e9;
  const int64_t every_ns = (argc > 6 ? std::atoll(argv[6]) : 10) * 1'000'000;
  physics::Scene loaded = load_scene(source_dir + "/config/cockpit.yaml");
  if (const char* other = std::getenv("HAND")) loaded.hands = {load_hand_model(source_dir + "/config/" + other)};
  physics::World world(std::move(loaded));
  const physics::Scene& scene = world.scene();
  const int control = scene.find_control(argv[3]);
  if (control < 0) throw std::invalid_argument(std::string("no control ") + argv[3]);
  const physics::ControlSpec& c = scene.controls[static_cast<std::size_t>(control)];
  const int body = c.body;
  const int objects = static_cast<int>(scene.objects.size());
  const double unit = c.joint == physics::JointKind::kRevolute ? 180.0 / M_PI : 1e3;
  const hand::HandModel& hand = scene.hands[0];
  HandStaticClearance clearance(scene, hand);
  auto step = [&] {
    world.step();
    const double t_s = static_cast<double>(world.time_ns()) * 1e-9;
    for (const auto& e : world.control_events())
      std::printf("%7.3f CONTROL %s %s -> %s cause %d link %d\n", t_s,
                  scene.controls[static_cast<std::size_t>(e.control)].name.c_str(),
                  scene.controls[static_cast<std::size_t>(e.control)].positions[static_cast<std::size_t>(e.from)].name.c_str(),
                  scene.controls[static_cast<std::size_t>(e.control)].positions[static_cast<std::size_t>(e.to)].name.c_str(),
                  static_cast<int>(e.cause), e.link);
    for (const auto& e : world.step_events())
      std::printf("%7.3f %s %s\n", t_s, e.grasp ? "GRASP" : "RELEASE",
                  scene.objects[static_cast<std::size_t>(e.object)].name.c_str());
    if (t_s < from_s || t_s > to_s || world.time_ns() % every_ns != 0) return;
    const physics::ControlState& s = world.state().controls[static_cast<std::size_t>(control)];
    std::string links;
    for (const auto& a : world.contacts()) {
      const bool mine_a = a.contact.body_a == body, mine_b = a.contact.body_b == body;
      if (!mine_a && !mine_b) continue;
      const int other = mine_a ? a.contact.body_b : a.contact.body_a;
      char text[128];
      if (other >= objects) {
        const Eigen::Vector3d n = mine_a ? Eigen::Vector3d(-a.contact.n_G) : a.contact.n_G;
        std::snprintf(text, sizeof text, " %s %.2fmm %.2fN (%.2f %.2f %.2f)",
                      short_link(other - objects), a.contact.depth_m * 1e3, a.normal_N, n.x(),
                      n.y(), n.z());
      } else {
        std::snprintf(text, sizeof text, " %s %.2fmm %.2fN",
                      scene.objects[static_cast<std::size_t>(other)].name.c_str(),
                      a.contact.depth_m * 1e3, a.normal_N);
      }
      links += text;
    }
    // what else the hand touches, and how far the drawn hand lags the tracked one
    std::string others;
    for (const auto& a : world.contacts()) {
      if (a.contact.body_a == body || a.contact.body_b == body || a.contact.body_b < objects) continue;
      char text[96];
      std::snprintf(text, sizeof text, " %s-%s %.2fmm",
                    scene.objects[static_cast<std::size_t>(a.contact.body_a)].name.c_str(),
                    short_link(a.contact.body_b - objects), a.contact.depth_m * 1e3);
      others += text;
    }
    std::printf("%7.3f q %8.3f qd %9.3f %-9s %s off %.1fmm |%s | others%s\n", t_s, s.q * unit, s.qd * unit,
                c.positions[static_cast<std::size_t>(s.position)].name.c_str(),
                world.bodies()[static_cast<std::size_t>(body)].held_by != physics::kNotHeld ? "HELD" : "free",
                world.tracked_offset_m() * 1e3, links.c_str(), others.c_str());
    if (std::getenv("TRACE_TIPS") != nullptr) {
      // the thumb, index and middle tips (the centres of their rounded ends) in the joint frame
      // at coordinate 0, mm: drawn hand, then tracked
      std::string tips;
      for (int l : {3, 6, 9}) {
        const double len = hand.capsules[static_cast<std::size_t>(l)].length_m;
        const Eigen::Vector3d a = c.X_GJ.inverse() * (world.X_GL()[l] * Eigen::Vector3d(len, 0, 0));
        const Eigen::Vector3d b = c.X_GJ.inverse() * (world.tracked_X_GL()[l] * Eigen::Vector3d(len, 0, 0));
        char text[160];
        std::snprintf(text, sizeof text, " %s (%.1f %.1f %.1f) t(%.1f %.1f %.1f)", short_link(l),
                      a.x() * 1e3, a.y() * 1e3, a.z() * 1e3, b.x() * 1e3, b.y() * 1e3, b.z() * 1e3);
        tips += text;
      }
      std::string planes;  // the static surfaces holding the drawn hand back (outward normals)
      for (const Eigen::Vector3d& n : world.state().hands[0].blocking_out_G) {
        char text[64];
        std::snprintf(text, sizeof text, " (%.2f %.2f %.2f)", n.x(), n.y(), n.z());
        planes += text;
      }
      // the glove's hand's deepest overlap with a static object: what the drawn hand stops at
      const Penetration p = clearance.deepest(world.tracked_X_GL());
      std::printf("        tips in J mm:%s | blocking%s | tracked %s in %s %.1fmm\n", tips.c_str(),
                  planes.c_str(), p.link >= 0 ? short_link(p.link) : "-",
                  p.object >= 0 ? scene.objects[static_cast<std::size_t>(p.object)].name.c_str() : "-",
                  p.depth_m * 1e3);
    }
  };
  physics_io::ReplayDriver driver(world, hand);
  hand::SampleValidator validator(hand);
  for (hand::GloveSample sample : script_samples(source_dir + "/config/gestures/" + argv[2], hand)) {
    if (!validator.accept(sample)) continue;
    driver.feed(sample, step);
  }
  return 0;
}

}  // namespace
}  // namespace vcockpit::test

int main(int argc, char** argv) {
  try {
    return vcockpit::test::run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "control_trace: %s\n", e.what());
    return 1;
  }
}
