#include "physics_node/config/grip_scene_yaml.hpp"

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <filesystem>
#include <mutex>
#include <set>
#include <string>
#include <utility>

#include "common/atomic_file.hpp"
#include "common/pose.hpp"
#include "common/yaml_config.hpp"
#include "physics_node/config/scene_config.hpp"

namespace vcockpit {
namespace {

namespace fs = std::filesystem;

// The cockpit must load itself, so a bad section is named in its own file, not in ours. Checked
// once a process for each version of the file (its path, size and time): grip_fit builds a scene
// for each candidate placement, and a cockpit's model files take a tenth of a second to read.
void check_cockpit_loads(const std::string& path) {
  static std::mutex mutex;
  static std::set<std::pair<std::string, std::string>> checked;
  std::error_code size_error, time_error;
  const auto size = fs::file_size(path, size_error);
  const auto time = fs::last_write_time(path, time_error);
  const std::string version = size_error || time_error
                                  ? std::string()  // not known: checked every time
                                  : std::to_string(size) + "@" +
                                        std::to_string(time.time_since_epoch().count());
  std::lock_guard lock(mutex);
  if (!version.empty() && checked.count({path, version})) return;
  load_scene(path);
  if (!version.empty()) checked.insert({path, version});
}

using physics::ShapeKind;

std::string format(const char* pattern, ...) {
  char text[512];
  va_list args;
  va_start(args, pattern);
  std::vsnprintf(text, sizeof text, pattern, args);
  va_end(args);
  return text;
}

std::string vec3(const Eigen::Vector3d& v) {
  return format("[%.6f, %.6f, %.6f]", v.x(), v.y(), v.z());
}

std::string shape_yaml(const physics::Shape& s) {
  switch (s.kind) {
    case ShapeKind::kBox:
      return "{box: " + vec3(s.box_size_m) + "}";
    case ShapeKind::kSphere:
      return format("{sphere: %.6f}", s.radius_m);
    case ShapeKind::kCapsule:
      return format("{capsule: [%.6f, %.6f]}", s.radius_m, s.length_m);
    case ShapeKind::kCylinder:
      return format("{cylinder: [%.6f, %.6f]}", s.radius_m, s.length_m);
    case ShapeKind::kMesh:  // (grip_fit's objects are primitives)
      break;
  }
  return "";
}

std::string pose_yaml(const Eigen::Vector3d& p, const Eigen::Vector3d& rpy_deg) {
  return "{position: " + vec3(p) + ", rpy_deg: " + vec3(rpy_deg) + "}";
}

// `key: <the node as the cockpit file has it>` for each key the cockpit file has.
std::string copied_sections(const ConfigNode& cockpit, std::initializer_list<const char*> keys) {
  std::string out;
  for (const char* key : keys) {
    const auto node = cockpit.find(key);
    if (!node) continue;
    YAML::Emitter emitter;
    emitter << YAML::BeginMap << YAML::Key << key << YAML::Value << node->raw() << YAML::EndMap;
    out += std::string(emitter.c_str()) + "\n";
  }
  return out;
}

// The material of the cockpit's object `name`, as the cockpit file writes it.
std::string object_material(const ConfigNode& cockpit, const std::string& name) {
  const ConfigNode objects = cockpit["objects"];
  for (const ConfigNode& object : objects.elements()) {
    if (object.get_string("name", "") != name) continue;
    const ConfigNode material = object["material"];
    YAML::Emitter emitter;
    emitter << YAML::Flow << material.raw();
    return emitter.c_str();
  }
  objects.fail("no object named '" + name + "' to take the material of");
}

// A YAML single-quoted scalar: any path reads back as written.
std::string quoted(const std::string& text) {
  std::string out = "'";
  for (char c : text)
    out += c == '\'' ? std::string("''") : std::string(1, c);
  return out + "'";
}

// The hand file as the scene names it: relative to the scene's folder, unless the two share no
// folder but the root (then a relative path would only climb to it: the absolute one).
std::string hand_reference(const std::string& hand_path, const std::string& out_path) {
  const fs::path hand = fs::weakly_canonical(fs::absolute(hand_path));
  const fs::path dir = fs::weakly_canonical(fs::absolute(out_path)).parent_path();
  const auto shared = std::mismatch(hand.begin(), hand.end(), dir.begin(), dir.end());
  const auto common = std::distance(hand.begin(), shared.first);
  const fs::path relative = hand.lexically_relative(dir);
  return quoted(common <= 1 || relative.empty() ? hand.string() : relative.string());
}

std::string static_box(const char* name, const char* comment, const fit::SupportBox& box,
                       const char* material, const char* color) {
  return format("  - name: %s    # %s\n    kind: static\n", name, comment) +
         "    shape: {box: " + vec3(box.size_m) + "}\n" +
         "    pose: " + pose_yaml(box.p_G, Eigen::Vector3d(0.0, 0.0, rad_to_deg(box.yaw_rad))) +
         "\n" + format("    material: %s\n", material) +
         (color ? format("    color: %s\n", color) : "");
}

}  // namespace

Eigen::Vector3d rpy_deg_from_rotation(const Eigen::Matrix3d& R) {
  const double s = -R(2, 0);  // sin(pitch)
  if (std::abs(s) > 1.0 - 1e-12) {
    // gimbal lock: only yaw - roll (or yaw + roll) is defined; roll 0
    return {0.0, s > 0.0 ? 90.0 : -90.0, rad_to_deg(std::atan2(-R(0, 1), R(1, 1)))};
  }
  return {rad_to_deg(std::atan2(R(2, 1), R(2, 2))), rad_to_deg(std::asin(s)),
          rad_to_deg(std::atan2(R(1, 0), R(0, 0)))};
}

Eigen::Vector3d object_rpy_deg(const physics::Shape& shape, const Eigen::Matrix3d& R_GO) {
  if (shape.kind == ShapeKind::kSphere) return Eigen::Vector3d::Zero();
  if (shape.kind == ShapeKind::kBox) return rpy_deg_from_rotation(R_GO);
  const Eigen::Vector3d a = R_GO.col(2);  // Rz(yaw) Ry(pitch) z = a
  return {0.0, rad_to_deg(std::acos(std::clamp(a.z(), -1.0, 1.0))),
          rad_to_deg(std::atan2(a.y(), a.x()))};
}

std::string grip_scene_text(const GripSceneSpec& spec, const std::string& out_path) {
  check_cockpit_loads(spec.cockpit_path);
  const ConfigNode cockpit = ConfigNode::load_file(spec.cockpit_path);
  constexpr const char* kFurniture = "{stiffness: 5.0e4, damping_ratio: 0.9, mu_s: 0.6, mu_d: 0.5}";
  std::string text;
  for (const std::string& line : spec.comments)
    text += "# " + line + "\n";
  text += "\n" + copied_sections(cockpit, {"gravity", "step_s"}) + "\n";
  text +=
      format("hands: [{file: %s, side: %s}]\n", hand_reference(spec.hand_path, out_path).c_str(),
             spec.left_hand ? "left" : "right");
  text += copied_sections(cockpit, {"hand_material"}) + "\nobjects:\n";

  const Eigen::Vector3d p_GO = spec.X_GO.translation();
  fit::SupportBox floor;
  floor.size_m = Eigen::Vector3d(20.0, 20.0, 0.1);
  floor.p_G = Eigen::Vector3d(p_GO.x(), p_GO.y(), -0.05);
  text +=
      static_box("floor", "top at z = 0, far below the hand, wide enough to catch anything", floor,
                 "{stiffness: 5.0e4, damping_ratio: 0.9, mu_s: 0.7, mu_d: 0.6}", nullptr);
  text += "\n" + static_box("pedestal", "its top touches the object's lowest point",
                            spec.layout.pedestal, kFurniture, "[0.4, 0.4, 0.42]");
  if (spec.layout.table) {
    text += "\n" + static_box("table", "the pedestal stands on it; it catches a dropped object",
                              *spec.layout.table, kFurniture, "[0.5, 0.45, 0.4]");
  }
  text += "\n  - name: " + spec.object_name + "\n    kind: dynamic\n";
  text += "    shape: " + shape_yaml(spec.shape) + "\n";
  text += format("    mass: %.6f\n", spec.mass_kg);
  text += "    pose: " + pose_yaml(p_GO, object_rpy_deg(spec.shape, spec.X_GO.linear())) + "\n";
  text += "    material: " + object_material(cockpit, spec.material_of) + "   # as the cockpit's " +
          spec.material_of + "\n";
  text += "    color: [0.2, 0.5, 0.9]\n\n";
  text += "# Stable grasp, contact and proxy settings: copied from " + spec.cockpit_path + ".\n";
  text += copied_sections(cockpit, {"grasp", "contact", "proxy", "sleep"});
  return text;
}

namespace {

// The scene the text is, as load_scene reads it from out_path.
physics::Scene parse_at(const std::string& text, const std::string& out_path) {
  const std::string dir = fs::path(out_path).parent_path().string();
  return parse_scene(ConfigNode::load_string(text, out_path), dir);
}

}  // namespace

GripSceneSpec with_candidate(GripSceneSpec base, const fit::GripTrial& trial) {
  base.X_GO = trial.placement.X_GO;
  if (trial.layout) base.layout = *trial.layout;
  return base;
}

physics::Scene grip_scene(const GripSceneSpec& spec, const std::string& out_path) {
  return parse_at(grip_scene_text(spec, out_path), out_path);
}

physics::Scene write_grip_scene(const GripSceneSpec& spec, const std::string& out_path) {
  const std::string text = grip_scene_text(spec, out_path);
  // what goes under the name must load: parse it first, from where it will be
  physics::Scene scene = parse_at(text, out_path);
  AtomicFile file(out_path);
  file.write(text);
  file.commit();
  return scene;
}

}  // namespace vcockpit
