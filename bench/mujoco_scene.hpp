#pragma once
// The same scene in MuJoCo 2.2.2, so benchmarks can step both engines side by side.
//
// Mapping (see mjcf_from_scene):
//   - static objects: geoms of the world body at their spec pose;
//   - each dynamic object: a body with a free joint whose frame IS our centroid frame O (inertial
//     and geom at the body origin), so qpos/qvel map to BodyState directly;
//   - the hand's 16 links: mocap bodies whose frame is the link frame L (palm box at the origin,
//     phalanx capsule centred at x = length / 2 with its axis along x_L), parked 100 m up until
//     set_hand;
//   - pairs that act as in ours, by contype/conaffinity bits: static-dynamic, dynamic-dynamic and
//     hand-dynamic; never static-static, hand-static or hand-hand;
//   - friction = the material's mu_s. MuJoCo combines a pair by the max, ours by the geometric
//     mean; contact stiffness and damping are MuJoCo's defaults (solref 0.02 1), not ours.
//   - timestep = scene.step_s, gravity = scene.gravity_mps2, semi-implicit Euler, the default
//     Newton solver and pyramidal cone.

#include <Eigen/Geometry>

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "physics_node/physics/body.hpp"
#include "hand/hand_joints.hpp"
#include "physics_node/physics/scene.hpp"

// MuJoCo's own types (mujoco.h typedefs them as mjModel and mjData).
struct mjModel_;
struct mjData_;

namespace vcockpit::bench {

// The MJCF text of a scene (see above).
std::string mjcf_from_scene(const physics::Scene& scene);

class MujocoWorld {
 public:
  // Compiles mjcf_from_scene(scene). Throws std::runtime_error with MuJoCo's error text.
  explicit MujocoWorld(const physics::Scene& scene);
  ~MujocoWorld();
  MujocoWorld(const MujocoWorld&) = delete;
  MujocoWorld& operator=(const MujocoWorld&) = delete;

  // Hand link frames in world (World::X_GL()): the mocap bodies are put there. Throws
  // std::logic_error for a scene without a hand.
  void set_hand(const std::array<Eigen::Isometry3d, hand::kLinkCount>& X_GL);
  // Our objects' state (one BodyState per scene object; static entries are ignored) into the
  // free joints' qpos and qvel. An object our hand holds (held_by) is welded to the palm where
  // it is now, as ours is attached (eqs. 28-29): MuJoCo's own way to hold a body. Call after
  // set_hand, so the weld takes the hand's pose.
  void set_object_states(const std::vector<physics::BodyState>& bodies);
  // mj_step. Throws std::runtime_error when MuJoCo reports that contacts or constraints did not
  // fit its buffers or that the state went bad (it then resets the state).
  void step();
  // mj_forward: positions, contacts and forces for the current state, without stepping.
  void forward();

  int contact_count() const;  // contacts found by the last step (or forward)
  // Centroid frame of an object: the free joint's pose for a dynamic one, the spec pose for a
  // static one.
  Eigen::Isometry3d object_pose(int object) const;
  double timestep_s() const;

  // For tests and diagnostics.
  const mjModel_* model() const { return m_; }
  const mjData_* data() const { return d_; }
  int object_body(int object) const;  // MuJoCo body id; -1 for a static object
  int object_geom(int object) const;  // MuJoCo geom id
  int hand_geom(int link) const;      // MuJoCo geom id of a hand link; -1 without a hand

 private:
  void weld_to_palm(int object, const physics::BodyState& body);

  mjModel_* m_ = nullptr;
  mjData_* d_ = nullptr;
  std::vector<Eigen::Isometry3d> X_GO_spec_;  // static objects' poses
  std::vector<int> object_body_;
  std::vector<int> object_geom_;
  std::vector<int> object_qpos_;  // qpos address of the free joint; -1 static
  std::vector<int> object_qvel_;  // qvel address of the free joint; -1 static
  std::vector<std::optional<physics::ControlSpec>> object_control_;  // a control's moving part
  std::array<int, hand::kLinkCount> hand_mocap_{};
  std::array<int, hand::kLinkCount> hand_geom_{};
  std::vector<int> object_weld_;  // equality id of the object's weld to the palm; -1 none
  bool has_hand_ = false;
};

}  // namespace vcockpit::bench
