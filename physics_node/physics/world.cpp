#include "physics_node/physics/world.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "common/assert.hpp"
#include "physics_node/physics/contact_sums.hpp"
#include "physics_node/physics/integrator.hpp"

namespace vcockpit::physics {
namespace {

// Adds the wall time of a scope to one stage (an observation; never feeds back into results).
class StageTimer {
 public:
  StageTimer(StageTimes& times, Stage stage)
      : slot_(times.ns[static_cast<int>(stage)]), start_(std::chrono::steady_clock::now()) {}
  ~StageTimer() {
    slot_ += std::chrono::duration_cast<std::chrono::nanoseconds>(
                 std::chrono::steady_clock::now() - start_)
                 .count();
  }

 private:
  int64_t& slot_;
  std::chrono::steady_clock::time_point start_;
};

Eigen::Isometry3d interpolate(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b, double s) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = a.translation() + s * (b.translation() - a.translation());
  X.linear() = Eigen::Quaterniond(a.linear()).slerp(s, Eigen::Quaterniond(b.linear())).toRotationMatrix();
  return X;
}

// Scales a link's velocity so that no point of it (within `length_m` of its origin, or of the
// palm's half-diagonal) moves faster than `max_mps`.
void limit_link_speed(double length_m, double max_mps, Eigen::Vector3d& v_G, Eigen::Vector3d& w_G) {
  const double reach_m = std::max(length_m, 0.1);
  const double fastest_mps = v_G.norm() + w_G.norm() * reach_m;
  if (fastest_mps <= max_mps) return;
  const double scale = max_mps / fastest_mps;
  v_G *= scale;
  w_G *= scale;
}

// 0 for a right hand, 1 for a left one (as the topics name them).
int hand_id_of(const Scene& scene) { return scene.hand && scene.hand->left ? 1 : 0; }

}  // namespace

const char* stage_name(Stage stage) {
  static constexpr const char* kNames[] = {"hand_kinematics", "broadphase", "narrowphase",
                                           "forces", "grasp", "integrate"};
  return kNames[static_cast<int>(stage)];
}

World::World(Scene scene)
    : scene_(std::move(scene)),
      collision_(scene_),
      substep_choice_(scene_, collision_),
      forces_(scene_.contact.slip_speed_mps),
      grasp_tracker_(scene_.grasp, scene_.step_s, scene_.gravity_mps2, hand_id_of(scene_)),
      body_check_(scene_),
      object_count_(static_cast<int>(scene_.objects.size())),
      step_ns_(std::llround(scene_.step_s * 1e9)) {
  if (scene_.contact.max_substeps < 1 || !(scene_.step_s > 0.0))
    throw std::invalid_argument("World: the step and max_substeps must be positive");
  hand_id_ = grasp_tracker_.hand_id();
  if (scene_.hand && scene_.proxy.enabled) {
    proxy_.emplace(scene_);
    proxy_->set_resting_links(&resting_links_);
  }
  state_.bodies.resize(object_count_);
  X_GO_.resize(object_count_);
  X_GO_before_.resize(object_count_);
  state_.grasp.resize(object_count_);
  I_O_inv_.resize(object_count_);
  held_mask_.assign(object_count_, 0);
  resting_links_.assign(object_count_, 0);
  state_.blocking_out_G.reserve(kMaxBlockingPlanes);
  start_bodies_.resize(object_count_);
  for (int i = 0; i < object_count_; ++i) {
    const ObjectSpec& o = scene_.objects[i];
    state_.bodies[i].X_GO = o.X_GO;
    state_.bodies[i].v_G = o.v_G;
    state_.bodies[i].w_G = o.w_G;
    X_GO_[i] = o.X_GO;
    X_GO_before_[i] = o.X_GO;
    state_.grasp[i] = grasp_tracker_.initial_hold(o);
    I_O_inv_[i] = o.dynamic ? Eigen::Matrix3d(o.I_O.inverse()) : Eigen::Matrix3d::Zero();
  }
  const int control_count = static_cast<int>(scene_.controls.size());
  state_.controls.resize(control_count);
  control_inertia_.resize(control_count);
  control_grasp_joint_.resize(control_count);
  control_push_link_.assign(control_count, -1);
  control_push_N_.assign(control_count, 0.0);
  control_touched_.assign(control_count, 0);
  control_commanded_.assign(control_count, -1);
  control_at_rest_.assign(control_count, 0);
  control_push_Q_.assign(control_count, 0.0);
  for (int ci = 0; ci < control_count; ++ci) {
    const ControlSpec& c = scene_.controls[ci];
    VCOCKPIT_ASSERT(c.body >= 0 && c.body < object_count_ && scene_.objects[c.body].control == ci &&
                        scene_.objects[c.body].dynamic && !c.positions.empty(),
                    "a control moves a dynamic object of its own and has positions");
    const ObjectSpec& o = scene_.objects[c.body];
    control_inertia_[ci] = joint_inertia(c, o.mass_kg, o.I_O);
    GraspJoint& joint = control_grasp_joint_[ci];
    joint.revolute = c.joint == JointKind::kRevolute;
    joint.axis_G = joint_axis_G(c);
    joint.origin_G = joint_origin_G(c);
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
    place_control(ci);
    X_GO_[c.body] = state_.bodies[c.body].X_GO;
    X_GO_before_[c.body] = X_GO_[c.body];
  }
  state_.X_GL.fill(Eigen::Isometry3d::Identity());
  X_GL_before_ = state_.X_GL;
  tracked_X_GL_ = state_.X_GL;
  state_.substeps = choose_substeps(false);  // for the initial state: the count the first step will use
  const int body_count = object_count_ + (scene_.hand ? kLinkCount : 0);
  contact_bodies_.resize(body_count);
  F_G_.resize(body_count);
  M_G_.resize(body_count);
  contacts_.reserve(256);
  applied_.reserve(256);
  hand_contacts_.reserve(64);
  events_.reserve(16);
  state_.anchors.reserve(256);
}

World::~World() = default;

// Substeps for the coming step (substep_choice.hpp): the hand sweeps from its links now to the
// latest input, or the proxy to where it heads (never farther than its speeds allow).
int World::choose_substeps(bool holding) {
  if (proxy_ && state_.hand_active) {
    proxy_start_ = {state_.X_GH, state_.q_rad};
    fingers_kept_ = 0;
    proxy_goal_ = proxy_->step_goal(proxy_start_, state_.hand_from, state_.hand_to,
                                    state_.pushing, holding, state_.blocking_out_G, scene_.step_s);
    return substep_choice_.choose(state_.bodies, &state_.X_GL, proxy_goal_.X_GH,
                                  proxy_goal_.q_rad);
  }
  return substep_choice_.choose(state_.bodies, state_.hand_active ? &state_.X_GL : nullptr,
                                state_.hand_to.X_GH, state_.hand_to.q_rad);
}

void World::restore(const WorldState& state) {
  VCOCKPIT_ASSERT(state.bodies.size() == state_.bodies.size() &&
                      state.grasp.size() == state_.grasp.size() &&
                      state.controls.size() == state_.controls.size(),
                  "a world state of another scene (object count)");
  for (int i = 0; i < object_count_; ++i)
    VCOCKPIT_ASSERT(state.grasp[i].history.size() == state_.grasp[i].history.size(),
                    "a world state of another scene (grasp velocity window)");
  VCOCKPIT_ASSERT(!state.hand_active || scene_.hand.has_value(), "a hand state without a hand");
  state_ = state;
  proxy_prev_links_valid_ = false;
  tracked_observed_ = false;
  // the last step's observations belong to the world the state came from
  applied_.clear();
  events_.clear();
  control_events_.clear();
  std::fill(control_at_rest_.begin(), control_at_rest_.end(), 0);
  std::fill(control_commanded_.begin(), control_commanded_.end(), -1);
  stage_times_ = StageTimes{};
  penetration_ = PenetrationStats{};
  body_check_.clear_new_faults();
}

void World::set_hand_input(const HandInput& input) {
  if (!scene_.hand) return;
  state_.hand_to = input;
  if (!state_.hand_active) {
    state_.hand_from = input;  // first sample: no sweep from nowhere
    state_.hand_active = true;
    place_hand(input.X_GH, input.q_rad);
    X_GL_before_ = state_.X_GL;
    proxy_prev_links_valid_ = false;
    tracked_observed_ = false;
  }
}

void World::step() {
  stage_times_ = StageTimes{};
  events_.clear();
  control_events_.clear();
  for (int ci = 0; ci < static_cast<int>(control_commanded_.size()); ++ci) {
    const int position = control_commanded_[ci];
    if (position < 0) continue;
    control_commanded_[ci] = -1;
    const ControlSpec& c = scene_.controls[ci];
    ControlState& s = state_.controls[ci];
    if (state_.bodies[c.body].held_by != kNotHeld) continue;  // a hand took it meanwhile
    if (c.latching) {
      s.latched = position == 1;
      s.q = spring_rest(c, s);
    } else {
      s.q = c.positions[static_cast<std::size_t>(position)].q;
    }
    s.qd = 0.0;
    s.push_link = -1;
    s.push_direction = 0;
    place_control(ci);
    control_at_rest_[ci] = 0;
    note_control_position(ci, ControlCause::kCommanded, -1, -1);
  }
  body_check_.clear_new_faults();
  std::copy(state_.bodies.begin(), state_.bodies.end(), start_bodies_.begin());
  // a held object and the hand move together: their contacts matter to the grasp test only,
  // which reads the last substep's, so the substeps before it leave them out (their friction
  // anchors carry over) -- but for a proxy hand, whose fingers stop at the held object's surface
  bool any_held = false;
  for (int i = 0; i < object_count_; ++i) {
    held_mask_[i] = state_.bodies[i].held_by != kNotHeld ? 1 : 0;
    resting_links_[i] = state_.grasp[i].resting_links;
    any_held = any_held || held_mask_[i] != 0;
  }
  {
    StageTimer timer(stage_times_, Stage::kBroadphase);
    state_.substeps = choose_substeps(any_held);
  }
  VCOCKPIT_ASSERT(state_.substeps >= 1 && state_.substeps <= scene_.contact.max_substeps,
                  "substeps in [1, max_substeps]");
  if (proxy_ && state_.hand_active && !proxy_prev_links_valid_) {
    forward_kinematics(*scene_.hand, state_.q_rad, proxy_prev_links_);
    proxy_prev_links_valid_ = true;
  }
  const double dt_s = scene_.step_s / state_.substeps;
  for (int s = 1; s <= state_.substeps; ++s)
    substep(dt_s, static_cast<double>(s) / state_.substeps, state_.substeps - s + 1,
            any_held && s < state_.substeps);
  // a held object's velocity is the hand's over the whole step: within it the proxy can go
  // into a panel and be shifted back out substep by substep, which is no motion of the object
  for (int i = 0; i < object_count_; ++i) {
    BodyState& body = state_.bodies[i];
    if (held_mask_[i] == 0 || body.held_by == kNotHeld) continue;
    finite_difference_velocity(start_bodies_[i].X_GO, body.X_GO, scene_.step_s, body.v_G, body.w_G);
  }
  state_.time_ns += step_ns_;
  ++state_.steps;
  {
    StageTimer timer(stage_times_, Stage::kIntegrate);
    body_check_.check(state_.bodies, start_bodies_, state_.time_ns);
  }
  grasp_stage();
  tracked_observed_ = false;
  state_.hand_from = state_.hand_to;
}

void World::substep(double dt_s, double alpha, int remaining, bool skip_held_hand_pairs) {
  held_pairs_skipped_ = skip_held_hand_pairs;
  {
    StageTimer timer(stage_times_, Stage::kHandKinematics);
    if (state_.hand_active) move_hand(alpha, remaining);
    move_held_objects(dt_s);
  }
  {
    StageTimer timer(stage_times_, Stage::kBroadphase);
    for (int i = 0; i < object_count_; ++i) X_GO_[i] = state_.bodies[i].X_GO;
    collision_.set_poses(X_GO_, state_.hand_active ? &state_.X_GL : nullptr);
    collision_.find_candidate_pairs();
  }
  {
    StageTimer timer(stage_times_, Stage::kNarrowphase);
    collision_.skip_hand_pairs_with(skip_held_hand_pairs ? &held_mask_ : nullptr);
    collision_.compute_contacts(contacts_, proxy_ ? &hand_static_ : nullptr);
  }
  if (proxy_ && state_.hand_active) {
    StageTimer timer(stage_times_, Stage::kHandKinematics);
    constrain_proxy(dt_s);
  }
  {
    StageTimer timer(stage_times_, Stage::kForces);
    build_contact_bodies();
    for (std::size_t b = 0; b < F_G_.size(); ++b) {
      F_G_[b].setZero();
      M_G_[b].setZero();
    }
    KeptPairs kept;
    if (skip_held_hand_pairs) kept = {&held_mask_, object_count_};
    forces_.apply(contacts_, contact_bodies_, dt_s, F_G_, M_G_, applied_, state_.anchors, kept);
    if (!scene_.controls.empty()) find_control_pushers();
  }
  {
    StageTimer timer(stage_times_, Stage::kIntegrate);
    integrate(dt_s);
  }
}

void World::move_hand(double alpha, int remaining) {
  X_GL_before_ = state_.X_GL;
  if (proxy_) {
    // the proxy's tentative pose; constrain_proxy holds it back after the narrowphase
    proxy_prev_ = {state_.X_GH, state_.q_rad};
    ProxyPose next = ProxyHand::advance(proxy_prev_, proxy_start_, proxy_goal_, state_.substeps);
    // a finger on a held object waits for the last substep, where their contacts are known,
    // and then takes the step's whole motion
    if (remaining > 1 && held_pairs_skipped_) {
      proxy_->keep_fingers(state_.fingers_on_held, proxy_prev_, next);
      fingers_kept_ = state_.fingers_on_held;
    } else if (remaining == 1 && fingers_kept_ != 0) {
      proxy_->catch_up_fingers(fingers_kept_, proxy_prev_, proxy_start_, proxy_goal_, next);
    }
    place_hand(next.X_GH, next.q_rad);
    return;
  }
  JointAngles q;
  for (int j = 0; j < kJointCount; ++j) {
    q[j] = state_.hand_from.q_rad[j] + alpha * (state_.hand_to.q_rad[j] - state_.hand_from.q_rad[j]);
  }
  place_hand(interpolate(state_.hand_from.X_GH, state_.hand_to.X_GH, alpha), q);
}

void World::place_hand(const Eigen::Isometry3d& X_GH, const JointAngles& q_rad) {
  state_.X_GH = X_GH;
  state_.q_rad = q_rad;
  forward_kinematics(*scene_.hand, q_rad, link_poses_);
  for (int l = 0; l < kLinkCount; ++l) state_.X_GL[l] = state_.X_GH * link_poses_.X_HL[l];
}

void World::constrain_proxy(double dt_s) {
  ProxyPose pose{state_.X_GH, state_.q_rad};
  const bool fingers_moved =
      proxy_->constrain_fingers(proxy_prev_, proxy_prev_links_, pose, link_poses_, state_.X_GL,
                                held_mask_, contacts_, hand_static_, dt_s);
  // the links' static contacts afresh: the wrist's shift must see exactly how deep they are
  if (fingers_moved) collision_.compute_hand_static_contacts(state_.X_GL, hand_static_);
  const ProxyConstraint r =
      proxy_->constrain_wrist(pose, state_.X_GL, held_mask_, contacts_, hand_static_,
                              state_.blocking_out_G);
  state_.X_GH = pose.X_GH;
  state_.q_rad = pose.q_rad;
  state_.pushing = r.pushing;
  if (!held_pairs_skipped_) state_.fingers_on_held = proxy_->fingers_touching(contacts_, held_mask_);
  proxy_prev_links_ = link_poses_;
  if (r.shift_G.squaredNorm() == 0.0) return;
  // the held objects move with the proxy (eq. 29)
  for (int i = 0; i < object_count_; ++i) {
    BodyState& body = state_.bodies[i];
    if (body.held_by == kNotHeld || scene_.objects[i].control >= 0) continue;  // a joint holds a control
    body.X_GO.translation() += r.shift_G;
    finite_difference_velocity(X_GO_before_[i], body.X_GO, dt_s, body.v_G, body.w_G);
  }
}

uint32_t World::glove_links_inside(int object, const GraspHold& hold) const {
  if (!proxy_ || !state_.hand_active || !hold.hand_clearing) return 0;
  observe_tracked_hand();
  uint32_t inside = 0;
  for (int l = 0; l < kLinkCount; ++l)
    if (collision_.link_overlaps(static_cast<Link>(l), tracked_X_GL_[l], object)) inside |= 1u << l;
  return inside;
}

void World::observe_tracked_hand() const {
  if (tracked_observed_) return;
  tracked_observed_ = true;
  tracked_offset_m_ = 0.0;
  if (!proxy_ || !state_.hand_active) return;
  HandLinkPoses tracked;
  forward_kinematics(*scene_.hand, state_.hand_to.q_rad, tracked);
  const Eigen::Isometry3d& X_GT = state_.hand_to.X_GH;
  double offset_m = 0.0;
  for (int l = 0; l < kLinkCount; ++l) {
    tracked_X_GL_[l] = X_GT * tracked.X_HL[l];
    offset_m = std::max(offset_m, (tracked_X_GL_[l].translation() - state_.X_GL[l].translation()).norm());
  }
  for (int f = 0; f < kFingerCount; ++f)
    offset_m = std::max(offset_m, (X_GT * tracked.p_H_tip[f] - state_.X_GH * link_poses_.p_H_tip[f]).norm());
  tracked_offset_m_ = offset_m;
}

void World::move_held_objects(double dt_s) {
  for (int i = 0; i < object_count_; ++i) {
    BodyState& body = state_.bodies[i];
    if (body.held_by == kNotHeld) continue;
    if (scene_.objects[i].control >= 0) {
      move_held_control(scene_.objects[i].control, dt_s);
      continue;
    }
    X_GO_before_[i] = body.X_GO;
    body.X_GO = state_.X_GH * state_.grasp[i].X_HO;  // eq. 29
    finite_difference_velocity(X_GO_before_[i], body.X_GO, dt_s, body.v_G, body.w_G);
  }
}

void World::build_contact_bodies() {
  for (int i = 0; i < object_count_; ++i) {
    const ObjectSpec& o = scene_.objects[i];
    const BodyState& s = state_.bodies[i];
    ContactBody& c = contact_bodies_[i];
    c.X_GB = s.X_GO;
    c.v_G = s.v_G;
    c.w_G = s.w_G;
    c.material = &o.material;
    c.dynamic = o.dynamic && s.held_by == kNotHeld;
    c.inv_mass = c.dynamic ? 1.0 / o.mass_kg : 0.0;
    c.mass_for_damping = c.dynamic ? o.mass_kg : 0.0;
    c.inv_I_O = c.dynamic ? I_O_inv_[i] : Eigen::Matrix3d::Zero();
  }
  if (!scene_.hand) return;
  // a link's velocity only where it touches something (the rotation's log is not free)
  std::array<bool, kLinkCount> touching{};
  std::array<bool, kLinkCount> touching_free{};
  for (const ContactPoint& c : contacts_) {
    if (c.body_b < object_count_) continue;
    const auto l = static_cast<std::size_t>(c.body_b - object_count_);
    touching[l] = true;
    if (c.body_a < object_count_ && contact_bodies_[c.body_a].dynamic) touching_free[l] = true;
  }
  const double dt_s = scene_.step_s / state_.substeps;
  for (int l = 0; l < kLinkCount; ++l) {
    ContactBody& c = contact_bodies_[object_count_ + l];
    c.X_GB = state_.X_GL[l];
    if (touching[static_cast<std::size_t>(l)]) {
      finite_difference_velocity(X_GL_before_[l], state_.X_GL[l], dt_s, c.v_G, c.w_G);
      // a proxy link pushes a free object no faster than push_speed_mps, however fast the
      // tracked hand (or a 30 Hz glove's jump) moved it: its speed feeds the contact damping
      if (proxy_ && touching_free[static_cast<std::size_t>(l)])
        limit_link_speed(scene_.hand->capsules[static_cast<std::size_t>(l)].length_m,
                         scene_.proxy.push_speed_mps, c.v_G, c.w_G);
    } else {
      c.v_G.setZero();
      c.w_G.setZero();
    }
    c.material = &scene_.hand_material;
    c.dynamic = false;
    c.inv_mass = 0.0;
    c.mass_for_damping = 0.0;
    c.inv_I_O.setZero();
  }
}

void World::integrate(double dt_s) {
  for (int i = 0; i < object_count_; ++i) {
    const ObjectSpec& o = scene_.objects[i];
    BodyState& body = state_.bodies[i];
    if (!o.dynamic || body.held_by != kNotHeld || o.control >= 0) continue;
    const Eigen::Vector3d F = total_force_G(F_G_[i], o.mass_kg, scene_.gravity_mps2);  // eq. 18
    integrate_body(body, F, M_G_[i], o.mass_kg, o.I_O, I_O_inv_[i], dt_s);
  }
  if (!scene_.controls.empty()) integrate_controls(dt_s);
}

bool World::command_control(int control, int position) {
  if (control < 0 || control >= static_cast<int>(scene_.controls.size())) return false;
  const ControlSpec& c = scene_.controls[control];
  if (position < 0 || position >= static_cast<int>(c.positions.size())) return false;
  if (state_.bodies[c.body].held_by != kNotHeld) return false;
  control_commanded_[control] = position;
  return true;
}

void World::integrate_controls(double dt_s) {
  for (int ci = 0; ci < static_cast<int>(scene_.controls.size()); ++ci) {
    const ControlSpec& c = scene_.controls[ci];
    BodyState& body = state_.bodies[c.body];
    if (body.held_by != kNotHeld) continue;  // moved with the hand (move_held_control)
    const ObjectSpec& o = scene_.objects[c.body];
    // a control its last substep left where it was, at rest, with nothing touching it now, stays
    // there exactly (the same inputs give the same step): most of a cockpit's controls, always
    const bool untouched = F_G_[c.body].isZero(0.0) && M_G_[c.body].isZero(0.0);
    if (untouched && control_at_rest_[ci] != 0) continue;
    // eqs. 18-19 on the body, gravity included, projected onto the joint
    const Eigen::Vector3d F_G = total_force_G(F_G_[c.body], o.mass_kg, scene_.gravity_mps2);
    const double Q = generalised_force(c, body.X_GO.translation(), F_G, M_G_[c.body]);
    ControlState& s = state_.controls[ci];
    const double q_before = s.q;
    integrate_control(c, control_inertia_[ci], Q, dt_s, 0u, s);
    control_at_rest_[ci] = untouched && s.q == q_before && s.qd == 0.0 ? 1 : 0;
    if (s.q != q_before || s.qd != 0.0 || body.v_G.squaredNorm() + body.w_G.squaredNorm() != 0.0)
      place_control(ci);
    // pushed: the hand's force drives the motion (a button that springs back out against a
    // withdrawing fingertip is returned by its spring), or drove it and the control goes on the
    // same way (a toggle snapping over once the finger has pushed it past its centre)
    if (control_push_link_[ci] >= 0 && control_push_Q_[ci] * s.qd > 0.0) {
      s.push_link = control_push_link_[ci];
      s.push_direction = s.qd > 0.0 ? 1 : -1;
    } else if (s.push_direction * s.qd <= 0.0) {
      s.push_link = -1;
      s.push_direction = 0;
    }
    if (s.push_direction != 0) {
      note_control_position(ci, ControlCause::kPushed, hand_id_, s.push_link);
    } else {
      note_control_position(ci, control_touched_[ci] != 0 ? ControlCause::kObject
                                                          : ControlCause::kMechanism,
                            -1, -1);
    }
  }
}

// eq. 29 restricted to the joint: the coordinate the hand's motion since the grasp asks for,
// as far as the travel and the gates (open only while the hand has lifted the lever) let it go
void World::move_held_control(int control, double dt_s) {
  const ControlSpec& c = scene_.controls[control];
  ControlState& s = state_.controls[control];
  const Eigen::Vector3d p_held_H = state_.grasp[c.body].X_HO.translation();
  const double lift_m = grasped_lift_m(c, s, state_.X_GH, p_held_H);
  uint32_t gates_open = 0;
  for (std::size_t g = 0; g < c.gates.size(); ++g)
    if (lift_m >= c.gates[g].lift_m) gates_open |= 1u << g;
  const double q = reachable_q(c, s.q, grasped_q(c, s, state_.X_GH, p_held_H), gates_open);
  s.qd = (q - s.q) / dt_s;
  s.q = q;
  s.push_link = -1;
  s.push_direction = 0;
  place_control(control);
  control_at_rest_[control] = 0;
  note_control_position(control, ControlCause::kGrasped, state_.bodies[c.body].held_by, -1);
}

void World::place_control(int control) {
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

void World::note_control_position(int control, ControlCause cause, int hand_id, int link) {
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
  control_events_.push_back(e);
}

// who pushes each control in this substep: the hand link with the largest normal force on its
// body, or another object
void World::find_control_pushers() {
  std::fill(control_push_link_.begin(), control_push_link_.end(), -1);
  std::fill(control_push_N_.begin(), control_push_N_.end(), 0.0);
  std::fill(control_touched_.begin(), control_touched_.end(), 0);
  std::fill(control_push_Q_.begin(), control_push_Q_.end(), 0.0);
  for (const AppliedContact& a : applied_) {
    const int body_a = a.contact.body_a;
    const int body_b = a.contact.body_b;
    for (const auto& [body, other] : {std::pair{body_a, body_b}, std::pair{body_b, body_a}}) {
      if (body >= object_count_) continue;
      const int ci = scene_.objects[body].control;
      if (ci < 0) continue;
      if (collision_.is_hand_body(other)) {
        if (a.normal_N > control_push_N_[ci]) {
          control_push_N_[ci] = a.normal_N;
          control_push_link_[ci] = other - object_count_;
        }
        // the hand's generalised force on the control: its contact force at the contact point
        const Eigen::Vector3d F_G = body == body_b ? a.F_on_b_G : Eigen::Vector3d(-a.F_on_b_G);
        const ControlSpec& c = scene_.controls[ci];
        control_push_Q_[ci] +=
            c.joint == JointKind::kPrismatic
                ? joint_axis_G(c).dot(F_G)
                : joint_axis_G(c).dot((a.contact.p_G - joint_origin_G(c)).cross(F_G));
      } else {
        control_touched_[ci] = 1;
      }
    }
  }
}

// A grasp of a control takes the hand's pose and the coordinate as the projection's reference; a
// release leaves the control with the hand's velocity along its joint.
void World::controls_after_grasp_stage() {
  for (const GraspEvent& e : events_) {
    const int ci = scene_.objects[e.object].control;
    if (ci < 0) continue;
    const ControlSpec& c = scene_.controls[ci];
    ControlState& s = state_.controls[ci];
    const BodyState& body = state_.bodies[c.body];
    if (e.grasp) {
      s.X_GH_grasp = state_.X_GH;
      s.q_grasp = s.q;
    } else {
      const Eigen::Vector3d a = joint_axis_G(c);
      s.qd = c.joint == JointKind::kPrismatic ? a.dot(body.v_G) : a.dot(body.w_G);
      place_control(ci);
      control_at_rest_[ci] = 0;
    }
  }
}

void World::grasp_stage() {
  StageTimer timer(stage_times_, Stage::kGrasp);
  penetration_ = PenetrationStats{};
  if (!scene_.hand) return;
  const HandNow hand{state_.time_ns, state_.hand_to.tracking, state_.X_GH, &state_.hand_to.q_rad};
  const auto grasp_object = [&](int object, const HandContact* contacts, std::size_t count) {
    GraspHold& hold = state_.grasp[object];
    const ObjectSpec& o = scene_.objects[object];
    grasp_tracker_.update(object, o, contacts, count, hand, glove_links_inside(object, hold), hold,
                          state_.bodies[object], events_,
                          o.control >= 0 ? &control_grasp_joint_[o.control] : nullptr);
  };
  // hand contacts of the last substep, grouped by object (contacts are sorted by body_a)
  std::size_t i = 0;
  int next_object = 0;  // objects before it have had their grasp test this step
  auto grasp_untouched_up_to = [&](int end) {
    for (; next_object < end; ++next_object) grasp_object(next_object, nullptr, 0);
  };
  while (i < applied_.size()) {
    const int object = applied_[i].contact.body_a;
    hand_contacts_.clear();
    for (; i < applied_.size() && applied_[i].contact.body_a == object; ++i) {
      const AppliedContact& a = applied_[i];
      if (!collision_.is_hand_body(a.contact.body_b) || collision_.is_hand_body(object)) continue;
      HandContact hc;
      hc.link = static_cast<Link>(a.contact.body_b - object_count_);
      hc.p_G = a.contact.p_G;
      hc.n_G = -a.contact.n_G;  // from the link into the object
      hc.F_G = -a.F_on_b_G;     // the link's force on the object
      hand_contacts_.push_back(hc);
      penetration_.max_m = std::max(penetration_.max_m, a.contact.depth_m);
      penetration_.sum_m += a.contact.depth_m;
      ++penetration_.points;
    }
    if (object >= object_count_) break;  // link-link pairs never occur; nothing further
    grasp_untouched_up_to(object);
    grasp_object(object, hand_contacts_.data(), hand_contacts_.size());
    next_object = object + 1;
  }
  grasp_untouched_up_to(object_count_);
  for (const ContactPoint& c : hand_static_)
    penetration_.static_max_m = std::max(penetration_.static_max_m, c.depth_m);
  // held poses for the release velocity
  for (int o = 0; o < object_count_; ++o)
    if (state_.bodies[o].held_by != kNotHeld)
      grasp_tracker_.record_held_pose(state_.grasp[o], state_.bodies[o]);
  if (!scene_.controls.empty()) controls_after_grasp_stage();
}

}  // namespace vcockpit::physics
