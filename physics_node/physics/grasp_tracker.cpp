#include "physics_node/physics/grasp_tracker.hpp"

#include <algorithm>
#include <cmath>

#include "common/assert.hpp"
#include "common/pose.hpp"
#include "physics_node/physics/integrator.hpp"

namespace vcockpit::physics {

double finger_flexion_rad(const JointAngles& q_rad, Finger finger) {
  const auto at = [&](hand::Joint j) { return q_rad[static_cast<std::size_t>(j)]; };
  switch (finger) {
    case Finger::kThumb: return at(hand::Joint::kThumbMcp) + at(hand::Joint::kThumbIp);
    case Finger::kIndex: return at(hand::Joint::kIndexMcp) + at(hand::Joint::kIndexPip) + at(hand::Joint::kIndexDip);
    case Finger::kMiddle:
      return at(hand::Joint::kMiddleMcp) + at(hand::Joint::kMiddlePip) + at(hand::Joint::kMiddleDip);
    case Finger::kRing: return at(hand::Joint::kRingMcp) + at(hand::Joint::kRingPip) + at(hand::Joint::kRingDip);
    case Finger::kLittle:
      return at(hand::Joint::kLittleMcp) + at(hand::Joint::kLittlePip) + at(hand::Joint::kLittleDip);
  }
  return 0.0;
}

GraspTracker::GraspTracker(const GraspParams& params, double step_s,
                           const Eigen::Vector3d& gravity_mps2, double hand_mu_s)
    : params_(params),
      step_s_(step_s),
      gravity_mps2_(gravity_mps2),
      hand_mu_s_(hand_mu_s),
      velocity_span_(std::max<std::size_t>(
          1, static_cast<std::size_t>(std::llround(params.velocity_window_s / step_s)))),
      settle_span_(std::max<std::size_t>(
          1, static_cast<std::size_t>(std::llround(params.settle_window_s / step_s)))),
      window_((params.settle_speed_mps > 0.0 ? std::max(velocity_span_, settle_span_)
                                              : velocity_span_) + 1),
      regrab_cooldown_ns_(std::llround(params.regrab_cooldown_s * 1e9)),
      release_delay_ns_(std::llround(params.release_delay_s * 1e9)),
      min_hold_ns_(std::llround(params.min_hold_s * 1e9)) {}

GraspHold GraspTracker::initial_hold(const ObjectSpec& o) const {
  GraspHold hold;
  // every slot set (Eigen leaves a pose uninitialised), so a state is all defined numbers
  if (o.dynamic) hold.history.assign(window_, Eigen::Isometry3d::Identity());
  return hold;
}

void GraspTracker::update(int object, const ObjectSpec& o, const HandContact* contacts,
                          std::size_t count, const HandNow& hand, uint32_t glove_links_inside,
                          GraspHold& hold, BodyState& body, std::vector<GraspEvent>& events,
                          const GraspJoint* joint) const {
  HandOnObject one{hand, contacts, count, glove_links_inside, false, 0, &hold};
  update_hands(object, o, &one, 1, body, events, joint);
}

void GraspTracker::clear_hand(const HandOnObject& h, bool held) const {
  GraspHold& hold = *h.hold;
  if (!hold.hand_clearing || held) return;
  // For the cooldown after a release, every link whose glove link passes through the object
  // rests off it: the hand does not push what it has just let go of. After it, if the pilot
  // let go (the glove opened from its grip, or the hand handed the object over) they rest until
  // the glove is clear of it; otherwise (the grip loosened with the glove still closed) they
  // all end, so the same grip can take the object again. A hand that handed the object over may
  // take it again once its glove has opened or left it.
  const bool cooled = h.hand.t_ns - hold.released_at_ns >= regrab_cooldown_ns_;
  if (!cooled && !hold.handed_over) {
    hold.resting_links |= h.glove_links_inside;
    return;
  }
  const bool opened = hand_opened(h.hand, hold);
  if (!cooled) {
    hold.resting_links |= h.glove_links_inside;
  } else {
    hold.resting_links = opened || hold.handed_over ? h.glove_links_inside : 0u;
  }
  if (hold.handed_over && (opened || h.glove_links_inside == 0)) hold.handed_over = false;
  if (cooled && hold.resting_links == 0 && !hold.handed_over) hold.hand_clearing = false;
}

void GraspTracker::note_let_go(const HandOnObject& h) {
  h.hold->hand_clearing = true;
  h.hold->resting_links = 0;
  for (std::size_t i = 0; i < h.count; ++i)
    h.hold->resting_links |= 1u << static_cast<int>(h.contacts[i].link);
}

bool GraspTracker::may_take(const HandOnObject& h) const {
  return h.hand.tracking && !h.hold->handed_over &&
         h.hand.t_ns - h.hold->released_at_ns >= regrab_cooldown_ns_;
}

void GraspTracker::update_hands(int object, const ObjectSpec& o, HandOnObject* hands,
                                std::size_t hand_count, BodyState& body,
                                std::vector<GraspEvent>& events, const GraspJoint* joint) const {
  if (!o.dynamic) return;
  VCOCKPIT_ASSERT(hand_count <= kMaxHands, "at most kMaxHands hands");
  std::array<bool, kMaxHands> was_held{};
  std::array<GraspCheck, kMaxHands> checks{};
  bool any = false;
  int holders = 0;
  for (std::size_t k = 0; k < hand_count; ++k) {
    was_held[k] = (body.holders & hands[k].hand.holder_bit) != 0;
    clear_hand(hands[k], was_held[k]);
    if (!was_held[k] && hands[k].count == 0) continue;
    any = true;
    holders += was_held[k] ? 1 : 0;
    checks[k] = evaluate_grasp(hands[k].contacts, hands[k].count, body.X_GO.translation(),
                               o.mass_kg, gravity_mps2_, params_, was_held[k], joint);
  }
  if (!any) return;
  if (holders >= 2) {
    update_two_handed(object, o, hands, hand_count, checks.data(), body, events);
  } else if (holders == 1) {
    std::size_t holder = 0;
    while (!was_held[holder]) ++holder;
    update_held_by_one(object, hands, hand_count, holder, checks.data(), body, events);
  } else {
    update_free(object, o, hands, hand_count, checks.data(), body, events, joint);
  }
  for (std::size_t k = 0; k < hand_count; ++k)
    if (was_held[k] && (body.holders & hands[k].hand.holder_bit) == 0) note_let_go(hands[k]);
}

// One hand holds it: another hand whose own test takes it (unheld thresholds) takes it over, in
// the same step; else the holder's own decision.
void GraspTracker::update_held_by_one(int object, HandOnObject* hands, std::size_t hand_count,
                                      std::size_t holder, const GraspCheck* checks, BodyState& body,
                                      std::vector<GraspEvent>& events) const {
  HandOnObject& from = hands[holder];
  for (std::size_t k = 0; k < hand_count && from.hand.tracking; ++k) {
    HandOnObject& to = hands[k];
    if (k == holder || to.count == 0 || !may_take(to) || !checks[k].holds()) continue;
    body.holders |= to.hand.holder_bit;  // it never leaves a hand: no release velocity
    release(object, GraspReason::kHandedOver, checks[holder], from.hand, *from.hold, body, events,
            to.hand.hand_id);
    from.hold->handed_over = true;
    attach(object, checks[k], to.hand, *to.hold, body, events, from.hand.hand_id);
    return;
  }
  decide(object, checks[holder], from, body, events);
}

// No hand holds it: the first hand whose own test takes it; else two hands whose gestures hold on
// their own, or that each pinch it (an opposer and an opposed finger: more than 2 contact points
// together), and whose contacts together meet eqs. 30-31 (not a control: one hand at a time).
void GraspTracker::update_free(int object, const ObjectSpec& o, HandOnObject* hands,
                               std::size_t hand_count, const GraspCheck* checks, BodyState& body,
                               std::vector<GraspEvent>& events, const GraspJoint* joint) const {
  for (std::size_t k = 0; k < hand_count && !body.held(); ++k) {
    if (hands[k].count == 0 || hands[k].hold->handed_over) continue;  // (gave it away, still on it)
    decide(object, checks[k], hands[k], body, events);
  }
  if (body.held() || joint != nullptr) return;
  const auto may_join = [&](std::size_t k) {
    return hands[k].count != 0 && may_take(hands[k]) &&
           (checks[k].gesture_holds() || checks[k].pinch);
  };
  for (std::size_t a = 0; a < hand_count; ++a) {
    for (std::size_t b = a + 1; b < hand_count && may_join(a); ++b) {
      if (!may_join(b)) continue;
      const Residuals both = two_hand_residuals(hands[a], hands[b], body, o);
      if (!residuals_hold(both, params_, false)) continue;
      GraspCheck ca = checks[a], cb = checks[b];
      ca.residual_force_N = cb.residual_force_N = both.force_N;
      ca.residual_torque_Nm = cb.residual_torque_Nm = both.torque_Nm;
      attach(object, ca, hands[a].hand, *hands[a].hold, body, events, hands[b].hand.hand_id);
      attach(object, cb, hands[b].hand, *hands[b].hold, body, events, hands[a].hand.hand_id);
      return;
    }
  }
}

Residuals GraspTracker::two_hand_residuals(const HandOnObject& a, const HandOnObject& b,
                                           const BodyState& body, const ObjectSpec& o) const {
  // eqs. 30-31 over both hands' contacts, gravity once: the sums first, then what the contacts'
  // static friction could still add against them (their reserve) taken off
  const Eigen::Vector3d c_G = body.X_GO.translation();
  const double mu = std::sqrt(hand_mu_s_ * o.material.mu_s);  // the pair's (contact model)
  Eigen::Vector3d F = o.mass_kg * gravity_mps2_;
  Eigen::Vector3d M = Eigen::Vector3d::Zero();
  for (const HandOnObject* h : {&a, &b}) {
    for (std::size_t i = 0; i < h->count; ++i) {
      const HandContact& c = h->contacts[i];
      F += c.F_G;
      M += (c.p_G - c_G).cross(c.F_G);
    }
  }
  // Each contact's friction may grow, within its cone |f_t| <= mu N, against the residual:
  // along -F by mu N |P_t F^|, and against M by mu N |P_t (M^ x r)| (P_t: onto its tangent
  // plane). A contact pressing along the residual (a palm on top of a bar) adds nothing; a
  // squeeze across it adds its whole cone. Force and torque are relieved each on its own, an
  // optimistic bound that a real grip's friction meets in the same step only roughly.
  const Eigen::Vector3d F_dir = F.norm() > 0.0 ? Eigen::Vector3d(F.normalized()) : Eigen::Vector3d::Zero();
  const Eigen::Vector3d M_dir = M.norm() > 0.0 ? Eigen::Vector3d(M.normalized()) : Eigen::Vector3d::Zero();
  double force_reserve_N = 0.0, torque_reserve_Nm = 0.0;
  for (const HandOnObject* h : {&a, &b}) {
    for (std::size_t i = 0; i < h->count; ++i) {
      const HandContact& c = h->contacts[i];
      const double friction_N = mu * std::max(0.0, c.F_G.dot(c.n_G));
      if (friction_N <= 0.0) continue;
      const auto tangential = [&](const Eigen::Vector3d& v) { return (v - v.dot(c.n_G) * c.n_G).norm(); };
      force_reserve_N += friction_N * tangential(F_dir);
      torque_reserve_Nm += friction_N * tangential(M_dir.cross(c.p_G - c_G));
    }
  }
  return {std::max(0.0, F.norm() - force_reserve_N), std::max(0.0, M.norm() - torque_reserve_Nm)};
}

GraspReason GraspTracker::held_verdict(const HandOnObject& h, const GraspCheck& check) const {
  if (!h.hand.tracking) return GraspReason::kGloveLost;
  note_tightest_grip(h);
  if (hand_opened(h.hand, *h.hold)) return GraspReason::kHandOpened;
  if (params_.hold_rule == HoldRule::kContactTest) return check.verdict;
  // (a hand whose tracked grip is not known has nothing that says it let go)
  const GraspReason grip = h.grip_known ? tracked_grip_verdict(h) : GraspReason::kStableGrasp;
  // The thumb or the fingers leave the surface as the hand opens, often before the flexion has
  // fallen by a share of the grasp's (a fist closes on past the grasp; a real one round a bar
  // had opened 29 deg from its tightest when its thumb left): the hand opening is the reason,
  // once the glove has opened from its tightest grip by release_opening_deg. With the glove
  // still closed, the hand left the object (it was pulled away, or the object was held back).
  const bool left = grip == GraspReason::kThumbLeft || grip == GraspReason::kFingersLeft;
  if (left && grip_flexion(h.hand, *h.hold).from_tightest_rad > deg_to_rad(params_.release_opening_deg))
    return GraspReason::kHandOpened;
  return grip;
}

void GraspTracker::note_tightest_grip(const HandOnObject& h) {
  if (h.hand.tracked_q_rad == nullptr) return;
  for (int f = 0; f < kFingerCount; ++f) {
    double& tightest_rad = h.hold->grip_tightest_rad[static_cast<std::size_t>(f)];
    tightest_rad = std::max(tightest_rad, finger_flexion_rad(*h.hand.tracked_q_rad, static_cast<Finger>(f)));
  }
}

GraspReason GraspTracker::tracked_grip_verdict(const HandOnObject& h) const {
  const GraspHold& hold = *h.hold;
  const auto near = [&](Link l) { return (h.tracked_links_near & (1u << static_cast<int>(l))) != 0; };
  const auto finger_near = [&](int f) {
    for (Link l : finger_links(static_cast<Finger>(f)))
      if (near(l)) return true;
    return false;
  };
  if (hold.palm_opposed ? !near(Link::kPalm) : !finger_near(static_cast<int>(Finger::kThumb)))
    return GraspReason::kThumbLeft;
  bool any_opposed = hold.opposed_fingers == 0;  // (none recorded: the opposer alone is asked)
  for (int f = 1; f < kFingerCount && !any_opposed; ++f)
    if ((hold.opposed_fingers & (1u << f)) != 0 && finger_near(f)) any_opposed = true;
  return any_opposed ? GraspReason::kStableGrasp : GraspReason::kFingersLeft;
}

bool GraspTracker::failed_long_enough(const HandOnObject& h, GraspReason verdict) const {
  GraspHold& hold = *h.hold;
  if (verdict == GraspReason::kGloveLost) return true;
  if (verdict == GraspReason::kStableGrasp) {
    hold.failing_since_ns = -1;
    return false;
  }
  if (hold.failing_since_ns < 0) hold.failing_since_ns = h.hand.t_ns;
  return h.hand.t_ns - hold.failing_since_ns >= release_delay_ns_ &&
         h.hand.t_ns - hold.held_since_ns >= min_hold_ns_;
}

// Both hands hold it. Each keeps its own gesture, glove and opening rules; eqs. 30-31 are over
// both hands' contacts. One that fails long enough lets go; the other keeps it if its own test
// (held thresholds) holds alone, else lets go too.
void GraspTracker::update_two_handed(int object, const ObjectSpec& o, HandOnObject* hands,
                                     std::size_t hand_count, const GraspCheck* checks,
                                     BodyState& body, std::vector<GraspEvent>& events) const {
  std::array<HandOnObject*, 2> h{};
  std::array<const GraspCheck*, 2> check{};
  for (std::size_t k = 0, n = 0; k < hand_count && n < 2; ++k) {
    if ((body.holders & hands[k].hand.holder_bit) == 0) continue;
    h[n] = &hands[k];
    check[n++] = &checks[k];
  }
  const Residuals both = two_hand_residuals(*h[0], *h[1], body, o);
  const bool together = residuals_hold(both, params_, true);
  const GraspReason apart = both.force_N > params_.xi_N * params_.exit_scale
                                ? GraspReason::kForceResidual
                                : GraspReason::kTorqueResidual;
  std::array<GraspReason, 2> verdict{};
  std::array<bool, 2> lets_go{};
  for (std::size_t i = 0; i < 2; ++i) {
    GraspReason v = held_verdict(*h[i], *check[i]);
    // the paper's rule: its gesture holds, and eqs. 30-31 are both hands' together (with the
    // tracked grip, the hands' own grips decide, as for one hand)
    if (params_.hold_rule == HoldRule::kContactTest &&
        (v == GraspReason::kStableGrasp || v == GraspReason::kForceResidual ||
         v == GraspReason::kTorqueResidual))
      v = together ? GraspReason::kStableGrasp : apart;
    verdict[i] = v;
    lets_go[i] = failed_long_enough(*h[i], v);
  }
  if (!lets_go[0] && !lets_go[1]) return;
  const std::size_t first = lets_go[0] ? 0 : 1;
  const std::size_t other = 1 - first;
  GraspCheck figures = *check[first];
  figures.residual_force_N = both.force_N;
  figures.residual_torque_Nm = both.torque_Nm;
  release(object, verdict[first], figures, h[first]->hand, *h[first]->hold, body, events,
          h[other]->hand.hand_id);
  // the other hand keeps it if its own test (held thresholds) holds it alone, else lets go too:
  // carrying alone what two hands carried is a new hold, and eqs. 30-31 judge it
  GraspReason alone = lets_go[other] ? verdict[other] : held_verdict(*h[other], *check[other]);
  if (alone == GraspReason::kStableGrasp && !check[other]->holds()) alone = check[other]->verdict;
  if (alone != GraspReason::kStableGrasp) {
    release(object, alone, *check[other], h[other]->hand, *h[other]->hold, body, events,
            h[first]->hand.hand_id);
  }
}

void GraspTracker::decide(int object, const GraspCheck& check, const HandNow& hand, GraspHold& hold,
                          BodyState& body, std::vector<GraspEvent>& events) const {
  HandOnObject h{hand, nullptr, 0, 0, false, 0, &hold};
  decide(object, check, h, body, events);
}

void GraspTracker::decide(int object, const GraspCheck& check, const HandOnObject& h,
                          BodyState& body, std::vector<GraspEvent>& events) const {
  GraspHold& hold = *h.hold;
  VCOCKPIT_ASSERT(hold.history.size() >= 2, "grasp decisions are for dynamic objects only");
  const bool held = (body.holders & h.hand.holder_bit) != 0;
  if (!held) {
    const bool cooled = h.hand.t_ns - hold.released_at_ns >= regrab_cooldown_ns_;
    if (h.hand.tracking && cooled && check.holds()) attach(object, check, h.hand, hold, body, events);
    return;
  }
  const GraspReason verdict = held_verdict(h, check);
  if (failed_long_enough(h, verdict)) release(object, verdict, check, h.hand, hold, body, events);
}

GraspTracker::GripFlexion GraspTracker::grip_flexion(const HandNow& hand, const GraspHold& hold) {
  GripFlexion out;
  if (hand.tracked_q_rad == nullptr || hold.grip_fingers == 0) return out;
  // The thumb opens a grip mostly by rotation and abduction, which its flexion does not show:
  // it counts only when it is the one gripping finger.
  const unsigned thumb = 1u << static_cast<int>(Finger::kThumb);
  const unsigned opening_fingers =
      (hold.grip_fingers & ~thumb) != 0 ? (hold.grip_fingers & ~thumb) : hold.grip_fingers;
  int fingers = 0;
  for (int f = 0; f < kFingerCount; ++f) {
    if ((opening_fingers & (1u << f)) == 0) continue;
    const double at_grasp_rad = hold.grip_flexion_rad[static_cast<std::size_t>(f)];
    out.at_grasp_rad += at_grasp_rad;
    const double now_rad = finger_flexion_rad(*hand.tracked_q_rad, static_cast<Finger>(f));
    out.opening_rad += at_grasp_rad - now_rad;
    out.from_tightest_rad += hold.grip_tightest_rad[static_cast<std::size_t>(f)] - now_rad;
    ++fingers;
  }
  out.at_grasp_rad /= fingers;
  out.opening_rad /= fingers;
  out.from_tightest_rad /= fingers;
  return out;
}

bool GraspTracker::hand_opened(const HandNow& hand, const GraspHold& hold) const {
  if (params_.release_opening_share <= 0.0) return false;
  const GripFlexion grip = grip_flexion(hand, hold);
  const double threshold_rad = std::max(params_.release_opening_share * grip.at_grasp_rad,
                                        deg_to_rad(params_.release_opening_deg));
  return grip.opening_rad > threshold_rad;
}

void GraspTracker::attach(int object, const GraspCheck& check, const HandNow& hand, GraspHold& hold,
                          BodyState& body, std::vector<GraspEvent>& events,
                          int other_hand_id) const {
  hold.X_HO = hand.X_GH.inverse() * body.X_GO;  // eq. 28
  hold.held_since_ns = hand.t_ns;
  hold.failing_since_ns = -1;
  hold.history_next = 0;
  hold.history_count = 0;
  hold.grip_fingers = check.fingers;
  hold.opposed_fingers = check.opposed_fingers;
  hold.palm_opposed = check.palm_opposes;
  hold.resting_links = 0;
  hold.hand_clearing = false;
  for (int f = 0; f < kFingerCount; ++f) {
    hold.grip_flexion_rad[static_cast<std::size_t>(f)] =
        hand.tracked_q_rad != nullptr ? finger_flexion_rad(*hand.tracked_q_rad, static_cast<Finger>(f))
                                      : 0.0;
    hold.grip_tightest_rad[static_cast<std::size_t>(f)] = hold.grip_flexion_rad[static_cast<std::size_t>(f)];
  }
  body.holders |= hand.holder_bit;
  if (body.held_by == kNotHeld) body.held_by = hand.hand_id;
  events.push_back(event(object, true, GraspReason::kStableGrasp, check, hand, other_hand_id));
}

void GraspTracker::release(int object, GraspReason reason, const GraspCheck& check,
                           const HandNow& hand, GraspHold& hold, BodyState& body,
                           std::vector<GraspEvent>& events, int other_hand_id) const {
  body.holders = static_cast<uint8_t>(body.holders & ~hand.holder_bit);
  if (body.held_by == hand.hand_id) body.held_by = kNotHeld;  // the world names the one left
  hold.released_at_ns = hand.t_ns;
  hold.failing_since_ns = -1;
  events.push_back(event(object, false, reason, check, hand, other_hand_id));
  if (body.held()) return;  // the other hand has it
  // the object leaves with the hand's motion over the last window (no jump, can be thrown),
  // or over the settle window when the hand was setting it down
  if (hold.history_count >= 2) {
    held_velocity(hold, velocity_span_, body.v_G, body.w_G);
    if (params_.settle_speed_mps > 0.0) {
      Eigen::Vector3d v_G, w_G;
      held_velocity(hold, settle_span_, v_G, w_G);
      if (v_G.norm() < params_.settle_speed_mps) {
        body.v_G = v_G;
        body.w_G = w_G;
      }
    }
  }
}

void GraspTracker::held_velocity(const GraspHold& hold, std::size_t span_steps,
                                 Eigen::Vector3d& v_G, Eigen::Vector3d& w_G) const {
  const std::size_t n = hold.history.size();
  const std::size_t span = std::min(span_steps, hold.history_count - 1);
  const std::size_t newest = (hold.history_next + n - 1) % n;
  const std::size_t oldest = (newest + n - span) % n;
  finite_difference_velocity(hold.history[oldest], hold.history[newest],
                             static_cast<double>(span) * step_s_, v_G, w_G);
}

GraspEvent GraspTracker::event(int object, bool grasp, GraspReason reason, const GraspCheck& check,
                               const HandNow& hand, int other_hand_id) const {
  GraspEvent e;
  e.t_ns = hand.t_ns;
  e.grasp = grasp;
  e.hand_id = hand.hand_id;
  e.other_hand_id = other_hand_id;
  e.object = object;
  e.reason = reason;
  e.contacts = check.links_in_contact;
  e.thumb_touching = check.thumb;
  e.palm_opposes = check.palm_opposes;
  e.min_thumb_angle_deg = check.min_thumb_angle_deg;
  e.best_opposition_deg = check.best_opposition_deg;
  e.residual_force_N = check.residual_force_N;
  e.residual_torque_Nm = check.residual_torque_Nm;
  return e;
}

void GraspTracker::record_held_pose(GraspHold& hold, const BodyState& body) const {
  hold.history[hold.history_next] = body.X_GO;
  hold.history_next = (hold.history_next + 1) % hold.history.size();
  hold.history_count = std::min(hold.history_count + 1, hold.history.size());
}

}  // namespace vcockpit::physics
