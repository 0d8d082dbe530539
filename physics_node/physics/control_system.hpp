#pragma once
// The cockpit's controls as a system beside the bodies (Box2D keeps its joints in their own
// files the same way, the world calling them at fixed points of its step). The world owns the
// state (WorldState::controls, and each control's body in WorldState::bodies); this system moves
// it, one control at a time, with control.hpp's laws:
//   begin_step    the positions commanded since the last step (a flight model's, an
//                 instructor's), each at rest at its position's coordinate;
//   solver_joints for the contact solver: each free control's body in a contact as a body on
//                 its joint (solver_joint.hpp);
//   find_pushers  after the solve: which hand link pushes each control hardest, the hands'
//                 generalised force on it, or another object touching it;
//   integrate     the motion of each control no hand holds over the step (gravity, its
//                 mechanism and the generalised impulse the solver gave its joint), the body
//                 placed from the coordinate;
//   move_held     a held control follows its hand projected onto the joint (eq. 29 restricted);
//   after_grasp   a grasp takes the hand's pose and the coordinate as the projection's
//                 reference; a release leaves the control with the hand's velocity along it.
// Each change of a discrete position is a ControlEvent of the step, with its cause.

#include <Eigen/Geometry>

#include <cstdint>
#include <vector>

#include "physics_node/physics/collision.hpp"
#include "physics_node/physics/control.hpp"
#include "physics_node/physics/grasp.hpp"
#include "physics_node/physics/grasp_tracker.hpp"
#include "physics_node/physics/scene.hpp"
#include "physics_node/physics/solver_joint.hpp"
#include "physics_node/physics/world_state.hpp"

namespace vcockpit::physics {

class ControlSystem {
 public:
  // `state` is the world's; it is not touched until start().
  ControlSystem(const Scene& scene, WorldState& state);
  // The controls at the scene's start, in `state` (its bodies already there): each at
  // q_initial, in the position nearest it, its body placed; no event.
  void start();
  ControlSystem(const ControlSystem&) = delete;
  ControlSystem& operator=(const ControlSystem&) = delete;

  bool empty() const { return count_ == 0; }
  // The joint of object `object`'s control, for the grasp test; null for an object that is not
  // a control's body.
  const GraspJoint* grasp_joint_of(int object) const;

  // A command to go to `position` at the next step; refused (false) for an unknown control or
  // position, and while a hand holds the control.
  bool command(int control, int position);

  // The step's start: the last step's events cleared, the commands since then applied.
  void begin_step();
  void find_pushers(const std::vector<AppliedContact>& applied, const CollisionWorld& collision);
  // The controls no hand holds whose bodies are in `contacts`, as the soft solver's joints for a
  // step of dt_s (`joints` cleared first).
  void solver_joints(const std::vector<ContactPoint>& contacts, double dt_s,
                     std::vector<SolverJoint>& joints);
  // After the solver: each free control moved over dt_s by gravity, its mechanism and the
  // generalised impulse its joint got (none for a control not in `joints`).
  void integrate(const std::vector<SolverJoint>& joints, double dt_s);
  // Control `control`, held by hand index `hand` whose wrist is at X_GH and holds the control's
  // body at p_held_H (the translation of its X_HO).
  void move_held(int control, int hand, const Eigen::Isometry3d& X_GH,
                 const Eigen::Vector3d& p_held_H, double dt_s);
  // The coordinate a hand at X_GH, holding the control's body at p_held_H, moves it to: what it
  // asks for (eq. 29 restricted to the joint), as far as the travel and the gates it has lifted
  // the lever over let it go from where it is.
  double held_q(int control, const Eigen::Isometry3d& X_GH, const Eigen::Vector3d& p_held_H) const;
  // The grasp stage's events of the step: the controls grasped and released.
  void after_grasp(const std::vector<GraspEvent>& grasp_events);

  // After WorldState was put back wholesale (World::restore): nothing pending, none known at
  // rest, no events.
  void forget_step();
  // An instructor's reset to `saved` (World::reset_objects): the controls as it has them, with
  // no push; a control whose position changes reports it as commanded at t_ns.
  void reset_to(const std::vector<ControlState>& saved, int64_t t_ns);

  // The position changes of the last step (or of the last reset_to).
  const std::vector<ControlEvent>& events() const { return events_; }

 private:
  void place(int control);
  // the free motion of control `control` under generalised force Q (contacts and gravity);
  // `untouched`: no contact force on it
  void advance(int control, double Q, bool untouched, double dt_s);
  // gravity's generalised force on control `control`'s body where it is now
  double weight_Q(int control) const;
  void note_position(int control, ControlCause cause, int hand_id, int link);

  const Scene& scene_;
  WorldState& state_;
  int count_;
  int object_count_;
  int64_t step_ns_;
  std::vector<int> hand_ids_;  // the topic id of each of the world's hands
  // per control, constant
  std::vector<double> inertia_;          // its body's inertia along the joint
  std::vector<GraspJoint> grasp_joint_;  // its joint, for the grasp test
  // per control, scratch of this step
  std::vector<int> push_link_;    // the hand link pushing it hardest in this step
  std::vector<int> push_hand_;    // ... and its hand
  std::vector<double> push_N_;    // ... and its normal force
  std::vector<double> push_Q_;    // ... and the hands' generalised force on it
  std::vector<uint8_t> touched_;  // ... touched by another object
  std::vector<int> commanded_;    // the position commanded since the last step, -1
  std::vector<uint8_t> at_rest_;  // its last free step changed nothing
  std::vector<double> contact_Q_;  // soft solver: the contacts' generalised force of the step
  std::vector<ControlEvent> events_;
};

}  // namespace vcockpit::physics
