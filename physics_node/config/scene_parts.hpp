#pragma once
// The pieces of a scene file that more than one part of it uses (scene_config.cpp defines them):
// checked scalars, shapes, poses, materials, colours and mass properties, each failing with the
// node's file:line:col and key. Internal to physics_config.

#include <Eigen/Geometry>

#include <array>
#include <string>
#include <string_view>

#include "common/yaml_config.hpp"
#include "physics_node/physics/scene.hpp"

namespace vcockpit::scene_parts {

std::string format_number(double value);
Eigen::Vector3d vector3(const std::array<double, 3>& v);
double require(const ConfigNode& node, double value, bool ok, const std::string& rule);
double positive(const ConfigNode& node, const std::string& what = "value");
double non_negative(const ConfigNode& node);

// Reads map[key] through `parse` when the key is present; otherwise `value` keeps its default.
template <typename T, typename Parse>
void read_optional(const ConfigNode& map, std::string_view key, T& value, Parse parse) {
  if (auto node = map.find(key)) value = parse(*node);
}

physics::Material parse_material(const ConfigNode& node, const physics::Material& defaults);
// How a shape is read: model files relative to base_dir; a moving shape (a dynamic object, a
// control's part) framed at its mesh's centroid.
struct ShapeContext {
  std::string base_dir;
  bool moving = false;
};
// box, sphere, capsule, cylinder or {mesh: FILE, node: NAME, scale: S, up: y|z}; a mesh's errors
// name the YAML line and the model file.
physics::Shape parse_shape(const ConfigNode& node, const ShapeContext& context = {});
// An object's colour when its YAML gives none: white for a mesh (the colours are its model's
// materials, times this), the cockpit's grey for a primitive.
std::array<float, 4> default_color(const physics::Shape& shape);
Eigen::Isometry3d parse_pose(const ConfigNode& node);
std::array<float, 4> parse_color(const ConfigNode& node);
std::string parse_name(const ConfigNode& node);
// `mass` or `density` (exactly one), and `inertia` or the shape's, into spec.
void parse_mass_properties(const ConfigNode& node, physics::ObjectSpec& spec);

// `controls:` (control_config.cpp): each control and its moving part, appended to the scene's
// controls and objects.
void parse_controls(const ConfigNode& list, const std::string& base_dir, physics::Scene& scene);

}  // namespace vcockpit::scene_parts
