#pragma once
// The mutable state of a world (MuJoCo's mjData without its scratch): everything that carries
// from one step to the next and affects results. The Scene is the constant model beside it; the
// world's per-step scratch (contacts, forces, work arrays) is rebuilt every step and is not here.
// A world restored to a WorldState steps bit-identically to the world it was taken from.

#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <vector>

#include "physics_node/physics/body.hpp"
#include "physics_node/physics/friction_force.hpp"
#include "physics_node/physics/grasp_tracker.hpp"
#include "physics_node/physics/scene.hpp"

namespace vcockpit::physics {

// What the tracked hand looks like now: the wrist in the world and the 22 joint angles.
struct HandInput {
  Eigen::Isometry3d X_GH = Eigen::Isometry3d::Identity();
  JointAngles q_rad{};
  bool tracking = true;  // false: glove lost; the hand stays, held objects are let go
};

// One simulated hand's state.
struct HandState {
  bool active = false;  // an input has arrived for it
  HandInput from;       // the hand at the start of the coming step
  HandInput to;         // at its end: the latest input
  // the hand now (after the last step), the proxy's when the scene has one (proxy_hand.hpp):
  // the coming step's link velocities and reach start here
  Eigen::Isometry3d X_GH = Eigen::Isometry3d::Identity();
  JointAngles q_rad{};
  std::array<Eigen::Isometry3d, kLinkCount> X_GL;
  bool pushing = false;  // a proxy link or held object touched a free object in the last step
  // The static surfaces the proxy rested on at the end of the last step (the directions that take
  // it out, at most kMaxBlockingPlanes): the next step's wrist motion is projected off them, so
  // the proxy slides along a panel it touches (a god-object) instead of going in and being
  // shifted back out every step.
  std::vector<Eigen::Vector3d> blocking_out_G;
  // Where the fingers held back by heavy loose objects or levers at the end of the last step
  // pull the wrist, from the tracked one (ProxyParams::finger_pull_ratio): the next step's wrist
  // heads for the tracked pose moved by this. Kept (turning with the wrist) while the hand holds
  // an object.
  Eigen::Vector3d finger_pull_G = Eigen::Vector3d::Zero();
  std::vector<GraspHold> grasp;  // per object: this hand's grasp of it
};

struct WorldState {
  int64_t time_ns = 0;
  uint64_t steps = 0;

  std::vector<BodyState> bodies;  // per object, the scene's order
  std::vector<ControlState> controls;  // per control (Scene::controls)
  std::vector<HandState> hands;   // per hand (Scene::hands)

  std::vector<StickAnchor> anchors;  // friction stick anchors of the last step, by pair
};

}  // namespace vcockpit::physics
