#include "bench/bench_scenes.hpp"

#include <array>
#include <cmath>
#include <random>
#include <stdexcept>

#include "common/pose.hpp"
#include "hand/glove_log.hpp"
#include "physics_node/config/scene_config.hpp"
#include "physics_node/io/replay_driver.hpp"

namespace vcockpit::bench {
namespace {

constexpr const char* kGraspLog = "config/glove_logs/reach_grasp_lift_release.csv";

physics::ObjectSpec loose_object(int index, std::mt19937& rng, const Eigen::Vector2d& xy) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const auto between = [&](double lo, double hi) { return lo + (hi - lo) * unit(rng); };
  physics::ObjectSpec o;
  o.name = "loose_" + std::to_string(index);
  o.dynamic = true;
  double rest_z_m = 0.0;  // centroid height resting on the floor (top at z = 0)
  Eigen::Vector3d rpy_deg = Eigen::Vector3d::Zero();
  switch (index % 4) {
    case 0: {
      const Eigen::Vector3d size(between(0.035, 0.055), between(0.035, 0.055),
                                 between(0.03, 0.05));
      o.shape = physics::Shape::box(size);
      rest_z_m = 0.5 * size.z();
      break;
    }
    case 1:
      o.shape = physics::Shape::sphere(between(0.018, 0.027));
      rest_z_m = o.shape.radius_m;
      break;
    case 2:  // lying on its side, axis along x
      o.shape = physics::Shape::capsule(between(0.012, 0.018), between(0.02, 0.035));
      rest_z_m = o.shape.radius_m;
      rpy_deg.y() = 90.0;
      break;
    default:  // standing
      o.shape = physics::Shape::cylinder(between(0.018, 0.027), between(0.035, 0.06));
      rest_z_m = 0.5 * o.shape.length_m;
      break;
  }
  physics::mass_properties_from_density(o.shape, between(400.0, 900.0), o.mass_kg, o.I_O);
  rpy_deg.z() += between(-30.0, 30.0);
  o.X_GO = pose_from_position_rpy_deg({xy.x(), xy.y(), rest_z_m},
                                      {rpy_deg.x(), rpy_deg.y(), rpy_deg.z()});
  o.material = physics::Material{1.0e5, 0.7, 0.6, 0.4};
  o.color_rgba = {0.3f + 0.5f * static_cast<float>(unit(rng)), 0.4f, 0.6f, 1.0f};
  return o;
}

}  // namespace

std::string source_path(const std::string& relative) {
  return std::string(VCOCKPIT_SOURCE_DIR) + "/" + relative;
}

physics::Scene cockpit_scene() { return load_scene(source_path("config/cockpit.yaml")); }

physics::Scene crowded_cockpit_scene(int loose_objects, uint32_t seed) {
  physics::Scene scene = cockpit_scene();
  // a cargo floor behind the cockpit: the cockpit floor (x -1..2) is extended back to x = -2.2,
  // and the objects stand in an 8 cm grid from x = -0.30 backwards (behind the back wall, whose
  // back face is at x = -0.25; an object reaches 3.9 cm from its centre in any yaw), y
  // -0.92..0.92, apart from each other
  const int floor = scene.find_object("floor");
  if (floor < 0) throw std::runtime_error("crowded_cockpit_scene: the cockpit has no floor");
  physics::ObjectSpec& f = scene.objects[static_cast<std::size_t>(floor)];
  f.shape.box_size_m.x() = 4.2;
  f.X_GO.translation().x() = -0.1;
  constexpr double kFirstRow_m = -0.30;
  constexpr double kCell_m = 0.08;
  constexpr int kColumns = 23;  // along y
  const int rows = (loose_objects + kColumns - 1) / kColumns;
  if (rows > 23) throw std::invalid_argument("crowded_cockpit_scene: at most 529 objects");
  std::mt19937 rng(seed);
  for (int i = 0; i < loose_objects; ++i) {
    const int row = i / kColumns, column = i % kColumns;
    const Eigen::Vector2d xy(kFirstRow_m - row * kCell_m, -0.92 + (column + 0.5) * kCell_m);
    scene.objects.push_back(loose_object(i, rng, xy));
  }
  return scene;
}

physics::Scene pile_scene(int objects, uint32_t seed) {
  physics::Scene scene;
  const physics::Material hard{1.0e5, 0.7, 0.6, 0.4};
  const auto static_box = [&](const char* name, const Eigen::Vector3d& size_m,
                              const std::array<double, 3>& p_m) {
    physics::ObjectSpec o;
    o.name = name;
    o.shape = physics::Shape::box(size_m);
    o.X_GO = pose_from_position_rpy_deg(p_m, {0.0, 0.0, 0.0});
    o.material = hard;
    scene.objects.push_back(o);
  };
  static_box("floor", {2.0, 2.0, 0.2}, {0.0, 0.0, -0.1});
  // a bin 45 x 40 cm inside, 60 cm high: a ball knocked off the heap stays in it
  static_box("wall_x_lo", {0.05, 0.5, 0.6}, {-0.25, 0.0, 0.3});
  static_box("wall_x_hi", {0.05, 0.5, 0.6}, {0.25, 0.0, 0.3});
  static_box("wall_y_lo", {0.45, 0.05, 0.6}, {0.0, -0.225, 0.3});
  static_box("wall_y_hi", {0.45, 0.05, 0.6}, {0.0, 0.225, 0.3});
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.005, 0.005);
  for (int i = 0; i < objects; ++i) {
    const int layer = i / 20;
    physics::ObjectSpec o;
    o.name = "pile_" + std::to_string(i);
    o.dynamic = true;
    o.shape = (i + layer) % 2 == 0 ? physics::Shape::box({0.04, 0.05, 0.03})
                                   : physics::Shape::sphere(0.02);
    o.mass_kg = 0.05;
    o.I_O = o.shape.unit_density_inertia() * (o.mass_kg / o.shape.volume_m3());
    const double half = 0.035 * (layer % 2);
    const double x = 0.07 * (i % 5 - 2) + half - 0.0175 + jitter(rng);
    const double y = 0.07 * ((i / 5) % 4 - 1.5) + half - 0.0175 + jitter(rng);
    o.X_GO = pose_from_position_rpy_deg({x, y, 0.03 + 0.06 * layer},
                                        {10.0 * i, 7.0 * i, 13.0 * i});
    o.material = hard;
    scene.objects.push_back(o);
  }
  return scene;
}

physics::HandInput step_to_hold(physics::World& world) {
  const hand::HandModel& hand = world.scene().hands[0];
  const auto samples = hand::read_glove_log(source_path(kGraspLog), hand).samples;
  const int64_t hold_ns = std::llround(kHoldTime_s * 1e9);
  physics_io::ReplayDriver driver(world, hand);
  for (const auto& sample : samples) {
    if (driver.world_time_of(sample) > hold_ns) {
      driver.push(sample);  // the interval that holds the hold time
      break;
    }
    driver.feed(sample, [&] { world.step(); });
  }
  driver.step_until(hold_ns, [&] { world.step(); });
  const physics::HandInput input = world.state().hands[0].to;  // the hand the last step went to
  const int cup = world.scene().find_object("cup");
  if (cup < 0 || world.bodies()[static_cast<std::size_t>(cup)].held_by == physics::kNotHeld)
    throw std::runtime_error("step_to_hold: the cup is not held at the hold time");
  return input;
}

}  // namespace vcockpit::bench
