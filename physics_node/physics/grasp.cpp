#include "physics_node/physics/grasp.hpp"

#include <algorithm>
#include <cmath>

#include "common/pose.hpp"

namespace vcockpit::physics {

const char* grasp_reason_name(GraspReason reason) {
  switch (reason) {
    case GraspReason::kStableGrasp: return "stable grasp";
    case GraspReason::kTooFewContacts: return "too few contacts";
    case GraspReason::kNoThumb: return "thumb not touching";
    case GraspReason::kFingersNotOpposed: return "fingers not opposed to the thumb";
    case GraspReason::kForceResidual: return "force residual too large";
    case GraspReason::kTorqueResidual: return "torque residual too large";
    case GraspReason::kGloveLost: return "glove lost";
    case GraspReason::kHandOpened: return "hand opened";
    case GraspReason::kHandedOver: return "handed over";
    case GraspReason::kReset: return "scene reset";
    case GraspReason::kThumbLeft: return "thumb left the object";
    case GraspReason::kFingersLeft: return "fingers left the object";
  }
  return "unknown";
}

Residuals grasp_residuals(const HandContact* contacts, std::size_t count,
                          const Eigen::Vector3d& centroid_G, double mass_kg,
                          const Eigen::Vector3d& gravity_mps2, const GraspJoint* joint) {
  Eigen::Vector3d F = mass_kg * gravity_mps2;
  Eigen::Vector3d M = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < count; ++i) {
    F += contacts[i].F_G;
    M += (contacts[i].p_G - centroid_G).cross(contacts[i].F_G);
  }
  Residuals r;
  if (joint == nullptr) {
    r.force_N = F.norm();
    r.torque_Nm = M.norm();
  } else if (joint->revolute) {  // the moment about the axis: M is about the centroid
    r.torque_Nm = std::abs(joint->axis_G.dot(M + (centroid_G - joint->origin_G).cross(F)));
  } else {
    r.force_N = std::abs(joint->axis_G.dot(F));
  }
  return r;
}

bool residuals_hold(const Residuals& r, const GraspParams& params, bool held) {
  const double scale = held ? params.exit_scale : 1.0;
  return r.force_N <= params.xi_N * scale && r.torque_Nm <= params.eta_Nm * scale;
}

namespace {

double angle_deg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return rad_to_deg(std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0)));
}

// The links of a hand on one object, as the gesture rule sees them.
struct HandTouch {
  std::array<bool, kLinkCount> link{};                 // touching
  std::array<Eigen::Vector3d, kLinkCount> link_normal;  // force-weighted sum of its normals
  std::array<bool, kFingerCount> finger{};
  std::array<Eigen::Vector3d, kFingerCount> finger_normal;  // sum over its touching phalanges
  std::array<int, kFingerCount> finger_link_count{};

  HandTouch(const HandContact* contacts, std::size_t count) {
    link_normal.fill(Eigen::Vector3d::Zero());
    finger_normal.fill(Eigen::Vector3d::Zero());
    for (std::size_t i = 0; i < count; ++i) {
      const int l = static_cast<int>(contacts[i].link);
      link[l] = true;
      link_normal[l] += (1e-6 + contacts[i].F_G.norm()) * contacts[i].n_G;
    }
    for (int f = 0; f < kFingerCount; ++f) {
      for (Link l : finger_links(static_cast<Finger>(f))) {
        if (!link[static_cast<int>(l)]) continue;
        finger[f] = true;
        ++finger_link_count[f];
        finger_normal[f] += link_normal[static_cast<int>(l)];
      }
    }
  }
  bool palm() const { return link[static_cast<int>(Link::kPalm)]; }
  const Eigen::Vector3d& palm_normal() const { return link_normal[static_cast<int>(Link::kPalm)]; }
};

// The project's reading with one opposer (the thumb's or the palm's normal): the fingers beyond
// alpha0 from it, and the links it and they make.
struct Opposition {
  uint8_t fingers = 0;
  int links = 0;
  double min_angle_deg = 180.0;  // of the counted fingers
};

Opposition opposition(const HandTouch& t, const Eigen::Vector3d& n_opposer, int opposer_links,
                      double alpha0_deg) {
  Opposition o;
  o.links = opposer_links;
  for (int f = 1; f < kFingerCount; ++f) {
    if (!t.finger[f]) continue;
    const double a = angle_deg(n_opposer, t.finger_normal[f]);
    if (a <= alpha0_deg) continue;
    o.fingers |= static_cast<uint8_t>(1u << f);
    o.links += t.finger_link_count[f];
    o.min_angle_deg = std::min(o.min_angle_deg, a);
  }
  return o;
}

}  // namespace

GraspCheck evaluate_grasp(const HandContact* contacts, std::size_t count,
                          const Eigen::Vector3d& centroid_G, double mass_kg,
                          const Eigen::Vector3d& gravity_mps2, const GraspParams& params,
                          bool held, const GraspJoint* joint) {
  const HandTouch t(contacts, count);
  GraspCheck check;
  const Residuals residuals = grasp_residuals(contacts, count, centroid_G, mass_kg, gravity_mps2, joint);
  check.residual_force_N = residuals.force_N;
  check.residual_torque_Nm = residuals.torque_Nm;
  for (bool touching : t.link) check.links_in_contact += touching ? 1 : 0;
  for (int f = 0; f < kFingerCount; ++f)
    if (t.finger[f]) check.fingers |= static_cast<uint8_t>(1u << f);
  check.thumb = t.finger[0];
  const bool palm_may_oppose = t.palm() && params.palm_opposition;

  // a held object stays held (kContactTest) while any finger is opposed, by the thumb or (with
  // palm opposition) the palm: a finger that wraps round the object's end does not undo a hold
  for (int f = 1; f < kFingerCount; ++f) {
    if (!t.finger[f]) continue;
    if (check.thumb)
      check.best_opposition_deg = std::max(check.best_opposition_deg, angle_deg(t.finger_normal[0], t.finger_normal[f]));
    if (palm_may_oppose)
      check.best_opposition_deg =
          std::max(check.best_opposition_deg, angle_deg(t.palm_normal(), t.finger_normal[f]));
  }

  const double scale = held ? params.exit_scale : 1.0;
  const double alpha0 = params.alpha0_deg - (held ? params.exit_alpha_margin_deg : 0.0);
  const int min_contacts = held || joint != nullptr ? params.exit_min_contacts : params.min_contacts;
  const bool gesture = params.gesture_rule != GestureRule::kNone;

  // The opposer and the fingers it opposes. The project's reading takes the thumb or the palm,
  // whichever opposes more links (a power grasp wraps the fingers against the palm, the thumb
  // lying on them); the paper's takes the palm only when the thumb does not touch, and then every
  // touching finger must be beyond alpha0.
  bool any_finger = false;
  int counted_links = check.links_in_contact;
  if (params.gesture_rule == GestureRule::kProject) {
    Opposition best;
    bool have = false;
    if (check.thumb) {
      best = opposition(t, t.finger_normal[0], t.finger_link_count[0], alpha0);
      have = true;
    }
    if (palm_may_oppose) {
      const Opposition by_palm = opposition(t, t.palm_normal(), 1, alpha0);
      const bool palm_better =
          !have || (by_palm.fingers != 0 && (best.fingers == 0 || by_palm.links > best.links));
      if (palm_better) {
        best = by_palm;
        check.palm_opposes = true;
        have = true;
      }
    }
    if (have) {
      check.opposed_fingers = best.fingers;
      check.min_thumb_angle_deg = best.min_angle_deg;
      any_finger = best.fingers != 0;
      counted_links = best.links;
    } else {
      check.min_thumb_angle_deg = 180.0;
    }
  } else {
    check.palm_opposes = !check.thumb && palm_may_oppose;
    check.min_thumb_angle_deg = 180.0;
    if (check.thumb || check.palm_opposes) {
      const Eigen::Vector3d& n_opposer = check.thumb ? t.finger_normal[0] : t.palm_normal();
      for (int f = 1; f < kFingerCount; ++f) {
        if (!t.finger[f]) continue;
        any_finger = true;
        const double a = angle_deg(n_opposer, t.finger_normal[f]);
        check.min_thumb_angle_deg = std::min(check.min_thumb_angle_deg, a);
        if (a > alpha0) check.opposed_fingers |= static_cast<uint8_t>(1u << f);
      }
    }
  }
  const bool opposer = check.thumb || check.palm_opposes;
  check.pinch = gesture && !held && opposer && any_finger &&
                (params.gesture_rule != GestureRule::kPaper || check.min_thumb_angle_deg > alpha0);

  // the gesture rule first (off: any contact will do), then eqs. 30-31
  if (check.links_in_contact < (gesture ? min_contacts : 1)) {
    check.verdict = GraspReason::kTooFewContacts;
  } else if (gesture && !opposer && !(held && palm_may_oppose)) {
    check.verdict = GraspReason::kNoThumb;
  } else if (gesture && held) {
    // the paper's re-evaluation while held: any finger opposed by the looser angle
    check.verdict = check.best_opposition_deg <= alpha0 ? GraspReason::kFingersNotOpposed
                                                        : GraspReason::kStableGrasp;
  } else if (gesture && params.gesture_rule == GestureRule::kPaper &&
             (!any_finger || check.min_thumb_angle_deg <= alpha0)) {
    check.verdict = GraspReason::kFingersNotOpposed;
  } else if (gesture && params.gesture_rule == GestureRule::kProject && !any_finger) {
    check.verdict = GraspReason::kFingersNotOpposed;
  } else if (gesture && params.gesture_rule == GestureRule::kProject && counted_links < min_contacts) {
    check.verdict = GraspReason::kTooFewContacts;
  } else {
    check.verdict = GraspReason::kStableGrasp;
  }
  if (check.verdict == GraspReason::kStableGrasp) {
    if (check.residual_force_N > params.xi_N * scale) {
      check.verdict = GraspReason::kForceResidual;
    } else if (check.residual_torque_Nm > params.eta_Nm * scale) {
      check.verdict = GraspReason::kTorqueResidual;
    }
  }
  return check;
}

}  // namespace vcockpit::physics
