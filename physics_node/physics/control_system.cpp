#include "physics_node/physics/control_system.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>

#include "common/assert.hpp"

namespace vcockpit::physics {

ControlSystem::ControlSystem(const Scene& scene, WorldState& state)
    : scene_(scene),
      state_(state),
      count_(static_cast<int>(scene.controls.size())),
      object_count_(static_cast<int>(scene.objects.size())),
      step_ns_(std::llround(scene.step_s * 1e9)) {
  for (const HandModel& hand : scene_.hands) hand_ids_.push_back(hand_id_of(hand));
  inertia_.resize(count_);
  grasp_joint_.resize(count_);
  push_link_.assign(count_, -1);
  push_hand_.assign(count_, -1);
  push_N_.assign(count_, 0.0);
  touched_.assign(count_, 0);
  commanded_.assign(count_, -1);
  at_rest_.assign(count_, 0);
  push_Q_.assign(count_, 0.0);
  contact_Q_.assign(count_, 0.0);
  for (int ci = 0; ci < count_; ++ci) {
    const ControlSpec& c = scene_.controls[ci];
    VCOCKPIT_ASSERT(c.body >= 0 && c.body < object_count_ && scene_.objects[c.body].control == ci &&
                        scene_.objects[c.body].dynamic && !c.positions.empty(),
                    "a control moves a dynamic object of its own and has positions");
    const ObjectSpec& o = scene_.objects[c.body];
    inertia_[ci] = joint_inertia(c, o.mass_kg, o.I_O);
    GraspJoint& joint = grasp_joint_[ci];
    joint.revolute = c.joint == JointKind::kRevolute;
    joint.axis_G = joint_axis_G(c);
    joint.origin_G = joint_origin_G(c);
  }
}

void ControlSystem::start() {
  VCOCKPIT_ASSERT(state_.bodies.size() == scene_.objects.size(), "the world's bodies first");
  state_.controls.assign(static_cast<std::size_t>(count_), ControlState{});
  for (int ci = 0; ci < count_; ++ci) {
    const ControlSpec& c = scene_.controls[ci];
    ControlState& s = state_.controls[ci];
    s.q = c.q_initial;
    // the position nearest the initial coordinate, then the one it is in (no event)
    double nearest = std::abs(c.positions[0].q - s.q);
    for (std::size_t p = 1; p < c.positions.size(); ++p) {
      if (std::abs(c.positions[p].q - s.q) < nearest) {
        nearest = std::abs(c.positions[p].q - s.q);
        s.position = static_cast<int>(p);
      }
    }
    if (c.latching) s.position = 0;
    update_position(c, s);
    place(ci);
  }
}

const GraspJoint* ControlSystem::grasp_joint_of(int object) const {
  const int ci = scene_.objects[static_cast<std::size_t>(object)].control;
  return ci >= 0 ? &grasp_joint_[static_cast<std::size_t>(ci)] : nullptr;
}

bool ControlSystem::command(int control, int position) {
  if (control < 0 || control >= count_) return false;
  const ControlSpec& c = scene_.controls[control];
  if (position < 0 || position >= static_cast<int>(c.positions.size())) return false;
  if (state_.bodies[c.body].held()) return false;
  commanded_[control] = position;
  return true;
}

void ControlSystem::begin_step() {
  events_.clear();
  for (int ci = 0; ci < count_; ++ci) {
    const int position = commanded_[ci];
    if (position < 0) continue;
    commanded_[ci] = -1;
    const ControlSpec& c = scene_.controls[ci];
    ControlState& s = state_.controls[ci];
    if (state_.bodies[c.body].held()) continue;  // a hand took it meanwhile
    if (c.latching) {
      s.latched = position == 1;
      s.q = spring_rest(c, s);
    } else {
      s.q = c.positions[static_cast<std::size_t>(position)].q;
    }
    s.qd = 0.0;
    s.push_hand = -1;
    s.push_link = -1;
    s.push_direction = 0;
    place(ci);
    at_rest_[ci] = 0;
    note_position(ci, ControlCause::kCommanded, -1, -1);
  }
}

// who pushes each control in this step: the hand link with the largest normal force on its
// body, or another object
void ControlSystem::find_pushers(const std::vector<AppliedContact>& applied,
                                 const CollisionWorld& collision) {
  std::fill(push_link_.begin(), push_link_.end(), -1);
  std::fill(push_hand_.begin(), push_hand_.end(), -1);
  std::fill(push_N_.begin(), push_N_.end(), 0.0);
  std::fill(touched_.begin(), touched_.end(), 0);
  std::fill(push_Q_.begin(), push_Q_.end(), 0.0);
  for (const AppliedContact& a : applied) {
    const int body_a = a.contact.body_a;
    const int body_b = a.contact.body_b;
    for (const auto& [body, other] : {std::pair{body_a, body_b}, std::pair{body_b, body_a}}) {
      if (body >= object_count_) continue;
      const int ci = scene_.objects[body].control;
      if (ci < 0) continue;
      if (collision.is_hand_body(other)) {
        if (a.normal_N > push_N_[ci]) {
          push_N_[ci] = a.normal_N;
          push_link_[ci] = static_cast<int>(collision.link_of_body(other));
          push_hand_[ci] = collision.hand_of_body(other);
        }
        // the hand's generalised force on the control: its contact force at the contact point
        const Eigen::Vector3d F_G = body == body_b ? a.F_on_b_G : Eigen::Vector3d(-a.F_on_b_G);
        const ControlSpec& c = scene_.controls[ci];
        push_Q_[ci] += c.joint == JointKind::kPrismatic
                           ? joint_axis_G(c).dot(F_G)
                           : joint_axis_G(c).dot((a.contact.p_G - joint_origin_G(c)).cross(F_G));
      } else {
        touched_[ci] = 1;
      }
    }
  }
}

void ControlSystem::solver_joints(const std::vector<ContactPoint>& contacts, double dt_s,
                                  std::vector<SolverJoint>& joints) {
  joints.clear();
  for (const ContactPoint& contact : contacts) {
    for (const int object : {contact.body_a, contact.body_b}) {
      if (object >= object_count_) continue;
      const int ci = scene_.objects[static_cast<std::size_t>(object)].control;
      if (ci < 0 || state_.bodies[object].held()) continue;
      const auto taken = [object](const SolverJoint& j) { return j.body == object; };
      if (std::any_of(joints.begin(), joints.end(), taken)) continue;  // (a few at a time)
      const ControlSpec& c = scene_.controls[ci];
      const ControlState& s = state_.controls[ci];
      const BodyState& body = state_.bodies[object];
      SolverJoint joint;
      joint.body = object;
      joint.revolute = c.joint == JointKind::kRevolute;
      joint.axis_G = joint_axis_G(c);
      joint.origin_G = joint_origin_G(c);
      joint.centroid_G = body.X_GO.translation();
      // its mean rate over the step under gravity and its mechanism alone, and how a generalised
      // impulse changes it (solver_joint.hpp). Its stops are the rate's bounds, not part of the
      // free rate: a toggle its snap holds against a stop moves only once a push beats the snap.
      const ControlStepFree free = free_control_motion(c, inertia_[ci], weight_Q(ci), dt_s, s);
      joint.qd_free = (free.q - s.q) / dt_s;
      joint.mobility = control_travel_per_force(c, inertia_[ci], s, dt_s) / (dt_s * dt_s);
      const double inf = std::numeric_limits<double>::infinity();
      joint.qd_min = (reachable_q(c, s.q, -inf, 0u) - s.q) / dt_s;
      joint.qd_max = (reachable_q(c, s.q, inf, 0u) - s.q) / dt_s;
      joints.push_back(joint);
    }
  }
}

void ControlSystem::integrate(const std::vector<SolverJoint>& joints, double dt_s) {
  std::fill(contact_Q_.begin(), contact_Q_.end(), 0.0);
  for (const SolverJoint& joint : joints)
    contact_Q_[scene_.objects[static_cast<std::size_t>(joint.body)].control] = joint.move_impulse / dt_s;
  for (int ci = 0; ci < count_; ++ci) {
    const ControlSpec& c = scene_.controls[ci];
    const BodyState& body = state_.bodies[c.body];
    if (body.held()) continue;  // moved with the hand (move_held)
    const bool untouched = contact_Q_[ci] == 0.0;
    if (untouched && at_rest_[ci] != 0) continue;
    advance(ci, contact_Q_[ci] + weight_Q(ci), untouched, dt_s);
  }
}

double ControlSystem::weight_Q(int ci) const {
  const ControlSpec& c = scene_.controls[ci];
  const Eigen::Vector3d weight_G = scene_.objects[c.body].mass_kg * scene_.gravity_mps2;
  return generalised_force(c, state_.bodies[c.body].X_GO.translation(), weight_G, Eigen::Vector3d::Zero());
}

void ControlSystem::advance(int ci, double Q, bool untouched, double dt_s) {
  const ControlSpec& c = scene_.controls[ci];
  const BodyState& body = state_.bodies[c.body];
  ControlState& s = state_.controls[ci];
  const double q_before = s.q;
  integrate_control(c, inertia_[ci], Q, dt_s, 0u, s);
  at_rest_[ci] = untouched && s.q == q_before && s.qd == 0.0 ? 1 : 0;
  if (s.q != q_before || s.qd != 0.0 || body.v_G.squaredNorm() + body.w_G.squaredNorm() != 0.0)
    place(ci);
  // pushed: the hand's force drives the motion (a button that springs back out against a
  // withdrawing fingertip is returned by its spring), or drove it and the control goes on the
  // same way (a toggle snapping over once the finger has pushed it past its centre)
  if (push_link_[ci] >= 0 && push_Q_[ci] * s.qd > 0.0) {
    s.push_hand = push_hand_[ci];
    s.push_link = push_link_[ci];
    s.push_direction = s.qd > 0.0 ? 1 : -1;
  } else if (s.push_direction * s.qd <= 0.0) {
    s.push_hand = -1;
    s.push_link = -1;
    s.push_direction = 0;
  }
  if (s.push_direction != 0) {
    note_position(ci, ControlCause::kPushed, hand_ids_[static_cast<std::size_t>(s.push_hand)],
                  s.push_link);
  } else {
    note_position(ci, touched_[ci] != 0 ? ControlCause::kObject : ControlCause::kMechanism, -1, -1);
  }
}

// eq. 29 restricted to the joint: the coordinate the hand's motion since the grasp asks for,
// as far as the travel and the gates (open only while the hand has lifted the lever) let it go
double ControlSystem::held_q(int control, const Eigen::Isometry3d& X_GH,
                             const Eigen::Vector3d& p_held_H) const {
  const ControlSpec& c = scene_.controls[control];
  const ControlState& s = state_.controls[control];
  const double lift_m = grasped_lift_m(c, s, X_GH, p_held_H);
  uint32_t gates_open = 0;
  for (std::size_t g = 0; g < c.gates.size(); ++g)
    if (lift_m >= c.gates[g].lift_m) gates_open |= 1u << g;
  return reachable_q(c, s.q, grasped_q(c, s, X_GH, p_held_H), gates_open);
}

void ControlSystem::move_held(int control, int hand, const Eigen::Isometry3d& X_GH,
                              const Eigen::Vector3d& p_held_H, double dt_s) {
  ControlState& s = state_.controls[control];
  const double q = held_q(control, X_GH, p_held_H);
  s.qd = (q - s.q) / dt_s;
  s.q = q;
  s.push_hand = -1;
  s.push_link = -1;
  s.push_direction = 0;
  place(control);
  at_rest_[control] = 0;
  note_position(control, ControlCause::kGrasped, hand_ids_[static_cast<std::size_t>(hand)], -1);
}

// A grasp of a control takes the hand's pose and the coordinate as the projection's reference; a
// release leaves the control with the hand's velocity along its joint.
void ControlSystem::after_grasp(const std::vector<GraspEvent>& grasp_events) {
  for (const GraspEvent& e : grasp_events) {
    const int ci = scene_.objects[e.object].control;
    if (ci < 0) continue;
    const ControlSpec& c = scene_.controls[ci];
    ControlState& s = state_.controls[ci];
    const BodyState& body = state_.bodies[c.body];
    if (e.grasp) {
      const auto hand = std::find(hand_ids_.begin(), hand_ids_.end(), e.hand_id) - hand_ids_.begin();
      s.X_GH_grasp = state_.hands[static_cast<std::size_t>(hand)].X_GH;
      s.q_grasp = s.q;
    } else if (!body.held()) {  // (handed over: the other hand's grasp follows)
      const Eigen::Vector3d a = joint_axis_G(c);
      s.qd = c.joint == JointKind::kPrismatic ? a.dot(body.v_G) : a.dot(body.w_G);
      place(ci);
      at_rest_[ci] = 0;
    }
  }
}

void ControlSystem::forget_step() {
  events_.clear();
  std::fill(at_rest_.begin(), at_rest_.end(), 0);
  std::fill(commanded_.begin(), commanded_.end(), -1);
}

void ControlSystem::reset_to(const std::vector<ControlState>& saved, int64_t t_ns) {
  VCOCKPIT_ASSERT(saved.size() == state_.controls.size(), "a state of this scene's controls");
  events_.clear();
  for (std::size_t ci = 0; ci < state_.controls.size(); ++ci) {
    ControlState& c = state_.controls[ci];
    const int from = c.position;
    c = saved[ci];
    c.push_hand = -1;
    c.push_link = -1;
    c.push_direction = 0;
    if (c.position != from) {
      ControlEvent e;
      e.t_ns = t_ns;
      e.control = static_cast<int>(ci);
      e.from = from;
      e.to = c.position;
      e.cause = ControlCause::kCommanded;
      events_.push_back(e);
    }
  }
  std::fill(at_rest_.begin(), at_rest_.end(), 0);
  std::fill(commanded_.begin(), commanded_.end(), -1);
}

void ControlSystem::place(int control) {
  const ControlSpec& c = scene_.controls[control];
  const ControlState& s = state_.controls[control];
  BodyState& body = state_.bodies[c.body];
  body.X_GO = control_body_pose(c, s.q);
  const Eigen::Vector3d a = joint_axis_G(c);
  if (c.joint == JointKind::kPrismatic) {
    body.v_G = s.qd * a;
    body.w_G.setZero();
  } else {
    body.w_G = s.qd * a;
    body.v_G = body.w_G.cross(body.X_GO.translation() - joint_origin_G(c));
  }
}

void ControlSystem::note_position(int control, ControlCause cause, int hand_id, int link) {
  ControlState& s = state_.controls[control];
  const int from = s.position;
  if (!update_position(scene_.controls[control], s)) return;
  ControlEvent e;
  e.t_ns = state_.time_ns + step_ns_;  // the end of the step it happens in
  e.control = control;
  e.from = from;
  e.to = s.position;
  e.cause = cause;
  e.hand_id = hand_id;
  e.link = link;
  events_.push_back(e);
}

}  // namespace vcockpit::physics
