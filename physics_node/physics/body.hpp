#pragma once
// The mutable state of one object (MuJoCo's mjData, in spirit) and the per-body data the contact
// model needs: inverse mass and inertia (0 = immovable: static, held, or a hand link), material,
// and how fast a point fixed on the body moves.

#include <Eigen/Geometry>

#include "physics_node/physics/scene.hpp"

namespace vcockpit::physics {

constexpr int kNotHeld = -1;

struct BodyState {
  Eigen::Isometry3d X_GO = Eigen::Isometry3d::Identity();  // centroid frame in world
  Eigen::Vector3d v_G = Eigen::Vector3d::Zero();            // centroid velocity (m/s)
  Eigen::Vector3d w_G = Eigen::Vector3d::Zero();            // angular velocity (rad/s)
  // The hands holding it: bit h for the world's hand h (World::hand_count()); two bits while
  // it is held with both hands. held_by is the id (0 right, 1 left) of the first of them, for
  // the outputs, or kNotHeld; the world keeps the two in step.
  uint8_t holders = 0;
  int held_by = kNotHeld;
  bool held() const { return holders != 0; }
  // Sleeping (sleep.hpp): how long it has been still, whether it sleeps, and its island (the
  // lowest object index of the bodies that fell asleep with it; they wake together).
  double still_s = 0.0;
  bool asleep = false;
  int island = -1;
  // Awake and judged afresh: still for no time, in no island.
  void wake() {
    asleep = false;
    still_s = 0.0;
    island = -1;
  }
};

// A body as the contact model sees it during one step.
struct ContactBody {
  Eigen::Isometry3d X_GB = Eigen::Isometry3d::Identity();  // pose now
  Eigen::Vector3d v_G = Eigen::Vector3d::Zero();           // velocity of the frame origin
  Eigen::Vector3d w_G = Eigen::Vector3d::Zero();
  double inv_mass = 0.0;        // 0: does not respond to contact forces
  double mass_for_damping = 0.0;  // effective mass seen by a contact (kg); 0 when immovable
  Eigen::Matrix3d inv_I_O = Eigen::Matrix3d::Zero();  // inverse inertia, body frame; 0 when immovable
  const Material* material = nullptr;
  bool dynamic = false;          // forces on it are integrated

  Eigen::Vector3d point_velocity(const Eigen::Vector3d& p_G) const {
    return v_G + w_G.cross(p_G - X_GB.translation());
  }
};

}  // namespace vcockpit::physics
