#include "physics_node/physics/world.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

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

// Velocity of a frame from two poses dt apart (eq. 15 for a tracked, kinematic body).
void finite_difference(const Eigen::Isometry3d& before, const Eigen::Isometry3d& now, double dt_s,
                       Eigen::Vector3d& v_G, Eigen::Vector3d& w_G) {
  v_G = (now.translation() - before.translation()) / dt_s;
  const Eigen::AngleAxisd turn(now.linear() * before.linear().transpose());
  w_G = turn.axis() * (turn.angle() / dt_s);
}

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
      object_count_(static_cast<int>(scene_.objects.size())),
      step_ns_(std::llround(scene_.step_s * 1e9)) {
  hand_id_ = scene_.hand && scene_.hand->left ? 1 : 0;
  bodies_.resize(object_count_);
  X_GO_.resize(object_count_);
  X_GO_before_.resize(object_count_);
  grasp_.resize(object_count_);
  I_O_inv_.resize(object_count_);
  held_mask_.assign(object_count_, 0);
  const std::size_t window = std::max<std::size_t>(
      2, static_cast<std::size_t>(std::llround(scene_.grasp.velocity_window_s / scene_.step_s)) + 1);
  for (int i = 0; i < object_count_; ++i) {
    const ObjectSpec& o = scene_.objects[i];
    bodies_[i].X_GO = o.X_GO;
    bodies_[i].v_G = o.v_G;
    bodies_[i].w_G = o.w_G;
    X_GO_[i] = o.X_GO;
    X_GO_before_[i] = o.X_GO;
    if (o.dynamic) grasp_[i].history.resize(window);
    I_O_inv_[i] = o.dynamic ? Eigen::Matrix3d(o.I_O.inverse()) : Eigen::Matrix3d::Zero();
  }
  X_GL_.fill(Eigen::Isometry3d::Identity());
  X_GL_before_ = X_GL_;
  substeps_ = choose_substeps();  // for the initial state: the count the first step will use
  const int body_count = object_count_ + (scene_.hand ? kLinkCount : 0);
  contact_bodies_.resize(body_count);
  F_G_.resize(body_count);
  M_G_.resize(body_count);
  contacts_.reserve(256);
  applied_.reserve(256);
  hand_contacts_.reserve(64);
  events_.reserve(16);
}

World::~World() = default;

// Substeps for the coming step (substep_choice.hpp): the hand sweeps from its links now to the
// latest input.
int World::choose_substeps() {
  return substep_choice_.choose(bodies_, hand_active_ ? &X_GL_ : nullptr, hand_to_.X_GH,
                                hand_to_.q_rad);
}

void World::set_hand_input(const HandInput& input) {
  if (!scene_.hand) return;
  hand_to_ = input;
  if (!hand_active_) {
    hand_from_ = input;  // first sample: no sweep from nowhere
    hand_active_ = true;
    move_hand(1.0);
    X_GL_before_ = X_GL_;
  }
}

void World::step() {
  stage_times_ = StageTimes{};
  events_.clear();
  {
    StageTimer timer(stage_times_, Stage::kBroadphase);
    substeps_ = choose_substeps();
  }
  // a held object and the hand move together: their contacts matter to the grasp test only,
  // which reads the last substep's, so the substeps before it leave them out (their friction
  // anchors carry over)
  bool any_held = false;
  for (int i = 0; i < object_count_; ++i) {
    held_mask_[i] = bodies_[i].held_by != kNotHeld ? 1 : 0;
    any_held = any_held || held_mask_[i] != 0;
  }
  const double dt_s = scene_.step_s / substeps_;
  for (int s = 1; s <= substeps_; ++s)
    substep(dt_s, static_cast<double>(s) / substeps_, any_held && s < substeps_);
  time_ns_ += step_ns_;
  ++steps_;
  grasp_stage();
  hand_from_ = hand_to_;
}

void World::substep(double dt_s, double alpha, bool skip_held_hand_pairs) {
  {
    StageTimer timer(stage_times_, Stage::kHandKinematics);
    if (hand_active_) move_hand(alpha);
    move_held_objects(dt_s);
  }
  {
    StageTimer timer(stage_times_, Stage::kBroadphase);
    for (int i = 0; i < object_count_; ++i) X_GO_[i] = bodies_[i].X_GO;
    collision_.set_poses(X_GO_, hand_active_ ? &X_GL_ : nullptr);
    collision_.find_candidate_pairs();
  }
  {
    StageTimer timer(stage_times_, Stage::kNarrowphase);
    collision_.skip_hand_pairs_with(skip_held_hand_pairs ? &held_mask_ : nullptr);
    collision_.compute_contacts(contacts_);
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
    forces_.apply(contacts_, contact_bodies_, F_G_, M_G_, applied_, kept);
  }
  {
    StageTimer timer(stage_times_, Stage::kIntegrate);
    integrate(dt_s);
  }
}

void World::move_hand(double alpha) {
  const HandModel& hand = *scene_.hand;
  X_GH_ = interpolate(hand_from_.X_GH, hand_to_.X_GH, alpha);
  JointAngles q;
  for (int j = 0; j < kJointCount; ++j) {
    q[j] = hand_from_.q_rad[j] + alpha * (hand_to_.q_rad[j] - hand_from_.q_rad[j]);
  }
  forward_kinematics(hand, q, link_poses_);
  X_GL_before_ = X_GL_;
  for (int l = 0; l < kLinkCount; ++l) X_GL_[l] = X_GH_ * link_poses_.X_HL[l];
}

void World::move_held_objects(double dt_s) {
  for (int i = 0; i < object_count_; ++i) {
    BodyState& body = bodies_[i];
    if (body.held_by == kNotHeld) continue;
    X_GO_before_[i] = body.X_GO;
    body.X_GO = X_GH_ * grasp_[i].X_HO;  // eq. 29
    finite_difference(X_GO_before_[i], body.X_GO, dt_s, body.v_G, body.w_G);
  }
}

void World::build_contact_bodies() {
  for (int i = 0; i < object_count_; ++i) {
    const ObjectSpec& o = scene_.objects[i];
    const BodyState& s = bodies_[i];
    ContactBody& c = contact_bodies_[i];
    c.X_GB = s.X_GO;
    c.v_G = s.v_G;
    c.w_G = s.w_G;
    c.material = &o.material;
    c.dynamic = o.dynamic && s.held_by == kNotHeld;
    c.inv_mass = c.dynamic ? 1.0 / o.mass_kg : 0.0;
    c.mass_for_damping = c.dynamic ? o.mass_kg : 0.0;
  }
  if (!scene_.hand) return;
  // a link's velocity only where it touches something (the rotation's log is not free)
  std::array<bool, kLinkCount> touching{};
  for (const ContactPoint& c : contacts_)
    if (c.body_b >= object_count_) touching[static_cast<std::size_t>(c.body_b - object_count_)] = true;
  const double dt_s = scene_.step_s / substeps_;
  for (int l = 0; l < kLinkCount; ++l) {
    ContactBody& c = contact_bodies_[object_count_ + l];
    c.X_GB = X_GL_[l];
    if (touching[static_cast<std::size_t>(l)]) {
      finite_difference(X_GL_before_[l], X_GL_[l], dt_s, c.v_G, c.w_G);
    } else {
      c.v_G.setZero();
      c.w_G.setZero();
    }
    c.material = &scene_.hand_material;
    c.dynamic = false;
    c.inv_mass = 0.0;
    c.mass_for_damping = 0.0;
  }
}

void World::integrate(double dt_s) {
  for (int i = 0; i < object_count_; ++i) {
    const ObjectSpec& o = scene_.objects[i];
    BodyState& body = bodies_[i];
    if (!o.dynamic || body.held_by != kNotHeld) continue;
    const Eigen::Vector3d F = total_force_G(F_G_[i], o.mass_kg, scene_.gravity_mps2);  // eq. 18
    integrate_body(body, F, M_G_[i], o.mass_kg, o.I_O, I_O_inv_[i], dt_s);
  }
}

void World::grasp_stage() {
  StageTimer timer(stage_times_, Stage::kGrasp);
  penetration_ = PenetrationStats{};
  if (!scene_.hand) return;
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
  record_held_history();
}

void World::grasp_object(int object, const HandContact* contacts, std::size_t count) {
  const ObjectSpec& o = scene_.objects[object];
  if (!o.dynamic) return;
  BodyState& body = bodies_[object];
  GraspState& g = grasp_[object];
  const bool held = body.held_by == hand_id_;
  if (!held && count == 0) return;

  const GraspCheck check = evaluate_grasp(contacts, count, body.X_GO.translation(), o.mass_kg,
                                          scene_.gravity_mps2, scene_.grasp, held);
  if (!held) {
    const bool cooled = time_ns_ - g.released_at_ns >=
                        std::llround(scene_.grasp.regrab_cooldown_s * 1e9);
    if (hand_to_.tracking && cooled && check.holds()) attach(object, check);
    return;
  }
  if (!hand_to_.tracking) {
    release(object, GraspReason::kGloveLost, check);
    return;
  }
  if (check.holds()) {
    g.failing_since_ns = -1;
    return;
  }
  if (g.failing_since_ns < 0) g.failing_since_ns = time_ns_;
  const bool failed_long_enough =
      time_ns_ - g.failing_since_ns >= std::llround(scene_.grasp.release_delay_s * 1e9);
  const bool held_long_enough =
      time_ns_ - g.held_since_ns >= std::llround(scene_.grasp.min_hold_s * 1e9);
  if (failed_long_enough && held_long_enough) release(object, check.verdict, check);
}

void World::attach(int object, const GraspCheck& check) {
  BodyState& body = bodies_[object];
  GraspState& g = grasp_[object];
  g.X_HO = X_GH_.inverse() * body.X_GO;  // eq. 28
  g.held_since_ns = time_ns_;
  g.failing_since_ns = -1;
  g.history_next = 0;
  g.history_count = 0;
  body.held_by = hand_id_;
  GraspEvent e;
  e.t_ns = time_ns_;
  e.grasp = true;
  e.hand_id = hand_id_;
  e.object = object;
  e.reason = GraspReason::kStableGrasp;
  e.contacts = check.links_in_contact;
  e.residual_force_N = check.residual_force_N;
  e.residual_torque_Nm = check.residual_torque_Nm;
  std::snprintf(e.text.data(), e.text.size(),
                "stable grasp: %d links, thumb opposed at %.0f deg, |F| %.2f N, |M| %.3f N m",
                check.links_in_contact, check.min_thumb_angle_deg, check.residual_force_N,
                check.residual_torque_Nm);
  events_.push_back(e);
}

void World::release(int object, GraspReason reason, const GraspCheck& check) {
  BodyState& body = bodies_[object];
  GraspState& g = grasp_[object];
  // the object leaves with the hand's motion over the last window (no jump, can be thrown)
  if (g.history_count >= 2) {
    const std::size_t n = g.history.size();
    const std::size_t newest = (g.history_next + n - 1) % n;
    const std::size_t oldest = g.history_count < n ? 0 : g.history_next;
    const std::size_t span = g.history_count < n ? g.history_count - 1 : n - 1;
    finite_difference(g.history[oldest], g.history[newest],
                      static_cast<double>(span) * scene_.step_s, body.v_G, body.w_G);
  }
  body.held_by = kNotHeld;
  g.released_at_ns = time_ns_;
  g.failing_since_ns = -1;
  GraspEvent e;
  e.t_ns = time_ns_;
  e.grasp = false;
  e.hand_id = hand_id_;
  e.object = object;
  e.reason = reason;
  e.contacts = check.links_in_contact;
  e.residual_force_N = check.residual_force_N;
  e.residual_torque_Nm = check.residual_torque_Nm;
  if (reason == GraspReason::kGloveLost) {
    std::snprintf(e.text.data(), e.text.size(), "glove lost");
  } else {
    std::snprintf(e.text.data(), e.text.size(),
                  "%s: %d links, thumb %s, min thumb angle %.0f deg, |F| %.2f N, |M| %.3f N m",
                  grasp_reason_name(reason), check.links_in_contact,
                  check.thumb ? "touching" : "off", check.min_thumb_angle_deg,
                  check.residual_force_N, check.residual_torque_Nm);
  }
  events_.push_back(e);
}

void World::record_held_history() {
  for (int i = 0; i < object_count_; ++i) {
    if (bodies_[i].held_by == kNotHeld) continue;
    GraspState& g = grasp_[i];
    g.history[g.history_next] = bodies_[i].X_GO;
    g.history_next = (g.history_next + 1) % g.history.size();
    g.history_count = std::min(g.history_count + 1, g.history.size());
  }
}

}  // namespace vcockpit::physics
