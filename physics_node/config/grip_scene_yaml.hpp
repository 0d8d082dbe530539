#pragma once
// grip_fit's scene file: the placed object on its pedestal and table (fit/grip_scene_layout.hpp),
// a floor, the hand, and the settings of the project's cockpit, written so load_scene reads it.
//
// - The hand is referenced, not copied: `hands: [{file: <path>, side: <the log's>}]`, the path
//   relative to the scene's folder (absolute when they share only the root), so the scene's hand
//   is the hand file the placement used, of the log's side.
// - From the cockpit file (config/cockpit.yaml by default), copied as they are: gravity, step_s,
//   hand_material, grasp, contact and proxy (each when present), and the object's material: that
//   of the cockpit object `material_of` (cup: the loose objects' glazed-ceramic material).
// - The object is dynamic with the given mass (inertia from its shape); a round object is
//   written turned about its own axis so its roll is 0 (the same body).
// - Floor, pedestal and table: static, with ../shared/real/leap_grab_scene.yaml's materials.
//
// Written atomically (AtomicFile: "<path>.partial", renamed when complete) and only after the
// text has loaded with parse_scene, so a scene under the name always loads.

#include <Eigen/Geometry>

#include <string>
#include <vector>

#include "physics_node/fit/grip_choice.hpp"
#include "physics_node/fit/grip_scene_layout.hpp"
#include "physics_node/physics/scene.hpp"

namespace vcockpit {

struct GripSceneSpec {
  std::string object_name = "object";
  physics::Shape shape;
  Eigen::Isometry3d X_GO = Eigen::Isometry3d::Identity();
  double mass_kg = 0.06;
  fit::GripSceneLayout layout;
  std::string hand_path;   // as the user gave it
  bool left_hand = false;  // the log's side
  std::string cockpit_path;
  std::string material_of = "cup";
  std::vector<std::string> comments;  // the header: what made the scene (without '#')
};

// The scene's text for a file at out_path. The cockpit file must load (load_scene); throws
// ConfigError naming its file:line:col when it does not or lacks the material_of object.
std::string grip_scene_text(const GripSceneSpec& spec, const std::string& out_path);

// The scene grip_scene_text is, as load_scene would read it from a file at out_path (nothing
// written): what grip_fit replays each candidate on (the numbers rounded as the file has them).
physics::Scene grip_scene(const GripSceneSpec& spec, const std::string& out_path);

// The spec of a candidate (fit/grip_choice.hpp): `base` (the object's name, shape, mass, the hand,
// the cockpit) with the candidate's pose and supports.
GripSceneSpec with_candidate(GripSceneSpec base, const fit::GripTrial& trial);

// Writes grip_scene_text atomically once it loads; returns the loaded scene. Throws ConfigError
// (the text does not load: a bad cockpit section) or FileError (cannot write).
physics::Scene write_grip_scene(const GripSceneSpec& spec, const std::string& out_path);

// The object's rpy_deg as the scene writes it: a sphere's 0; a cylinder's or capsule's turned
// about its own axis so its roll is 0 (the same body); a box's as it is.
Eigen::Vector3d object_rpy_deg(const physics::Shape& shape, const Eigen::Matrix3d& R_GO);

// R = Rz(yaw) Ry(pitch) Rx(roll) -> (roll, pitch, yaw) in degrees, the scene's rpy_deg; at
// pitch +-90 deg roll is 0.
Eigen::Vector3d rpy_deg_from_rotation(const Eigen::Matrix3d& R);

}  // namespace vcockpit
