#include "physics_node/physics/proxy_hand.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>

#include "common/assert.hpp"
#include "physics_node/physics/world_state.hpp"

namespace vcockpit::physics {
namespace {

// The hand's reach from the wrist (m): a wrist turn of w rad/s moves a fingertip about w times
// this, so a pushing hand turns no faster than push_speed_mps / kHandReach_m.
constexpr double kHandReach_m = 0.2;

constexpr int kShiftPasses = 16;           // Gauss-Seidel passes over the contact planes
constexpr double kShiftTolerance_m = 1e-7;  // a pass that corrects less than this ends them
constexpr double kTinyDepth_m = 1e-12;
constexpr double kStandardGravity_mps2 = 9.80665;

// Removes the contacts that no longer overlap, keeping the order of the rest.
void drop_separated(std::vector<ContactPoint>& contacts) {
  contacts.erase(std::remove_if(contacts.begin(), contacts.end(),
                                [](const ContactPoint& c) { return !(c.depth_m > 0.0); }),
                 contacts.end());
}

}  // namespace

ProxyHand::ProxyHand(const Scene& scene, int hand)
    : scene_(scene),
      hand_(scene.hands.at(static_cast<std::size_t>(hand))),
      params_(scene.proxy),
      object_count_(static_cast<int>(scene.objects.size())),
      link_base_(object_count_ + hand * kLinkCount) {
  depth_limit_m_.resize(scene.objects.size());
  dynamic_.resize(scene.objects.size());
  holds_fingers_back_.resize(scene.objects.size());
  grip_balance_.assign(scene.objects.size(), GripBalance{});
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const ObjectSpec& o = scene.objects[i];
    dynamic_[i] = o.dynamic ? 1 : 0;
    // (a lever that turns about a pivot; the gear's, which slides, is a knob a fingertip pushes)
    const ControlSpec* control =
        o.control >= 0 ? &scene.controls[static_cast<std::size_t>(o.control)] : nullptr;
    const bool lever = control != nullptr && control->kind == ControlKind::kLever &&
                       control->joint == JointKind::kRevolute;
    const bool heavy = o.control < 0 && o.mass_kg * kStandardGravity_mps2 >= params_.grip_force_N;
    holds_fingers_back_[i] = o.dynamic && (lever || heavy) ? 1 : 0;
    // a light object is pressed no harder than a few times its weight (at one standard g, so a
    // weightless scene grips alike): a finger that arrives first nudges a 60 g bar, not flings it.
    // A control's joint holds it: a finger presses a 5 g button cap with what its spring asks.
    const double force_N =
        o.control >= 0 ? params_.grip_force_N
                       : std::min(params_.grip_force_N,
                                  params_.grip_weight_ratio * o.mass_kg * kStandardGravity_mps2);
    depth_limit_m_[i] = o.dynamic ? force_N / pair_stiffness(scene.hand_material, o.material)
                                  : params_.static_depth_m;
  }
  for (int f = 0; f < kFingerCount; ++f)
    for (const hand::DhRow& row : hand_.fingers[static_cast<std::size_t>(f)].rows)
      if (row.joint >= 0 && row.joint < kJointCount)
        finger_joints_[static_cast<std::size_t>(f)][static_cast<std::size_t>(row.joint)] = true;
  for (int f = 0; f < kFingerCount; ++f) {
    FingerJoints& list = finger_joint_list_[static_cast<std::size_t>(f)];
    for (int j = 0; j < kJointCount && list.count < kMaxFingerJoints; ++j)
      if (finger_joints_[static_cast<std::size_t>(f)][static_cast<std::size_t>(j)]) list.joint[static_cast<std::size_t>(list.count++)] = j;
  }
  planes_.reserve(64);
}

ProxyPose ProxyHand::step_goal(const ProxyPose& now, const HandInput& tracked_from,
                               const HandInput& tracked, bool pushing, bool holding,
                               const std::vector<Eigen::Vector3d>& blocking_out_G,
                               double step_s, hand::KinematicsMemo& fk) const {
  double v_max = pushing ? params_.push_speed_mps : params_.max_speed_mps;
  double w_max =
      pushing ? std::min(params_.max_spin_radps, params_.push_speed_mps / kHandReach_m)
              : params_.max_spin_radps;
  if (holding) {
    // a held object moves as the tracked hand moves, and the proxy's lag behind it (where the
    // world held the hand back) closes no faster than the pushing speed: catching up at the
    // free speed would fling what the hand carries
    const double tracked_mps =
        (tracked.X_GH.translation() - tracked_from.X_GH.translation()).norm() / step_s;
    const double tracked_radps = Eigen::Quaterniond(tracked_from.X_GH.linear())
                                     .angularDistance(Eigen::Quaterniond(tracked.X_GH.linear())) /
                                 step_s;
    // (half the pushing speed each to the wrist's shift and its turn, at the hand's reach)
    v_max = std::min(v_max, tracked_mps + 0.5 * params_.push_speed_mps);
    w_max = std::min(w_max, tracked_radps + 0.5 * params_.push_speed_mps / kHandReach_m);
  }
  ProxyPose goal;
  goal.q_rad = tracked.q_rad;
  Eigen::Vector3d dp = tracked.X_GH.translation() - now.X_GH.translation();
  // off the surfaces it rests on (sequential projection: exact for one plane and for two at a
  // right angle, and never into any of them after the last pass for an edge or a corner)
  for (int pass = 0; pass < kMaxBlockingPlanes; ++pass) {
    bool projected = false;
    for (const Eigen::Vector3d& out : blocking_out_G) {
      const double into_m = -out.dot(dp);
      if (into_m <= 0.0) continue;
      dp += into_m * out;
      projected = true;
    }
    if (!projected) break;
  }
  const double reach_m = v_max * step_s;
  const double dp_m = dp.norm();
  goal.X_GH.translation() =
      now.X_GH.translation() + (dp_m > reach_m ? (reach_m / dp_m) * dp : dp);
  const Eigen::Quaterniond q_now(now.X_GH.linear());
  const Eigen::Quaterniond q_to(tracked.X_GH.linear());
  const double turn_rad = q_now.angularDistance(q_to);
  const double turn_max_rad = w_max * step_s;
  const double share = turn_rad > turn_max_rad ? turn_max_rad / turn_rad : 1.0;
  goal.X_GH.linear() = q_now.slerp(share, q_to).normalized().toRotationMatrix();
  limit_finger_speed(now.q_rad, params_.max_speed_mps * step_s, goal.q_rad, fk);
  return goal;
}

void ProxyHand::limit_finger_speed(const JointAngles& now_rad, double reach_m,
                                   JointAngles& goal_rad, hand::KinematicsMemo& fk) const {
  // The shares are found from how far each finger's links and tip would move (in the hand's
  // frame); a share is exact only to first order (a curling finger's tip moves along an arc
  // longer than its chord), so the scaled step is measured again, a few times.
  constexpr int kPasses = 4;
  HandLinkPoses from;
  HandLinkPoses to;
  fk.solve(now_rad, from);
  for (int pass = 0; pass < kPasses; ++pass) {
    fk.solve(goal_rad, to);
    std::array<double, kFingerCount> moved_m{};
    for (int f = 0; f < kFingerCount; ++f)
      moved_m[static_cast<std::size_t>(f)] =
          (to.p_H_tip[static_cast<std::size_t>(f)] - from.p_H_tip[static_cast<std::size_t>(f)]).norm();
    for (int l = 0; l < kLinkCount; ++l) {
      Finger finger;
      if (!finger_of(static_cast<Link>(l), finger)) continue;
      double& m = moved_m[static_cast<std::size_t>(finger)];
      m = std::max(m, (to.X_HL[static_cast<std::size_t>(l)].translation() -
                       from.X_HL[static_cast<std::size_t>(l)].translation()).norm());
    }
    // a joint moving several fingers takes the least of their shares, and one in no finger's
    // chain (the wrist's pitch and yaw move the whole hand in its frame) the least of all
    double least = 1.0;
    std::array<double, kFingerCount> share{};
    for (int f = 0; f < kFingerCount; ++f) {
      const double m = moved_m[static_cast<std::size_t>(f)];
      share[static_cast<std::size_t>(f)] = m > reach_m ? reach_m / m : 1.0;
      least = std::min(least, share[static_cast<std::size_t>(f)]);
    }
    if (least >= 1.0) return;
    for (int j = 0; j < kJointCount; ++j) {
      double s = 1.0;
      bool in_a_finger = false;
      for (int f = 0; f < kFingerCount; ++f) {
        if (!finger_joints_[static_cast<std::size_t>(f)][static_cast<std::size_t>(j)]) continue;
        in_a_finger = true;
        s = std::min(s, share[static_cast<std::size_t>(f)]);
      }
      goal_rad[j] = now_rad[j] + (in_a_finger ? s : least) * (goal_rad[j] - now_rad[j]);
    }
  }
}

bool ProxyHand::constrain_fingers(const ProxyPose& prev, const HandLinkPoses& prev_links,
                                  ProxyPose& pose, HandLinkPoses& links,
                                  std::array<Eigen::Isometry3d, kLinkCount>& X_GL,
                                  const std::vector<uint8_t>& held,
                                  std::vector<ContactPoint>& contacts,
                                  std::vector<ContactPoint>& hand_static, double dt_s) {
  ProxyConstraint result;
  balance_held_grips(contacts, held);
  hold_back_fingers(prev, prev_links, pose, links, X_GL, held, contacts, hand_static, dt_s, result);
  bend_out(pose, links, X_GL, contacts, hand_static, result);
  return result.fingers_held;
}

void ProxyHand::balance_held_grips(const std::vector<ContactPoint>& contacts,
                                   const std::vector<uint8_t>& held) {
  std::fill(grip_balance_.begin(), grip_balance_.end(), GripBalance{});
  // contacts are grouped by pair, so each object's hand contacts are consecutive
  std::size_t i = 0;
  while (i < contacts.size()) {
    const int object = contacts[i].body_a;
    std::size_t end = i;
    while (end < contacts.size() && contacts[end].body_a == object) ++end;
    if (is_link(object) || held[static_cast<std::size_t>(object)] == 0) {
      i = end;
      continue;
    }
    // the grip's axis: the opposing links' normals (into the object), one vote per link
    Eigen::Vector3d axis = Eigen::Vector3d::Zero();
    uint32_t opposing = 0;
    for (std::size_t k = i; k < end; ++k) {
      const ContactPoint& c = contacts[k];
      if (!is_link(c.body_b) || !opposes_fingers(link_of(c.body_b))) continue;
      const auto l = static_cast<uint32_t>(c.body_b - link_base_);
      if ((opposing >> l & 1u) == 0) axis -= c.n_G;  // n points from the object into the link
      opposing |= 1u << l;
    }
    if (opposing != 0 && axis.norm() > 0.0) {
      axis.normalize();
      // what each side can press along the axis, in grip forces: one per opposing link, and
      // each finger link's share along the axis (its first point's normal); no fingers, no share
      const double opposing_capacity = std::popcount(opposing);
      double finger_capacity = 0.0;
      uint32_t counted = 0;
      for (std::size_t k = i; k < end; ++k) {
        const ContactPoint& c = contacts[k];
        if (!is_link(c.body_b) || opposes_fingers(link_of(c.body_b))) continue;
        const auto l = static_cast<uint32_t>(c.body_b - link_base_);
        if ((counted >> l & 1u) != 0) continue;
        counted |= 1u << l;
        finger_capacity += std::max(0.0, c.n_G.dot(axis));  // the link pushes along -n
      }
      GripBalance& g = grip_balance_[static_cast<std::size_t>(object)];
      if (finger_capacity > opposing_capacity)
        g.finger_scale = opposing_capacity / finger_capacity;
      else if (finger_capacity > 0.0)
        g.opposing_scale = finger_capacity / opposing_capacity;
    }
    i = end;
  }
}

ProxyConstraint ProxyHand::constrain_wrist(ProxyPose& pose,
                                           std::array<Eigen::Isometry3d, kLinkCount>& X_GL,
                                           const std::vector<uint8_t>& held,
                                           std::vector<ContactPoint>& contacts,
                                           std::vector<ContactPoint>& hand_static,
                                           std::vector<Eigen::Vector3d>& blocking_out_G) {
  ProxyConstraint result;
  shift_out(X_GL, pose, held, contacts, hand_static, result, blocking_out_G);
  return result;
}

void ProxyHand::hold_back_fingers(const ProxyPose& prev, const HandLinkPoses& prev_links,
                                  ProxyPose& pose, HandLinkPoses& links,
                                  std::array<Eigen::Isometry3d, kLinkCount>& X_GL,
                                  const std::vector<uint8_t>& held,
                                  std::vector<ContactPoint>& contacts,
                                  std::vector<ContactPoint>& hand_static, double dt_s,
                                  ProxyConstraint& result) {
  std::array<double, kFingerCount> share;
  share.fill(1.0);
  limits_.clear();
  // Each contact of a phalanx: the depth its finger's own joints added over this step (the
  // contact point carried from the previous joint angles, the wrist as it is now), and the share
  // of that motion the limits allow, to first order.
  const auto limit_finger = [&](const ContactPoint& c) {
    if (!is_link(c.body_b)) return;  // an object pair
    const Link link = link_of(c.body_b);
    Finger finger;
    if (!finger_of(link, finger)) return;  // the palm moves with the wrist alone
    const auto l = static_cast<std::size_t>(link);
    const Eigen::Vector3d p_L = X_GL[l].inverse() * c.p_G;
    const Eigen::Vector3d p_before_G = pose.X_GH * (prev_links.X_HL[l] * p_L);
    // the link is body_b and n points into it: moving it by u deepens the contact by -n.u
    const double deepened_m = c.n_G.dot(p_before_G - c.p_G);
    const int other = c.body_a;
    const double depth_before_m = c.depth_m - deepened_m;
    double allowed_m = depth_limit_m(other, c.body_b) - depth_before_m;
    const auto o = static_cast<std::size_t>(other);
    if (dynamic_[o] != 0 && held[o] == 0) {
      // into a free object no faster than the pushing speed (from where it first touches)
      allowed_m = std::min(allowed_m, params_.push_speed_mps * dt_s + std::max(0.0, -depth_before_m));
    }
    limits_.push_back({&c, link, finger, p_L, deepened_m, allowed_m});
    if (deepened_m <= kTinyDepth_m) return;
    const auto f = static_cast<std::size_t>(finger);
    share[f] = std::min(share[f], std::clamp(allowed_m / deepened_m, 0.0, 1.0));
  };
  for (const ContactPoint& c : hand_static) limit_finger(c);
  for (const ContactPoint& c : contacts) limit_finger(c);
  if (std::all_of(share.begin(), share.end(), [](double s) { return s >= 1.0; })) return;

  // a joint moving several fingers takes the least of their shares
  const JointAngles q_goal_rad = pose.q_rad;
  for (int j = 0; j < kJointCount; ++j) {
    double s = 1.0;
    for (int f = 0; f < kFingerCount; ++f)
      if (finger_joints_[static_cast<std::size_t>(f)][static_cast<std::size_t>(j)])
        s = std::min(s, share[static_cast<std::size_t>(f)]);
    pose.q_rad[j] = prev.q_rad[j] + s * (pose.q_rad[j] - prev.q_rad[j]);
  }
  for (int f = 0; f < kFingerCount; ++f)
    if (share[static_cast<std::size_t>(f)] < 1.0)
      slide_finger(static_cast<Finger>(f), share[static_cast<std::size_t>(f)], q_goal_rad, pose);
  result.fingers_held = true;
  move_links(q_goal_rad, pose, links, X_GL, contacts, hand_static);
}

void ProxyHand::slide_finger(Finger finger, double share, const JointAngles& q_goal_rad,
                             ProxyPose& pose) {
  constexpr int kMaxRows = 4;       // the binding contacts that steer the slide
  constexpr double kDamping_m2 = 1e-8;
  constexpr double kBinding_m = 1e-6;  // a contact this close to its limit binds the slide
  constexpr int kActiveSetPasses = 3;
  const FingerJoints& finger_joints = finger_joint_list_[static_cast<std::size_t>(finger)];
  const auto& joints = finger_joints.joint;
  const int joint_count = finger_joints.count;
  if (joint_count == 0) return;
  // what the share left of the finger's step
  Eigen::Matrix<double, kMaxFingerJoints, 1> rest = Eigen::Matrix<double, kMaxFingerJoints, 1>::Zero();
  for (int k = 0; k < joint_count; ++k) {
    const int j = joints[static_cast<std::size_t>(k)];
    rest(k) = q_goal_rad[j] - pose.q_rad[j];
  }
  if (rest.squaredNorm() <= 0.0) return;

  // the depth each of the finger's contacts gains per radian of each joint, at the held-back pose
  slide_rows_.clear();
  slide_points_.clear();
  finger_kinematics(hand_, finger, pose.q_rad, slide_links_, chain_);
  for (std::size_t i = 0; i < limits_.size(); ++i) {
    const ContactLimit& cl = limits_[i];
    if (cl.finger != finger) continue;
    slide_rows_.push_back({i, Eigen::Matrix<double, kMaxFingerJoints, 1>::Zero(), 0.0, false});
    const auto l = static_cast<std::size_t>(cl.link);
    slide_points_.push_back({l, cl.p_L, slide_links_.X_HL[l] * cl.p_L, cl.contact->n_G});
  }
  if (slide_rows_.empty()) return;
  finger_depth_jacobian(hand_, chain_, finger_joints, pose.q_rad, pose.X_GH, slide_points_.data(),
                        slide_points_.size(), probe_links_,
                        [&](std::size_t i, int k, double d) { slide_rows_[i].gradient_m(k) = d; });
  for (SlideRow& row : slide_rows_) {
    const ContactLimit& cl = limits_[row.limit];
    row.room_m = cl.allowed_m - share * cl.deepened_m;  // how much deeper it may still go
    // a finger that an object stopped stays on it (it grips or pushes it); only a panel's
    // surface is slid along
    if (row.room_m <= kBinding_m && row.gradient_m.dot(rest) > kTinyDepth_m &&
        dynamic_[static_cast<std::size_t>(cl.contact->body_a)] != 0)
      return;
  }

  // the rest projected off the gradients of the binding contacts it would deepen (an active
  // set, grown a few times): the finger slides along the surfaces that stopped it
  Eigen::Matrix<double, kMaxFingerJoints, 1> slide = rest;
  std::array<const SlideRow*, kMaxRows> active{};
  int active_count = 0;
  for (int pass = 0; pass < kActiveSetPasses; ++pass) {
    bool grew = false;
    for (SlideRow& row : slide_rows_) {
      if (row.active || row.room_m > kBinding_m || row.gradient_m.dot(slide) <= kTinyDepth_m) continue;
      if (active_count == kMaxRows) break;
      row.active = true;
      active[static_cast<std::size_t>(active_count++)] = &row;
      grew = true;
    }
    if (!grew) break;
    Eigen::Matrix<double, kMaxRows, kMaxFingerJoints> G = Eigen::Matrix<double, kMaxRows, kMaxFingerJoints>::Zero();
    for (int i = 0; i < active_count; ++i) G.row(i) = active[static_cast<std::size_t>(i)]->gradient_m.transpose();
    const auto Ga = G.topRows(active_count);
    slide = rest - Ga.transpose() * damped_gram(Ga, kDamping_m2).solve(Ga * rest);
  }
  // ... and as far along it as every contact of the finger allows (first order)
  double along = 1.0;
  for (const SlideRow& row : slide_rows_) {
    // the active rows are projected off (to within the damping's trace): they do not deepen
    if (row.active) continue;
    const double deepens_m = row.gradient_m.dot(slide);
    if (deepens_m <= kTinyDepth_m) continue;
    along = std::min(along, std::max(0.0, row.room_m) / deepens_m);
  }
  if (!(along > 0.0)) return;
  for (int k = 0; k < joint_count; ++k) {
    const int j = joints[static_cast<std::size_t>(k)];
    const hand::JointRange& range = hand_.joints[static_cast<std::size_t>(j)];
    pose.q_rad[j] = std::clamp(pose.q_rad[j] + along * slide(k), range.min_rad, range.max_rad);
  }
}

void ProxyHand::move_links(const JointAngles& links_q_rad, const ProxyPose& pose,
                           HandLinkPoses& links, std::array<Eigen::Isometry3d, kLinkCount>& X_GL,
                           std::vector<ContactPoint>& contacts,
                           std::vector<ContactPoint>& hand_static) {
  const std::array<Eigen::Isometry3d, kLinkCount> X_GL_was = X_GL;
  // only the fingers whose joints moved: a finger's chain depends on its own joints alone, so
  // the others' links are already what forward kinematics gives (bit for bit)
  for (int f = 0; f < kFingerCount; ++f) {
    bool moved = false;
    for (std::size_t j = 0; j < kJointCount && !moved; ++j)
      moved = finger_joints_[static_cast<std::size_t>(f)][j] &&
              std::memcmp(&pose.q_rad[j], &links_q_rad[j], sizeof(double)) != 0;
    if (moved) finger_kinematics(hand_, static_cast<Finger>(f), pose.q_rad, links);
  }
  for (int l = 0; l < kLinkCount; ++l) X_GL[l] = pose.X_GH * links.X_HL[l];
  // the contacts follow their links (to first order: the overlap's midpoint moves half as far)
  const auto follow = [&](std::vector<ContactPoint>& list) {
    for (ContactPoint& c : list) {
      if (!is_link(c.body_b)) continue;
      const auto l = static_cast<std::size_t>(link_of(c.body_b));
      const Eigen::Vector3d u = X_GL[l] * (X_GL_was[l].inverse() * c.p_G) - c.p_G;
      c.depth_m -= c.n_G.dot(u);
      c.p_G += 0.5 * u;
    }
    drop_separated(list);
  };
  follow(hand_static);
  follow(contacts);
}

void ProxyHand::bend_out(ProxyPose& pose, HandLinkPoses& links,
                                   std::array<Eigen::Isometry3d, kLinkCount>& X_GL,
                                   std::vector<ContactPoint>& contacts,
                                   std::vector<ContactPoint>& hand_static,
                                   ProxyConstraint& result) {
  constexpr int kRows = 3;          // the deepest contacts of a finger that steer its joints
  // The finger's other contacts that the step could take past their limits: a fingertip wedged
  // between a panel and a held object (a thumb under a bar on its pedestal) bent out of the
  // panel alone went up to kMaxBend_rad into the object in one step (4.6 mm on a real log with
  // calibration error). Each one the step would take past its limit joins the rows, held at it.
  constexpr int kGuards = 4;
  constexpr double kGuardBand_m = 1e-3;  // contacts this close to their limits are watched
  constexpr int kGuardPasses = 2;
  constexpr double kDamping_m2 = 1e-6;  // (1 mm/rad)^2: keeps the step small near a singular finger
  // The most a joint bends in one step. A bend reaches links not yet touching anything (their
  // contacts come with the next step's narrowphase), so it is kept small, ~1.6 mm at a
  // fingertip, where only panels are left: at 0.05 rad a thumb bent out of a table swung 4-5 mm
  // into the bar lying on it (a real log with 0.1-0.7 s gaps); a panel does not move, and the
  // hand's own motion into it is bounded. Out of a moving body (a lever's handle turning under
  // the fingers, a held object) it bends faster, ~4 mm, or the fingers fall behind it (at 0.02
  // rad the levers' grips went 1.4 mm deeper on average over the study's 30 trials).
  constexpr double kMaxBendOutOfPanels_rad = 0.02;
  constexpr double kMaxBend_rad = 0.05;
  bool moved = false;
  // how far a contact is beyond its limit, and the depth to bring it to
  const auto excess_of = [&](const ContactPoint& c) {
    return c.depth_m - depth_limit_m(c.body_a, c.body_b);
  };
  const auto target_of = [&](const ContactPoint& c) {
    const double limit_m = depth_limit_m(c.body_a, c.body_b);
    return dynamic_[static_cast<std::size_t>(c.body_a)] != 0 ? limit_m : 0.5 * limit_m;
  };
  ProxyPose bent = pose;
  for (int f = 0; f < kFingerCount; ++f) {
    // the finger's contacts farthest beyond their limits, then those near theirs
    std::array<const ContactPoint*, kRows + kGuards> rows{};
    int row_count = 0;
    int guard_count = 0;
    const auto of_finger = [&](const ContactPoint& c) {
      if (!is_link(c.body_b) || is_link(c.body_a)) return false;
      Finger finger;
      return finger_of(link_of(c.body_b), finger) && static_cast<int>(finger) == f;
    };
    const auto consider = [&](const ContactPoint& c) {
      if (!of_finger(c) || excess_of(c) <= 0.0) return;
      if (row_count < kRows) {
        rows[static_cast<std::size_t>(row_count++)] = &c;
        return;
      }
      auto least = std::min_element(rows.begin(), rows.begin() + kRows, [&](auto* a, auto* b) {
        return excess_of(*a) < excess_of(*b);
      });
      if (excess_of(**least) < excess_of(c)) *least = &c;
    };
    for (const ContactPoint& c : hand_static) consider(c);
    for (const ContactPoint& c : contacts) consider(c);
    if (row_count == 0) continue;
    const auto watch = [&](const ContactPoint& c) {
      if (guard_count == kGuards || !of_finger(c)) return;
      const double excess_m = excess_of(c);
      if (excess_m > 0.0 || excess_m < -kGuardBand_m) return;  // a row already, or far off
      rows[static_cast<std::size_t>(row_count + guard_count++)] = &c;
    };
    for (const ContactPoint& c : hand_static) watch(c);
    for (const ContactPoint& c : contacts) watch(c);
    const int point_count = row_count + guard_count;
    const FingerJoints& finger_joints = finger_joint_list_[static_cast<std::size_t>(f)];
    const auto& joints = finger_joints.joint;
    const int joint_count = finger_joints.count;
    // J(i, k): the depth gained at contact i per radian of joint k
    std::array<FingerPoint, kRows + kGuards> points;
    for (int i = 0; i < point_count; ++i) {
      const ContactPoint& c = *rows[static_cast<std::size_t>(i)];
      const auto l = static_cast<std::size_t>(link_of(c.body_b));
      const Eigen::Vector3d p_H = links.X_HL[l] * (X_GL[l].inverse() * c.p_G);
      points[static_cast<std::size_t>(i)] = {l, links.X_HL[l].inverse() * p_H, p_H, c.n_G};
    }
    Eigen::Matrix<double, kRows + kGuards, kMaxFingerJoints> J =
        Eigen::Matrix<double, kRows + kGuards, kMaxFingerJoints>::Zero();
    finger_kinematics(hand_, static_cast<Finger>(f), pose.q_rad, probe_links_, chain_);
    finger_depth_jacobian(hand_, chain_, finger_joints, pose.q_rad, pose.X_GH,
                          points.data(), static_cast<std::size_t>(point_count), probe_links_,
                          [&](std::size_t i, int k, double d) {
                            J(static_cast<Eigen::Index>(i), k) = d;
                          });
    // the rows in use: the contacts beyond their limits, and the guards the step would take past
    // theirs (first order), brought to their targets by a damped least-squares step
    std::array<int, kRows + kGuards> use{};
    int use_count = 0;
    for (int i = 0; i < row_count; ++i) use[static_cast<std::size_t>(use_count++)] = i;
    Eigen::VectorXd dq;
    for (int pass = 0;; ++pass) {
      Eigen::MatrixXd Jr(use_count, joint_count);
      Eigen::VectorXd excess(use_count);
      for (int r = 0; r < use_count; ++r) {
        const int i = use[static_cast<std::size_t>(r)];
        Jr.row(r) = J.row(i).head(joint_count);
        const ContactPoint& c = *rows[static_cast<std::size_t>(i)];
        // a guard is only kept from going deeper than its target
        excess(r) = i < row_count ? c.depth_m - target_of(c) : std::max(0.0, c.depth_m - target_of(c));
      }
      dq = -Jr.transpose() * damped_gram(Jr, kDamping_m2).solve(excess);
      // a first-order step, trusted only so far: near a singular finger (a contact close to a
      // joint's axis) it would swing a phalanx through the object it is leaving
      bool panels_only = true;
      for (int r = 0; r < row_count; ++r)
        panels_only = panels_only && dynamic_[static_cast<std::size_t>(rows[static_cast<std::size_t>(r)]->body_a)] == 0;
      const double max_bend_rad = panels_only ? kMaxBendOutOfPanels_rad : kMaxBend_rad;
      const double largest_rad = dq.cwiseAbs().maxCoeff();
      if (largest_rad > max_bend_rad) dq *= max_bend_rad / largest_rad;
      if (pass == kGuardPasses) break;
      bool grew = false;
      for (int i = row_count; i < point_count; ++i) {
        if (std::find(use.begin(), use.begin() + use_count, i) != use.begin() + use_count) continue;
        const ContactPoint& c = *rows[static_cast<std::size_t>(i)];
        if (excess_of(c) + J.row(i).head(joint_count).dot(dq) <= 0.0) continue;
        use[static_cast<std::size_t>(use_count++)] = i;
        grew = true;
      }
      if (!grew) break;
    }
    for (int k = 0; k < joint_count; ++k) {
      const int j = joints[static_cast<std::size_t>(k)];
      const hand::JointRange& range = hand_.joints[static_cast<std::size_t>(j)];
      bent.q_rad[j] = std::clamp(pose.q_rad[j] + dq(k), range.min_rad, range.max_rad);
    }
    moved = true;
  }
  if (!moved) return;
  const JointAngles links_q_rad = pose.q_rad;
  pose.q_rad = bent.q_rad;
  result.fingers_held = true;
  move_links(links_q_rad, pose, links, X_GL, contacts, hand_static);
}

void ProxyHand::shift_out(std::array<Eigen::Isometry3d, kLinkCount>& X_GL, ProxyPose& pose,
                          const std::vector<uint8_t>& held, std::vector<ContactPoint>& contacts,
                          std::vector<ContactPoint>& hand_static, ProxyConstraint& result,
                          std::vector<Eigen::Vector3d>& blocking_out_G) {
  // which side of a contact moves with the proxy: its links and the objects it holds
  const auto moves = [&](int body) {
    return is_link(body) || held[static_cast<std::size_t>(body)] != 0;
  };
  planes_.clear();
  const auto collect = [&](const std::vector<ContactPoint>& list) {
    for (const ContactPoint& c : list) {
      const bool a = moves(c.body_a);
      const bool b = moves(c.body_b);
      if (a == b) continue;
      const int other = a ? c.body_b : c.body_a;  // static or free: never a link
      planes_.push_back({b ? c.n_G : Eigen::Vector3d(-c.n_G), c.depth_m,
                         depth_limit_m(other, a ? c.body_a : c.body_b),
                         dynamic_[static_cast<std::size_t>(other)] == 0});
    }
  };
  collect(hand_static);
  collect(contacts);

  Eigen::Vector3d shift = Eigen::Vector3d::Zero();
  project_shift(false, shift);
  // the panels win: where a free object's plane and a panel's ask for opposite shifts (a link
  // wedged between them), the link stays out of the panel and the object is pushed
  project_shift(true, shift);
  result.shift_G = shift;
  // the static surfaces it ends on: a plane at its limit (within kRestingBand_m)
  constexpr double kRestingBand_m = 5e-5;
  constexpr double kAlikeCos = 0.995;  // ~6 deg
  blocking_out_G.clear();
  for (const Plane& p : planes_) {
    if (!p.blocking || p.depth_m - p.out_G.dot(shift) - p.limit_m < -kRestingBand_m) continue;
    bool alike = false;
    for (const Eigen::Vector3d& n : blocking_out_G) alike = alike || n.dot(p.out_G) > kAlikeCos;
    if (!alike && static_cast<int>(blocking_out_G.size()) < kMaxBlockingPlanes)
      blocking_out_G.push_back(p.out_G);
  }

  const bool shifted = shift.squaredNorm() > 0.0;
  if (shifted) {
    pose.X_GH.translation() += shift;
    for (auto& X : X_GL) X.translation() += shift;
  }
  const auto follow = [&](std::vector<ContactPoint>& list) {
    for (ContactPoint& c : list) {
      const bool a = moves(c.body_a);
      const bool b = moves(c.body_b);
      if (a == b) continue;
      if (shifted) {
        c.depth_m -= (b ? 1.0 : -1.0) * c.n_G.dot(shift);
        c.p_G += 0.5 * shift;
      }
      const int other = a ? c.body_b : c.body_a;
      if (c.depth_m > 0.0 && dynamic_[static_cast<std::size_t>(other)] != 0) result.pushing = true;
    }
    if (shifted) drop_separated(list);
  };
  follow(hand_static);
  follow(contacts);
}

void ProxyHand::project_shift(bool panels_only, Eigen::Vector3d& shift_G) const {
  for (int pass = 0; pass < kShiftPasses; ++pass) {
    double largest_m = 0.0;
    for (const Plane& p : planes_) {
      if (panels_only && !p.blocking) continue;
      const double excess_m = p.depth_m - p.out_G.dot(shift_G) - p.limit_m;
      if (excess_m > 0.0) {
        shift_G += excess_m * p.out_G;
        largest_m = std::max(largest_m, excess_m);
      }
    }
    if (largest_m < kShiftTolerance_m) break;
  }
}

}  // namespace vcockpit::physics
