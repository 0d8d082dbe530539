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
                           const Eigen::Vector3d& gravity_mps2, int hand_id)
    : params_(params),
      step_s_(step_s),
      gravity_mps2_(gravity_mps2),
      hand_id_(hand_id),
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
  if (!o.dynamic) return;
  const bool held = body.held_by == hand_id_;
  if (hold.hand_clearing && !held) {
    // For the cooldown after a release, every link whose glove link passes through the object
    // rests off it: the hand does not push what it has just let go of. After it, if the pilot
    // let go (the glove opened from its grip) they rest until the glove is clear of it;
    // otherwise (the grip loosened with the glove still closed) they all end, so the same grip
    // can take the object again.
    const bool cooled = hand.t_ns - hold.released_at_ns >= regrab_cooldown_ns_;
    if (!cooled) {
      hold.resting_links |= glove_links_inside;
    } else {
      const bool let_go = params_.release_opening_deg > 0.0 &&
                          grip_opening_rad(hand, hold) > deg_to_rad(params_.release_opening_deg);
      hold.resting_links = let_go ? glove_links_inside : 0u;
    }
    if (cooled && hold.resting_links == 0) hold.hand_clearing = false;
  }
  if (!held && count == 0) return;
  const GraspCheck check = evaluate_grasp(contacts, count, body.X_GO.translation(), o.mass_kg,
                                          gravity_mps2_, params_, held, joint);
  decide(object, check, hand, hold, body, events);
  if (held && body.held_by == kNotHeld) {  // let go this step: name the links that touched it
    hold.hand_clearing = true;
    hold.resting_links = 0;
    for (std::size_t i = 0; i < count; ++i)
      hold.resting_links |= 1u << static_cast<int>(contacts[i].link);
  }
}

void GraspTracker::decide(int object, const GraspCheck& check, const HandNow& hand, GraspHold& hold,
                          BodyState& body, std::vector<GraspEvent>& events) const {
  VCOCKPIT_ASSERT(hold.history.size() >= 2, "grasp decisions are for dynamic objects only");
  const bool held = body.held_by == hand_id_;
  if (!held) {
    const bool cooled = hand.t_ns - hold.released_at_ns >= regrab_cooldown_ns_;
    if (hand.tracking && cooled && check.holds()) attach(object, check, hand, hold, body, events);
    return;
  }
  if (!hand.tracking) {
    release(object, GraspReason::kGloveLost, check, hand, hold, body, events);
    return;
  }
  GraspReason verdict = check.verdict;
  if (params_.release_opening_deg > 0.0 &&
      grip_opening_rad(hand, hold) > deg_to_rad(params_.release_opening_deg))
    verdict = GraspReason::kHandOpened;
  if (verdict == GraspReason::kStableGrasp) {
    hold.failing_since_ns = -1;
    return;
  }
  if (hold.failing_since_ns < 0) hold.failing_since_ns = hand.t_ns;
  const bool failed_long_enough = hand.t_ns - hold.failing_since_ns >= release_delay_ns_;
  const bool held_long_enough = hand.t_ns - hold.held_since_ns >= min_hold_ns_;
  if (failed_long_enough && held_long_enough)
    release(object, verdict, check, hand, hold, body, events);
}

double GraspTracker::grip_opening_rad(const HandNow& hand, GraspHold& hold) const {
  if (hand.tracked_q_rad == nullptr || hold.grip_fingers == 0) return 0.0;
  // The thumb opens a grip mostly by rotation and abduction, which its flexion does not show:
  // it counts only when it is the one gripping finger.
  const unsigned thumb = 1u << static_cast<int>(Finger::kThumb);
  const unsigned opening_fingers =
      (hold.grip_fingers & ~thumb) != 0 ? (hold.grip_fingers & ~thumb) : hold.grip_fingers;
  double opening_rad = 0.0;
  int fingers = 0;
  for (int f = 0; f < kFingerCount; ++f) {
    if ((opening_fingers & (1u << f)) == 0) continue;
    double& tightest = hold.grip_flexion_rad[static_cast<std::size_t>(f)];
    const double now = finger_flexion_rad(*hand.tracked_q_rad, static_cast<Finger>(f));
    tightest = std::max(tightest, now);
    opening_rad += tightest - now;
    ++fingers;
  }
  return opening_rad / fingers;
}

void GraspTracker::attach(int object, const GraspCheck& check, const HandNow& hand, GraspHold& hold,
                          BodyState& body, std::vector<GraspEvent>& events) const {
  hold.X_HO = hand.X_GH.inverse() * body.X_GO;  // eq. 28
  hold.held_since_ns = hand.t_ns;
  hold.failing_since_ns = -1;
  hold.history_next = 0;
  hold.history_count = 0;
  hold.grip_fingers = check.fingers;
  hold.resting_links = 0;
  hold.hand_clearing = false;
  for (int f = 0; f < kFingerCount; ++f)
    hold.grip_flexion_rad[static_cast<std::size_t>(f)] =
        hand.tracked_q_rad != nullptr ? finger_flexion_rad(*hand.tracked_q_rad, static_cast<Finger>(f))
                                      : 0.0;
  body.held_by = hand_id_;
  events.push_back(event(object, true, GraspReason::kStableGrasp, check, hand));
}

void GraspTracker::release(int object, GraspReason reason, const GraspCheck& check,
                           const HandNow& hand, GraspHold& hold, BodyState& body,
                           std::vector<GraspEvent>& events) const {
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
  body.held_by = kNotHeld;
  hold.released_at_ns = hand.t_ns;
  hold.failing_since_ns = -1;
  events.push_back(event(object, false, reason, check, hand));
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
                               const HandNow& hand) const {
  GraspEvent e;
  e.t_ns = hand.t_ns;
  e.grasp = grasp;
  e.hand_id = hand_id_;
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
