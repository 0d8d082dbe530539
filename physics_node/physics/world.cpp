#include "physics_node/physics/world.hpp"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <optional>
#include <stdexcept>

#include "common/assert.hpp"
#include "physics_node/physics/integrator.hpp"

namespace vcockpit::physics {
namespace {

// Adds the wall time of a scope to one stage (an observation; never feeds back into results),
// on the steps that are timed (StageTimes::timed).
class StageTimer {
 public:
  StageTimer(StageTimes& times, Stage stage)
      : slot_(times.timed ? &times.ns[static_cast<int>(stage)] : nullptr),
        start_(slot_ ? std::chrono::steady_clock::now() : std::chrono::steady_clock::time_point{}) {}
  ~StageTimer() {
    if (!slot_) return;
    *slot_ += std::chrono::duration_cast<std::chrono::nanoseconds>(
                  std::chrono::steady_clock::now() - start_)
                  .count();
  }

 private:
  int64_t* slot_;
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

// The first hand of a non-empty BodyState::holders.
int lowest_bit(uint8_t holders) { return std::countr_zero(holders); }

// Merges lists each sorted by (body_a, body_b), no pair in two of them, into `out` (cleared
// first): the order one sorted list split in parts had.
void merge_by_pair(const std::vector<const std::vector<ContactPoint>*>& lists,
                   std::vector<ContactPoint>& out) {
  out.clear();
  std::array<std::size_t, kMaxHands + 1> at{};
  VCOCKPIT_ASSERT(lists.size() <= at.size(), "a list per hand and one more");
  for (;;) {
    std::size_t best = lists.size();
    for (std::size_t k = 0; k < lists.size(); ++k) {
      if (at[k] >= lists[k]->size()) continue;
      const ContactPoint& c = (*lists[k])[at[k]];
      if (best == lists.size()) {
        best = k;
        continue;
      }
      const ContactPoint& b = (*lists[best])[at[best]];
      if (c.body_a < b.body_a || (c.body_a == b.body_a && c.body_b < b.body_b)) best = k;
    }
    if (best == lists.size()) return;
    out.push_back((*lists[best])[at[best]++]);
  }
}

}  // namespace

const char* stage_name(Stage stage) {
  static constexpr const char* kNames[] = {"proxy_goal", "hand_kinematics", "broadphase",
                                           "narrowphase", "proxy_hand", "forces", "integrate",
                                           "body_check", "grasp"};
  static_assert(std::size(kNames) == kStageCount, "a name per stage");
  return kNames[static_cast<int>(stage)];
}

World::World(Scene scene)
    : scene_(std::move(scene)),
      collision_(scene_),
      soft_(SoftSolverParams{scene_.contact.iterations, scene_.contact.relax_iterations,
                             scene_.contact.restitution_threshold_mps, scene_.contact.slip_speed_mps}),
      grasp_tracker_(scene_.grasp, scene_.step_s, scene_.gravity_mps2, scene_.hand_material.mu_s),
      body_check_(scene_),
      sleep_(scene_),
      object_count_(static_cast<int>(scene_.objects.size())),
      step_ns_(std::llround(scene_.step_s * 1e9)),
      controls_(scene_, state_) {
  if (!(scene_.step_s > 0.0)) throw std::invalid_argument("World: the step must be positive");
  const std::size_t hand_count = scene_.hands.size();
  if (hand_count > kMaxHands) throw std::invalid_argument("World: more hands than kMaxHands");
  for (std::size_t a = 0; a < hand_count; ++a)
    for (std::size_t b = a + 1; b < hand_count; ++b)
      if (hand_id_of(scene_.hands[a]) == hand_id_of(scene_.hands[b]))
        throw std::invalid_argument("World: two hands of the same side (one right, one left)");
  state_.bodies.resize(object_count_);
  X_GO_.resize(object_count_);
  I_O_inv_.resize(object_count_);
  held_mask_.assign(object_count_, 0);
  may_sleep_.assign(object_count_, 0);
  start_bodies_.resize(object_count_);
  hands_.resize(hand_count);  // never again: each proxy keeps a pointer to its hand's vectors
  state_.hands.resize(hand_count);
  on_object_.resize(hand_count);
  for (std::size_t h = 0; h < hand_count; ++h) {
    HandSim& sim = hands_[h];
    HandState& hs = state_.hands[h];
    sim.hand_id = hand_id_of(scene_.hands[h]);
    sim.fk.emplace(scene_.hands[h]);
    sim.holder_bit = static_cast<uint8_t>(1u << h);
    sim.held_mask.assign(object_count_, 0);
    sim.resting_links.assign(object_count_, 0);
    if (scene_.proxy.enabled) {
      sim.proxy.emplace(scene_, static_cast<int>(h));
      sim.proxy->set_resting_links(&sim.resting_links);
    }
    hs.blocking_out_G.reserve(kMaxBlockingPlanes);
    hs.grasp.resize(object_count_);
    hs.X_GL.fill(Eigen::Isometry3d::Identity());
    sim.X_GL_before = hs.X_GL;
    sim.tracked_X_GL = hs.X_GL;
    sim.contacts.reserve(256);
    sim.hand_static.reserve(64);
    sim.on_object.reserve(64);
  }
  for (int i = 0; i < object_count_; ++i) {
    const ObjectSpec& o = scene_.objects[i];
    state_.bodies[i].X_GO = o.X_GO;
    state_.bodies[i].v_G = o.v_G;
    state_.bodies[i].w_G = o.w_G;
    X_GO_[i] = o.X_GO;
    for (HandState& hs : state_.hands) hs.grasp[i] = grasp_tracker_.initial_hold(o);
    I_O_inv_[i] = o.dynamic ? Eigen::Matrix3d(o.I_O.inverse()) : Eigen::Matrix3d::Zero();
  }
  controls_.start();
  for (const ControlSpec& c : scene_.controls) {
    X_GO_[c.body] = state_.bodies[c.body].X_GO;
  }
  const int body_count = object_count_ + static_cast<int>(hand_count) * kLinkCount;
  contact_bodies_.resize(body_count);
  contacts_.reserve(256);
  merged_.reserve(256);
  applied_.reserve(256);
  events_.reserve(16);
  state_.anchors.reserve(256);
  joints_.reserve(scene_.controls.size());
}

World::~World() = default;

int World::hand_index(int hand_id) const {
  for (std::size_t h = 0; h < hands_.size(); ++h)
    if (hands_[h].hand_id == hand_id) return static_cast<int>(h);
  return -1;
}

int World::holder_of(const BodyState& body) const {
  return body.held() ? lowest_bit(body.holders) : -1;
}

// Where each proxy heads over the coming step: from where it is towards the latest input, never
// farther than its speeds allow (ProxyHand::step_goal).
void World::aim_proxies(bool holding) {
  for (std::size_t h = 0; h < hands_.size(); ++h) {
    HandSim& sim = hands_[h];
    const HandState& hs = state_.hands[h];
    if (!hs.active || !sim.proxy) continue;
    const bool this_holds = holding && sim.holds_any;
    // (the tracked hand where the fingers the world holds back pull it: finger_pull_G)
    HandInput from = hs.from;
    HandInput to = hs.to;
    from.X_GH.translation() += hs.finger_pull_G;
    to.X_GH.translation() += hs.finger_pull_G;
    sim.proxy_goal = sim.proxy->step_goal({hs.X_GH, hs.q_rad}, from, to, hs.pushing, this_holds,
                                          hs.blocking_out_G, scene_.step_s, *sim.fk);
  }
}

Eigen::Vector3d World::finger_pull_G(int hand) const {
  const HandSim& sim = hands_[static_cast<std::size_t>(hand)];
  const HandState& hs = hand_state(hand);
  const double ratio = scene_.proxy.finger_pull_ratio;
  // (a lost glove's hand stays where it was: no pull on its last, stale shape)
  if (!sim.proxy || !hs.active || !hs.to.tracking || ratio <= 0.0) return Eigen::Vector3d::Zero();
  // A hand that holds something keeps the pull it grasped with, turning with the wrist: the grip
  // it centred stays centred. Dropped at the grasp, it would shift the hand and what it holds by
  // up to kMaxFingerPull_m in one step (a lever a few degrees).
  for (int i = 0; i < object_count_; ++i)
    if ((state_.bodies[static_cast<std::size_t>(i)].holders & sim.holder_bit) != 0)
      return hs.to.X_GH.linear() * hs.from.X_GH.linear().transpose() * hs.finger_pull_G;
  // Each finger link's deepest shortfall on an object that holds it back and no hand holds
  // (ProxyHand::holds_fingers_back): how much farther into it the tracked link goes than the
  // proxy's, along the contact normal
  const int link_base = object_count_ + hand * kLinkCount;
  std::array<double, kLinkCount> short_m{};
  std::array<Eigen::Vector3d, kLinkCount> n_G{};
  bool observed = false;
  for (const ContactPoint& c : sim.contacts) {
    if (c.body_a >= object_count_ || c.body_b < link_base || c.body_b >= link_base + kLinkCount)
      continue;
    if (state_.bodies[static_cast<std::size_t>(c.body_a)].holders != 0 ||
        !sim.proxy->holds_fingers_back(c.body_a))
      continue;
    const auto l = static_cast<std::size_t>(c.body_b - link_base);
    Finger finger;
    if (!finger_of(static_cast<Link>(l), finger)) continue;  // the palm is the wrist's own
    if (!observed) observe_tracked_hand(hand);
    observed = true;
    // n points from the object into the link: the tracked point lies deeper along -n
    const Eigen::Vector3d p_tracked_G = sim.tracked_X_GL[l] * (hs.X_GL[l].inverse() * c.p_G);
    const double short_by_m = c.n_G.dot(c.p_G - p_tracked_G);
    if (short_by_m > short_m[l]) {
      short_m[l] = short_by_m;
      n_G[l] = c.n_G;
    }
  }
  if (!observed) return Eigen::Vector3d::Zero();
  // The wrist's offset s where its spring balances the fingers' (each r times as stiff), each
  // finger's shortfall shrinking by s along its normal as the wrist gives:
  // s = r sum_l (u_l - n_l.s) n_l, i.e. (I + r sum n n^T) s = r sum u_l n_l.
  Eigen::Matrix3d A = Eigen::Matrix3d::Identity();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  for (std::size_t l = 0; l < kLinkCount; ++l) {
    if (short_m[l] <= 0.0) continue;
    A += ratio * n_G[l] * n_G[l].transpose();
    b += ratio * short_m[l] * n_G[l];
  }
  Eigen::Vector3d s = A.ldlt().solve(b);  // A is symmetric positive definite
  const double s_m = s.norm();
  if (s_m > kMaxFingerPull_m) s *= kMaxFingerPull_m / s_m;
  return s;
}

void World::restore(const WorldState& state) {
  VCOCKPIT_ASSERT(state.bodies.size() == state_.bodies.size() &&
                      state.controls.size() == state_.controls.size() &&
                      state.hands.size() == state_.hands.size(),
                  "a world state of another scene (object, control or hand count)");
  for (std::size_t h = 0; h < state.hands.size(); ++h) {
    VCOCKPIT_ASSERT(state.hands[h].grasp.size() == state_.hands[h].grasp.size(),
                    "a world state of another scene (object count)");
    for (int i = 0; i < object_count_; ++i)
      VCOCKPIT_ASSERT(state.hands[h].grasp[i].history.size() == state_.hands[h].grasp[i].history.size(),
                      "a world state of another scene (grasp velocity window)");
  }
  state_ = state;
  for (HandSim& sim : hands_) {
    sim.proxy_prev_links_valid = false;
    sim.tracked_observed = false;
  }
  count_passing_through();
  // the last step's observations belong to the world the state came from
  applied_.clear();
  events_.clear();
  controls_.forget_step();
  stage_times_ = StageTimes{};
  penetration_ = PenetrationStats{};
  body_check_.clear_new_faults();
}

void World::reset_objects(const WorldState& saved) {
  VCOCKPIT_ASSERT(saved.bodies.size() == state_.bodies.size() &&
                      saved.controls.size() == state_.controls.size(),
                  "a world state of another scene (object or control count)");
  events_.clear();
  applied_.clear();
  const int64_t t_ns = state_.time_ns;
  for (std::size_t h = 0; h < hands_.size(); ++h) {
    HandState& hs = state_.hands[h];
    for (int i = 0; i < object_count_; ++i) {
      if ((state_.bodies[static_cast<std::size_t>(i)].holders & hands_[h].holder_bit) != 0) {
        GraspEvent e;
        e.t_ns = t_ns;
        e.grasp = false;
        e.hand_id = hands_[h].hand_id;
        e.object = i;
        e.reason = GraspReason::kReset;
        events_.push_back(e);
      }
      // a fresh hold: no cooldown, no resting links (the object is somewhere else now)
      hs.grasp[static_cast<std::size_t>(i)] = grasp_tracker_.initial_hold(scene_.objects[static_cast<std::size_t>(i)]);
    }
    hs.pushing = false;
    hs.finger_pull_G.setZero();  // (what pulled it is elsewhere now)
    hands_[h].proxy_prev_links_valid = false;
  }
  state_.bodies = saved.bodies;
  for (BodyState& body : state_.bodies) {
    body.holders = 0;
    body.held_by = kNotHeld;
  }
  SleepTracker::wake_all(state_.bodies);  // (put back, they rest on nothing computed yet)
  controls_.reset_to(saved.controls, t_ns);
  state_.anchors.clear();
  // an object put back round a hand that stands where it was is not flung off it: those links
  // pass through it until they are out, as a hand's that appears inside one
  for (int i = 0; i < object_count_; ++i) X_GO_[i] = state_.bodies[static_cast<std::size_t>(i)].X_GO;
  collision_.set_object_poses(X_GO_);
  for (int h = 0; h < hand_count(); ++h)
    if (hand_state(h).active) note_objects_around(h);
  count_passing_through();
}

void World::set_hand_input(const HandInput& input, int hand) {
  if (hand < 0 || hand >= hand_count()) return;
  HandSim& sim = hands_[static_cast<std::size_t>(hand)];
  HandState& hs = state_.hands[static_cast<std::size_t>(hand)];
  hs.to = input;
  // the tracked hand is this input's from now on: one observed before (a read between steps, as
  // the physics node publishes) must not reach the step
  sim.tracked_observed = false;
  if (!hs.active) {
    hs.from = input;  // first sample: no sweep from nowhere
    hs.active = true;
    place_hand(hand, input.X_GH, input.q_rad);
    sim.X_GL_before = hs.X_GL;
    sim.proxy_prev_links_valid = false;
    note_objects_around(hand);
    count_passing_through();
  }
}

void World::note_objects_around(int hand) {
  HandState& hs = state_.hands[static_cast<std::size_t>(hand)];
  for (int i = 0; i < object_count_; ++i) {
    const ObjectSpec& o = scene_.objects[static_cast<std::size_t>(i)];
    bool inside = false;
    if (o.dynamic || o.control >= 0)
      for (int l = 0; l < kLinkCount && !inside; ++l)
        inside = collision_.link_overlaps(hand, static_cast<Link>(l), hs.X_GL[l], i);
    hs.grasp[static_cast<std::size_t>(i)].passing_through = inside;
  }
}

void World::count_passing_through() {
  passing_through_ = 0;
  for (const HandState& hs : state_.hands)
    for (const GraspHold& hold : hs.grasp) passing_through_ += hold.passing_through ? 1 : 0;
}

void World::pass_through() {
  if (passing_through_ == 0) return;  // (the usual step: no scan of every hold)
  deepest_in_.assign(state_.hands.size() * static_cast<std::size_t>(object_count_), -1.0);
  const auto at = [&](std::size_t h, std::size_t o) { return h * static_cast<std::size_t>(object_count_) + o; };
  const auto passing_pair = [&](const ContactPoint& c, std::size_t& index) {
    if (!collision_.is_hand_body(c.body_b) || collision_.is_hand_body(c.body_a)) return false;
    const auto h = static_cast<std::size_t>(collision_.hand_of_body(c.body_b));
    const auto o = static_cast<std::size_t>(c.body_a);
    index = at(h, o);
    return state_.hands[h].grasp[o].passing_through;
  };
  std::size_t index = 0;
  for (const ContactPoint& c : contacts_)
    if (passing_pair(c, index)) deepest_in_[index] = std::max(deepest_in_[index], c.depth_m);
  for (std::size_t h = 0; h < state_.hands.size(); ++h)
    for (std::size_t o = 0; o < static_cast<std::size_t>(object_count_); ++o)
      if (deepest_in_[at(h, o)] <= scene_.proxy.pass_through_depth_m)
        state_.hands[h].grasp[o].passing_through = false;
  std::erase_if(contacts_, [&](const ContactPoint& c) { return passing_pair(c, index); });
  count_passing_through();
}

void World::step() {
  stage_times_ = StageTimes{};
  stage_times_.timed = state_.steps % static_cast<uint64_t>(stage_timing_every_) == 0;
  events_.clear();
  controls_.begin_step();
  body_check_.clear_new_faults();
  std::copy(state_.bodies.begin(), state_.bodies.end(), start_bodies_.begin());
  tell_sleepers();
  bool any_held = false;
  for (HandSim& sim : hands_) {
    sim.holds_any = false;
    sim.tracked_observed = false;  // observed in this step, never before it
  }
  for (int i = 0; i < object_count_; ++i) {
    const BodyState& body = state_.bodies[i];
    held_mask_[i] = body.held() ? 1 : 0;
    any_held = any_held || held_mask_[i] != 0;
    for (std::size_t h = 0; h < hands_.size(); ++h) {
      hands_[h].held_mask[i] = (body.holders & hands_[h].holder_bit) != 0 ? 1 : 0;
      hands_[h].holds_any = hands_[h].holds_any || hands_[h].held_mask[i] != 0;
      hands_[h].resting_links[i] = state_.hands[h].grasp[i].resting_links;
    }
  }
  {
    StageTimer timer(stage_times_, Stage::kProxyGoal);
    aim_proxies(any_held);
  }
  for (std::size_t h = 0; h < hands_.size(); ++h) {
    HandSim& sim = hands_[h];
    const HandState& hs = state_.hands[h];
    if (sim.proxy && hs.active && !sim.proxy_prev_links_valid) {
      forward_kinematics(scene_.hands[h], hs.q_rad, sim.proxy_prev_links);
      sim.proxy_prev_links_valid = true;
    }
  }
  advance(scene_.step_s);
  // a held object's velocity is the hand's over the step (a held control's too: its joint moved it)
  for (int i = 0; i < object_count_; ++i) {
    BodyState& body = state_.bodies[i];
    if (held_mask_[i] == 0 || !body.held()) continue;
    finite_difference_velocity(start_bodies_[i].X_GO, body.X_GO, scene_.step_s, body.v_G, body.w_G);
  }
  state_.time_ns += step_ns_;
  ++state_.steps;
  {
    StageTimer timer(stage_times_, Stage::kBodyCheck);
    body_check_.check(state_.bodies, start_bodies_, state_.time_ns);
    if (body_check_.any_recovered()) forget_anchors_of_recovered_bodies();
  }
  grasp_stage();
  if (scene_.sleep.enabled) update_sleep();
  for (std::size_t h = 0; h < hands_.size(); ++h)
    state_.hands[h].finger_pull_G = finger_pull_G(static_cast<int>(h));
  for (std::size_t h = 0; h < hands_.size(); ++h) {
    hands_[h].tracked_observed = false;
    state_.hands[h].from = state_.hands[h].to;
  }
  if (stage_times_.timed)  // this step stands for the ones up to the next timed one
    for (int64_t& ns : stage_times_.ns) ns *= stage_timing_every_;
}

void World::set_stage_timing_every(int steps) {
  VCOCKPIT_ASSERT(steps >= 1, "stage timing needs a step count of at least 1");
  stage_timing_every_ = steps;
}

// One step of dt_s: the contacts are soft constraints (contact_solver.hpp), stable at the full
// step, so one collision and one solve a step.
void World::advance(double dt_s) {
  {
    StageTimer timer(stage_times_, Stage::kHandKinematics);
    for (int h = 0; h < hand_count(); ++h)
      if (hand_state(h).active) move_hand(h);
    move_held_objects(dt_s);
  }
  {
    StageTimer timer(stage_times_, Stage::kBroadphase);
    for (int i = 0; i < object_count_; ++i) X_GO_[i] = state_.bodies[i].X_GO;
    collision_.set_object_poses(X_GO_);
    for (int h = 0; h < hand_count(); ++h)
      collision_.set_hand_poses(h, hand_state(h).active ? &hand_state(h).X_GL : nullptr);
    collision_.find_candidate_pairs();
  }
  {
    StageTimer timer(stage_times_, Stage::kNarrowphase);
    collision_.compute_contacts(contacts_, has_proxy() ? &hand_static_ : nullptr);
  }
  // something that moves touched a sleeping island: it wakes, and this step's collision is
  // found again with it awake (its contacts with what it rests on)
  while (wake_touched()) {
    {
      StageTimer timer(stage_times_, Stage::kBroadphase);
      tell_sleepers();
      collision_.find_candidate_pairs();
    }
    StageTimer timer(stage_times_, Stage::kNarrowphase);
    collision_.compute_contacts(contacts_, has_proxy() ? &hand_static_ : nullptr);
  }
  pass_through();
  if (has_proxy()) {
    StageTimer timer(stage_times_, Stage::kProxyHand);
    constrain_proxies(dt_s);
  }
  {
    StageTimer timer(stage_times_, Stage::kForces);
    build_contact_bodies();
    if (!controls_.empty()) controls_.solver_joints(contacts_, dt_s, joints_);
    soft_.solve(contacts_, contact_bodies_, joints_, scene_.gravity_mps2, dt_s, applied_,
                state_.anchors, touched_);
    if (!controls_.empty()) controls_.find_pushers(applied_, collision_);
  }
  StageTimer timer(stage_times_, Stage::kIntegrate);
  integrate(dt_s);
  if (!controls_.empty()) controls_.integrate(joints_, dt_s);
}

// The hand where this step takes it: the proxy's goal (constrain_proxy then holds it back), or
// the tracked hand itself.
void World::move_hand(int hand) {
  HandSim& sim = hands_[static_cast<std::size_t>(hand)];
  const HandState& hs = hand_state(hand);
  sim.X_GL_before = hs.X_GL;
  if (sim.proxy) {
    sim.proxy_prev = {hs.X_GH, hs.q_rad};
    place_hand(hand, sim.proxy_goal.X_GH, sim.proxy_goal.q_rad);
    return;
  }
  place_hand(hand, hs.to.X_GH, hs.to.q_rad);
}

void World::place_hand(int hand, const Eigen::Isometry3d& X_GH, const JointAngles& q_rad) {
  HandSim& sim = hands_[static_cast<std::size_t>(hand)];
  HandState& hs = state_.hands[static_cast<std::size_t>(hand)];
  hs.X_GH = X_GH;
  hs.q_rad = q_rad;
  sim.fk->solve(q_rad, sim.link_poses);
  for (int l = 0; l < kLinkCount; ++l) hs.X_GL[l] = hs.X_GH * sim.link_poses.X_HL[l];
}

// Each active proxy takes its share of the contacts: its own links' (never another hand's) and
// those of the objects it alone or first holds (which move with it), constrains them, and the
// shares go back into one list in the order the narrowphase gave.
void World::constrain_proxies(double dt_s) {
  for (HandSim& sim : hands_) {
    sim.contacts.clear();
    sim.hand_static.clear();
  }
  const auto proxied = [&](int hand) {
    return hands_[static_cast<std::size_t>(hand)].proxy.has_value() && hand_state(hand).active;
  };
  bool any = false;
  for (int h = 0; h < hand_count(); ++h) any = any || proxied(h);
  if (!any) return;
  for (const ContactPoint& c : hand_static_) {
    const int h = collision_.hand_of_body(c.body_b);
    if (proxied(h)) hands_[static_cast<std::size_t>(h)].hand_static.push_back(c);
  }
  merged_.clear();  // first the contacts no proxy takes
  for (const ContactPoint& c : contacts_) {
    // a hand link is always body_b (links come after the objects); an object pair goes to the
    // first hand holding one of its objects (held objects move with their hand's proxy)
    int owner = -1;
    if (collision_.is_hand_body(c.body_b)) {
      owner = collision_.hand_of_body(c.body_b);
    } else {
      for (const int body : {c.body_a, c.body_b})
        if (owner < 0) owner = holder_of(state_.bodies[static_cast<std::size_t>(body)]);
    }
    if (owner >= 0 && proxied(owner))
      hands_[static_cast<std::size_t>(owner)].contacts.push_back(c);
    else
      merged_.push_back(c);
  }
  for (int h = 0; h < hand_count(); ++h)
    if (proxied(h)) constrain_proxy(h, dt_s);
  merge_lists_.clear();
  merge_lists_.push_back(&merged_);
  for (const HandSim& sim : hands_) merge_lists_.push_back(&sim.contacts);
  merge_by_pair(merge_lists_, contacts_);
}

void World::constrain_proxy(int hand, double dt_s) {
  HandSim& sim = hands_[static_cast<std::size_t>(hand)];
  HandState& hs = state_.hands[static_cast<std::size_t>(hand)];
  ProxyPose pose{hs.X_GH, hs.q_rad};
  // the fingers see every held object as held (it does not give: a grip on it is balanced, and
  // they close on it at the grip speed, whichever hand holds it); the wrist's shift carries only
  // the objects this hand holds
  const bool fingers_moved =
      sim.proxy->constrain_fingers(sim.proxy_prev, sim.proxy_prev_links, pose, sim.link_poses, hs.X_GL,
                                   held_mask_, sim.contacts, sim.hand_static, dt_s);
  // the links' static contacts afresh: the wrist's shift must see exactly how deep they are
  if (fingers_moved) collision_.compute_hand_static_contacts(hand, hs.X_GL, sim.hand_static);
  const ProxyConstraint r = sim.proxy->constrain_wrist(pose, hs.X_GL, sim.held_mask, sim.contacts,
                                                       sim.hand_static, hs.blocking_out_G);
  hs.X_GH = pose.X_GH;
  hs.q_rad = pose.q_rad;
  if (fingers_moved) sim.fk->remember(hs.q_rad, sim.link_poses);  // (the next step starts here)
  hs.pushing = r.pushing;
  sim.proxy_prev_links = sim.link_poses;
  if (r.shift_G.squaredNorm() == 0.0) return;
  // the held objects move with the proxy (eq. 29; one held with both hands, halfway)
  for (int i = 0; i < object_count_; ++i) {
    BodyState& body = state_.bodies[i];
    if ((body.holders & sim.holder_bit) == 0 || scene_.objects[i].control >= 0) continue;  // a joint holds a control
    body.X_GO.translation() += r.shift_G / std::popcount(body.holders);
    finite_difference_velocity(start_bodies_[i].X_GO, body.X_GO, dt_s, body.v_G, body.w_G);
  }
}

uint32_t World::glove_links_inside(int hand, int object, const GraspHold& hold) const {
  const HandSim& sim = hands_[static_cast<std::size_t>(hand)];
  if (!sim.proxy || !hand_state(hand).active || !hold.hand_clearing) return 0;
  observe_tracked_hand(hand);
  uint32_t inside = 0;
  for (int l = 0; l < kLinkCount; ++l)
    if (collision_.link_overlaps(hand, static_cast<Link>(l), sim.tracked_X_GL[l], object))
      inside |= 1u << l;
  return inside;
}

void World::note_grip_gaps(int hand, int object, GraspHold& hold) const {
  const HandSim& sim = hands_[static_cast<std::size_t>(hand)];
  const HandState& hs = hand_state(hand);
  hold.grip_gap_m.fill(0.0);
  if (!hs.active) return;
  observe_tracked_hand(hand);
  const Eigen::Isometry3d X_HT = sim.proxy ? hs.X_GH * hs.to.X_GH.inverse() : Eigen::Isometry3d::Identity();
  for (int l = 0; l < kLinkCount; ++l) {
    const Eigen::Isometry3d X_GL = sim.proxy ? X_HT * sim.tracked_X_GL[l] : hs.X_GL[l];
    // (at most one gap more: a link that far off at the grasp was not gripping)
    hold.grip_gap_m[static_cast<std::size_t>(l)] =
        std::min(collision_.link_gap_m(hand, static_cast<Link>(l), X_GL, object), scene_.grasp.release_gap_m);
  }
}

uint32_t World::tracked_links_near(int hand, int object, const GraspHold& hold) const {
  const HandSim& sim = hands_[static_cast<std::size_t>(hand)];
  const HandState& hs = hand_state(hand);
  observe_tracked_hand(hand);
  // the tracked hand's shape on the proxy's wrist: X_GH X_GT^-1 X_GL(tracked)
  const Eigen::Isometry3d X_HT = sim.proxy ? hs.X_GH * hs.to.X_GH.inverse() : Eigen::Isometry3d::Identity();
  // A held control moves only along its joint, and only as fast as the proxy's wrist: a wrist
  // catching up (after a tracking gap) turns and shifts on its own path, not round the joint,
  // and takes the tracked fingers posed on it off a handle or knob they still hold. So a link
  // also counts where the tracked hand is, against the control as that hand would move it: the
  // link carried back by the joint motion the control has yet to make (X_back, from the control
  // at the tracked hand's coordinate to the control now). A hand pulled off the control, or
  // past an end stop or a closed gate, is off it both ways. (For a round knob on its own axis
  // the carrying back changes no distance; for a lever's handle it does.)
  const int control = scene_.objects[static_cast<std::size_t>(object)].control;
  // each link's gap counted from where it gripped (GraspHold::grip_gap_m)
  const auto gap_m = [&](int link) {
    return scene_.grasp.release_gap_m + hold.grip_gap_m[static_cast<std::size_t>(link)];
  };
  std::optional<Eigen::Isometry3d> X_back;  // (worked out the first time a link needs it)
  const auto carried_back = [&]() -> const Eigen::Isometry3d& {
    if (!X_back) {
      const double q_tracked = controls_.held_q(control, hs.to.X_GH, X_HO(object, hand).translation());
      X_back = joint_motion_G(scene_.controls[static_cast<std::size_t>(control)], q_tracked,
                              state_.controls[static_cast<std::size_t>(control)].q);
    }
    return *X_back;
  };
  const auto near = [&](Link l) {
    const int i = static_cast<int>(l);
    const Eigen::Isometry3d X_GL = sim.proxy ? X_HT * sim.tracked_X_GL[i] : hs.X_GL[i];
    if (collision_.link_within(hand, l, X_GL, object, gap_m(i))) return true;
    return sim.proxy && control >= 0 &&
           collision_.link_within(hand, l, carried_back() * sim.tracked_X_GL[i], object, gap_m(i));
  };
  const auto bit = [](Link l) { return 1u << static_cast<int>(l); };
  // a finger's links from its tip in: the tip is the one nearest an object it grips
  const auto first_near = [&](Finger f) -> uint32_t {
    const auto links = finger_links(f);
    for (auto it = links.rbegin(); it != links.rend(); ++it)
      if (near(*it)) return bit(*it);
    return 0u;
  };
  uint32_t found = hold.palm_opposed ? (near(Link::kPalm) ? bit(Link::kPalm) : 0u)
                                     : first_near(Finger::kThumb);
  for (int f = 1; f < kFingerCount; ++f) {
    if ((hold.opposed_fingers & (1u << f)) == 0) continue;
    const uint32_t hit = first_near(static_cast<Finger>(f));
    found |= hit;
    if (hit != 0) break;
  }
  return found;
}

void World::observe_tracked_hand(int hand) const {
  const HandSim& sim = hands_[static_cast<std::size_t>(hand)];
  const HandState& hs = hand_state(hand);
  if (sim.tracked_observed) return;
  sim.tracked_observed = true;
  sim.tracked_offset_m = 0.0;
  if (!sim.proxy || !hs.active) return;
  HandLinkPoses tracked;
  sim.fk->solve(hs.to.q_rad, tracked);
  const Eigen::Isometry3d& X_GT = hs.to.X_GH;
  double offset_m = 0.0;
  for (int l = 0; l < kLinkCount; ++l) {
    sim.tracked_X_GL[l] = X_GT * tracked.X_HL[l];
    offset_m = std::max(offset_m, (sim.tracked_X_GL[l].translation() - hs.X_GL[l].translation()).norm());
  }
  for (int f = 0; f < kFingerCount; ++f)
    offset_m = std::max(offset_m, (X_GT * tracked.p_H_tip[f] - hs.X_GH * sim.link_poses.p_H_tip[f]).norm());
  sim.tracked_offset_m = offset_m;
}

Eigen::Isometry3d World::held_pose(int object) const {
  const BodyState& body = state_.bodies[static_cast<std::size_t>(object)];
  const int a = lowest_bit(body.holders);
  const Eigen::Isometry3d X_a = hand_state(a).X_GH * X_HO(object, a);  // eq. 29
  const auto rest = static_cast<uint8_t>(body.holders & ~(1u << a));
  if (rest == 0) return X_a;
  const int b = lowest_bit(rest);
  return interpolate(X_a, hand_state(b).X_GH * X_HO(object, b), 0.5);  // halfway: mean, slerp 0.5
}

void World::move_held_objects(double dt_s) {
  for (int i = 0; i < object_count_; ++i) {
    BodyState& body = state_.bodies[i];
    if (!body.held()) continue;
    if (const int control = scene_.objects[i].control; control >= 0) {
      // eq. 29 restricted to the joint
      const int hand = holder_of(body);
      controls_.move_held(control, hand, hand_state(hand).X_GH, X_HO(i, hand).translation(), dt_s);
      continue;
    }
    body.X_GO = held_pose(i);
    finite_difference_velocity(start_bodies_[i].X_GO, body.X_GO, dt_s, body.v_G, body.w_G);
  }
}

void World::forget_anchors_of_recovered_bodies() {
  // a broken body's contacts solved with its broken state: their impulses (a NaN, or a runaway's
  // absurd push) must not warm-start the next step
  const auto broken = [&](int body) { return body < object_count_ && body_check_.recovered(body); };
  std::erase_if(state_.anchors, [&](const StickAnchor& a) { return broken(a.body_a) || broken(a.body_b); });
}

void World::build_contact_bodies() {
  for (int i = 0; i < object_count_; ++i) {
    const ObjectSpec& o = scene_.objects[i];
    const BodyState& s = state_.bodies[i];
    if (s.asleep) continue;  // in no contact
    ContactBody& c = contact_bodies_[i];
    c.X_GB = s.X_GO;
    c.v_G = s.v_G;
    c.w_G = s.w_G;
    c.material = &o.material;
    c.dynamic = o.dynamic && !s.held();
    c.inv_mass = c.dynamic ? 1.0 / o.mass_kg : 0.0;
    c.mass_for_damping = c.dynamic ? o.mass_kg : 0.0;
    c.inv_I_O = c.dynamic ? I_O_inv_[i] : Eigen::Matrix3d::Zero();
  }
  const double dt_s = scene_.step_s;
  for (int h = 0; h < hand_count(); ++h) {
    const HandSim& sim = hands_[static_cast<std::size_t>(h)];
    const HandState& hs = hand_state(h);
    const int first = collision_.hand_link_body(h, Link::kPalm);
    // a link's velocity only where it touches something (the rotation's log is not free)
    std::array<bool, kLinkCount> touching{};
    std::array<bool, kLinkCount> touching_free{};
    for (const ContactPoint& c : contacts_) {
      if (c.body_b < first || c.body_b >= first + kLinkCount) continue;
      const auto l = static_cast<std::size_t>(c.body_b - first);
      touching[l] = true;
      if (c.body_a < object_count_ && contact_bodies_[c.body_a].dynamic) touching_free[l] = true;
    }
    for (int l = 0; l < kLinkCount; ++l) {
      ContactBody& c = contact_bodies_[first + l];
      c.X_GB = hs.X_GL[l];
      if (touching[static_cast<std::size_t>(l)]) {
        finite_difference_velocity(sim.X_GL_before[l], hs.X_GL[l], dt_s, c.v_G, c.w_G);
        // a proxy link pushes a free object no faster than push_speed_mps, however fast the
        // tracked hand (or a 30 Hz glove's jump) moved it: its speed feeds the contact damping
        if (sim.proxy && touching_free[static_cast<std::size_t>(l)])
          limit_link_speed(scene_.hands[static_cast<std::size_t>(h)].capsules[static_cast<std::size_t>(l)].length_m,
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
}

// Positions from the solver's velocities; a body in no contact falls freely (or spins: the top).
void World::integrate(double dt_s) {
  for (int i = 0; i < object_count_; ++i) {
    const ObjectSpec& o = scene_.objects[i];
    BodyState& body = state_.bodies[i];
    if (!o.dynamic || body.held() || o.control >= 0 || body.asleep) continue;
    if (touched_[static_cast<std::size_t>(i)] != 0) {
      const ContactBody& c = contact_bodies_[i];
      integrate_position(body, c.v_G, c.w_G, soft_.v_end(i), soft_.w_end(i), o.I_O, dt_s);
    } else {
      const Eigen::Vector3d F = o.mass_kg * scene_.gravity_mps2;  // eq. 18 with no contact
      integrate_body(body, F, Eigen::Vector3d::Zero(), o.mass_kg, o.I_O, I_O_inv_[i], dt_s);
    }
  }
}

bool World::command_control(int control, int position) {
  return controls_.command(control, position);
}

void World::grasp_stage() {
  StageTimer timer(stage_times_, Stage::kGrasp);
  penetration_ = PenetrationStats{};
  if (hands_.empty()) return;
  for (std::size_t h = 0; h < hands_.size(); ++h) {
    const HandSim& sim = hands_[h];
    HandState& hs = state_.hands[h];
    on_object_[h].hand = {state_.time_ns, hs.to.tracking, hs.X_GH, &hs.to.q_rad, sim.hand_id,
                          sim.holder_bit};
  }
  const auto grasp_object = [&](int object) {
    const ObjectSpec& o = scene_.objects[object];
    // (a sleeping object has no hand on it, and every hand's hold of it is idle: update_sleep)
    if (!o.dynamic || state_.bodies[object].asleep) return;
    for (std::size_t h = 0; h < hands_.size(); ++h) {
      HandOnObject& on = on_object_[h];
      GraspHold& hold = state_.hands[h].grasp[static_cast<std::size_t>(object)];
      on.contacts = hands_[h].on_object.data();
      on.count = hands_[h].on_object.size();
      on.hold = &hold;
      on.glove_links_inside = glove_links_inside(static_cast<int>(h), object, hold);
      on.grip_known = scene_.grasp.hold_rule == HoldRule::kTrackedGrip && state_.hands[h].active &&
                      (state_.bodies[object].holders & hands_[h].holder_bit) != 0;
      on.tracked_links_near = on.grip_known ? tracked_links_near(static_cast<int>(h), object, hold) : 0u;
    }
    const std::size_t events_before = events_.size();
    grasp_tracker_.update_hands(object, o, on_object_.data(), on_object_.size(), state_.bodies[object],
                                events_, controls_.grasp_joint_of(object));
    for (std::size_t e = events_before; e < events_.size(); ++e) {
      if (!events_[e].grasp || events_[e].object != object) continue;
      const int h = hand_index(events_[e].hand_id);
      if (h >= 0) note_grip_gaps(h, object, state_.hands[static_cast<std::size_t>(h)].grasp[static_cast<std::size_t>(object)]);
    }
  };
  const auto clear_hand_contacts = [&] {
    for (HandSim& sim : hands_) sim.on_object.clear();
  };
  // hand contacts of the step, grouped by object (contacts are sorted by body_a), and
  // by hand: a hand's contacts count only for its own grasp test
  std::size_t i = 0;
  int next_object = 0;  // objects before it have had their grasp test this step
  auto grasp_untouched_up_to = [&](int end) {
    clear_hand_contacts();
    for (; next_object < end; ++next_object) grasp_object(next_object);
  };
  while (i < applied_.size()) {
    const int object = applied_[i].contact.body_a;
    if (object >= object_count_) break;  // link-link pairs never occur; nothing further
    grasp_untouched_up_to(object);
    for (; i < applied_.size() && applied_[i].contact.body_a == object; ++i) {
      const AppliedContact& a = applied_[i];
      if (!collision_.is_hand_body(a.contact.body_b)) continue;
      HandContact hc;
      hc.link = collision_.link_of_body(a.contact.body_b);
      hc.p_G = a.contact.p_G;
      hc.n_G = -a.contact.n_G;  // from the link into the object
      hc.F_G = -a.F_on_b_G;     // the link's force on the object
      hands_[static_cast<std::size_t>(collision_.hand_of_body(a.contact.body_b))].on_object.push_back(hc);
      penetration_.max_m = std::max(penetration_.max_m, a.contact.depth_m);
      penetration_.sum_m += a.contact.depth_m;
      ++penetration_.points;
    }
    grasp_object(object);
    next_object = object + 1;
  }
  grasp_untouched_up_to(object_count_);
  for (const HandSim& sim : hands_)
    for (const ContactPoint& c : sim.hand_static)
      penetration_.static_max_m = std::max(penetration_.static_max_m, c.depth_m);
  // held poses for the release velocity
  for (int o = 0; o < object_count_; ++o) {
    const BodyState& body = state_.bodies[o];
    for (std::size_t h = 0; h < hands_.size(); ++h)
      if ((body.holders & hands_[h].holder_bit) != 0)
        grasp_tracker_.record_held_pose(state_.hands[h].grasp[o], body);
  }
  name_holders();
  if (!controls_.empty()) controls_.after_grasp(events_);
}

void World::tell_sleepers() {
  for (int i = 0; i < object_count_; ++i)
    if (scene_.objects[i].dynamic) collision_.set_object_asleep(i, state_.bodies[i].asleep);
}

bool World::wake_touched() {
  int woken = 0;
  for (const ContactPoint& c : contacts_) {
    if (c.body_a < object_count_) woken += SleepTracker::wake_island(c.body_a, state_.bodies);
    if (c.body_b < object_count_) woken += SleepTracker::wake_island(c.body_b, state_.bodies);
  }
  return woken > 0;
}

void World::update_sleep() {
  for (int i = 0; i < object_count_; ++i) {
    // a hand still letting go of it (its grasp state moves on each step; a held one is not free)
    bool idle = true;
    for (const HandState& hs : state_.hands) {
      const GraspHold& hold = hs.grasp[static_cast<std::size_t>(i)];
      idle = idle && !hold.hand_clearing && !hold.handed_over;
    }
    may_sleep_[i] = idle ? 1 : 0;
  }
  sleep_.update(contacts_, may_sleep_, state_.bodies);
}

void World::name_holders() {
  for (BodyState& body : state_.bodies)
    body.held_by = body.held() ? hand_id(lowest_bit(body.holders)) : kNotHeld;
}

}  // namespace vcockpit::physics
