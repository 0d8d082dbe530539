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

GraspCheck evaluate_grasp(const HandContact* contacts, std::size_t count,
                          const Eigen::Vector3d& centroid_G, double mass_kg,
                          const Eigen::Vector3d& gravity_mps2, const GraspParams& params,
                          bool held, const GraspJoint* joint) {
  // per link: touching, and the force-weighted sum of normals (plain sum if no force yet)
  std::array<bool, kLinkCount> touching{};
  std::array<Eigen::Vector3d, kLinkCount> normal_sum;
  normal_sum.fill(Eigen::Vector3d::Zero());
  for (std::size_t i = 0; i < count; ++i) {
    const HandContact& c = contacts[i];
    const int l = static_cast<int>(c.link);
    touching[l] = true;
    normal_sum[l] += (1e-6 + c.F_G.norm()) * c.n_G;
  }

  GraspCheck check;
  const Residuals residuals = grasp_residuals(contacts, count, centroid_G, mass_kg, gravity_mps2, joint);
  check.residual_force_N = residuals.force_N;
  check.residual_torque_Nm = residuals.torque_Nm;
  // a finger touches if any of its phalanges does; its normal is the sum over them
  std::array<Eigen::Vector3d, kFingerCount> finger_normal;
  std::array<bool, kFingerCount> finger_touching{};
  for (int f = 0; f < kFingerCount; ++f) {
    finger_normal[f].setZero();
    for (Link link : finger_links(static_cast<Finger>(f))) {
      if (!touching[static_cast<int>(link)]) continue;
      finger_touching[f] = true;
      finger_normal[f] += normal_sum[static_cast<int>(link)];
    }
  }
  for (bool t : touching) check.links_in_contact += t ? 1 : 0;
  for (int f = 0; f < kFingerCount; ++f)
    if (finger_touching[f]) check.fingers |= static_cast<uint8_t>(1u << f);
  check.thumb = finger_touching[static_cast<int>(Finger::kThumb)];
  // a power grasp: the palm opposes the fingers when the thumb does not touch (Iberall's
  // palm opposition; the thumb then usually lies on the fingers)
  const bool palm = touching[static_cast<int>(Link::kPalm)];
  check.palm_opposes = !check.thumb && palm && params.palm_opposition;
  check.min_thumb_angle_deg = 180.0;
  check.best_opposition_deg = 0.0;
  bool any_finger = false;
  const auto angle_deg = [](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    return rad_to_deg(std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0)));
  };
  if (check.thumb || check.palm_opposes) {
    const Eigen::Vector3d n_opposer =
        check.thumb ? finger_normal[0] : normal_sum[static_cast<int>(Link::kPalm)];
    for (int f = 1; f < kFingerCount; ++f) {
      if (!finger_touching[f]) continue;
      any_finger = true;
      check.min_thumb_angle_deg = std::min(check.min_thumb_angle_deg, angle_deg(n_opposer, finger_normal[f]));
    }
  }
  // a held object stays held while any finger is opposed, by the thumb or (with palm
  // opposition) the palm: a finger that wraps round the object's end does not undo a hold
  const bool palm_may_oppose = palm && params.palm_opposition;
  for (int f = 1; f < kFingerCount; ++f) {
    if (!finger_touching[f]) continue;
    if (check.thumb)
      check.best_opposition_deg = std::max(check.best_opposition_deg, angle_deg(finger_normal[0], finger_normal[f]));
    if (palm_may_oppose)
      check.best_opposition_deg = std::max(
          check.best_opposition_deg, angle_deg(normal_sum[static_cast<int>(Link::kPalm)], finger_normal[f]));
  }

  const double scale = held ? params.exit_scale : 1.0;
  const double alpha0 = params.alpha0_deg - (held ? params.exit_alpha_margin_deg : 0.0);
  const int min_contacts =
      held || joint != nullptr ? params.exit_min_contacts : params.min_contacts;
  // the gesture rule first (off: any contact will do), then eqs. 30-31
  if (check.links_in_contact < (params.gesture_rule ? min_contacts : 1)) {
    check.verdict = GraspReason::kTooFewContacts;
  } else if (params.gesture_rule && !check.thumb && !check.palm_opposes &&
             !(held && palm_may_oppose)) {
    check.verdict = GraspReason::kNoThumb;
  } else if (params.gesture_rule &&
             (held ? check.best_opposition_deg <= alpha0
                   : (!any_finger || check.min_thumb_angle_deg <= alpha0))) {
    check.verdict = GraspReason::kFingersNotOpposed;
  } else if (check.residual_force_N > params.xi_N * scale) {
    check.verdict = GraspReason::kForceResidual;
  } else if (check.residual_torque_Nm > params.eta_Nm * scale) {
    check.verdict = GraspReason::kTorqueResidual;
  } else {
    check.verdict = GraspReason::kStableGrasp;
  }
  return check;
}

}  // namespace vcockpit::physics
