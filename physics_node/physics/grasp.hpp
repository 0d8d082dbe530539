#pragma once
// The stable-grasp condition (paper §4.4) for one object and one hand:
//   equilibrium  |sum F| <= xi and |sum M| <= eta (eqs. 30-31) over the hand's contacts on the
//                object plus gravity, moments about the centroid;
//   gesture      read as GraspParams::gesture_rule says (scene.hpp). The project's reading: the
//                thumb touches (or, for a power grasp, the palm), and it and the fingers whose
//                contact normal is more than alpha0 from its own make more than 2 links
//                (min_contacts); a finger touching at less than alpha0 neither counts nor vetoes.
//                The paper's literal reading: more than 2 links, the thumb among them, and every
//                touching finger beyond alpha0. kNone: any contact meeting eqs. 30-31 grasps.
// A link with several contact points counts once, with its force-weighted mean normal; a finger's
// normal is the sum over its touching phalanges.
//
// While held (held true) the test is the paper's re-evaluation at looser thresholds (exit_scale,
// exit_alpha_margin_deg, exit_min_contacts, any finger opposed): hysteresis against the chatter
// the paper describes. Only GraspParams::hold_rule kContactTest lets go on it; the project's
// kTrackedGrip judges the tracked hand's grip instead (grasp_tracker.hpp) and reports these
// figures.
//
// A control (control.hpp) is grasped by the same rule restricted to its joint: the joint carries
// every force and moment but the generalised one, so the equilibrium test is on that alone (the
// hand's and gravity's force along a prismatic joint against xi, their moment about a revolute
// axis against eta: a knob pinched without twisting it), and exit_min_contacts links (by default
// the thumb and one opposed finger) are enough to take it: a pinch turns a knob.

#include <Eigen/Core>

#include <array>
#include <cstddef>
#include <vector>

#include "physics_node/physics/hand_names.hpp"
#include "physics_node/physics/scene.hpp"

namespace vcockpit::physics {

enum class GraspReason : uint8_t {
  kStableGrasp,        // GRASP: every condition held
  kTooFewContacts,     // RELEASE (or no grasp): fewer than min_contacts (held: exit_min_contacts)
  kNoThumb,            // the thumb does not touch
  kFingersNotOpposed,  // no finger opposes the thumb, or one's normal is within alpha0 of it
  kForceResidual,      // eq. 30 fails
  kTorqueResidual,     // eq. 31 fails
  kGloveLost,          // RELEASE: the hand is not tracked any more
  kHandOpened,         // RELEASE: the tracked fingers opened from their grip (release_opening_deg)
  kHandedOver,         // RELEASE: the other hand took it (its own grasp holds it alone)
  kReset,              // RELEASE: the scene was reset (World::reset_objects)
  kThumbLeft,          // RELEASE: the tracked thumb (or opposing palm) left the object's surface
  kFingersLeft,        // RELEASE: every tracked finger opposed at the grasp left its surface
};

const char* grasp_reason_name(GraspReason reason);

// One hand contact on the object.
struct HandContact {
  Link link = Link::kPalm;
  Eigen::Vector3d p_G = Eigen::Vector3d::Zero();
  Eigen::Vector3d n_G = Eigen::Vector3d::Zero();  // unit, from the hand into the object
  Eigen::Vector3d F_G = Eigen::Vector3d::Zero();  // force of the hand on the object (N)
};

struct GraspCheck {
  int links_in_contact = 0;
  bool thumb = false;
  uint8_t fingers = 0;               // bit f: finger f touches
  // the fingers that oppose the grasp's opposer (the thumb, or the palm when palm_opposes) by
  // more than alpha0 (bit f; the thumb's bit never set)
  uint8_t opposed_fingers = 0;
  double min_thumb_angle_deg = 0.0;  // smallest thumb-finger normal angle (180: no finger)
  // the largest angle between a finger's normal and the thumb's or (palm_opposition) the palm's:
  // the hold's test once an object is held (0: no such pair)
  double best_opposition_deg = 0.0;
  bool palm_opposes = false;         // the palm's normal stood for the thumb's (power grasp)
  double residual_force_N = 0.0;
  double residual_torque_Nm = 0.0;
  GraspReason verdict = GraspReason::kTooFewContacts;  // kStableGrasp when it holds
  // The gesture rule but for its count: an opposer and a finger opposed to it (a pinch). Two
  // hands that each pinch an object have more than 2 contact points on it together (the
  // two-handed grasp, GraspTracker::update_free).
  bool pinch = false;
  bool holds() const { return verdict == GraspReason::kStableGrasp; }
  // The gesture rule holds (contacts, thumb or palm, opposition); eqs. 30-31 may not.
  bool gesture_holds() const {
    return verdict == GraspReason::kStableGrasp || verdict == GraspReason::kForceResidual ||
           verdict == GraspReason::kTorqueResidual;
  }
};

// A control's joint, for the grasp test restricted to it.
struct GraspJoint {
  bool revolute = false;
  Eigen::Vector3d axis_G = Eigen::Vector3d::UnitZ();    // unit
  Eigen::Vector3d origin_G = Eigen::Vector3d::Zero();   // a point on the axis
};

// Eqs. 30-31 alone over `contacts` and gravity: |sum F| and |sum M| (about the centroid), or on
// a control's joint the generalised one (in `force_N` for a slider, `torque_Nm` for a knob).
struct Residuals {
  double force_N = 0.0;
  double torque_Nm = 0.0;
};
Residuals grasp_residuals(const HandContact* contacts, std::size_t count,
                          const Eigen::Vector3d& centroid_G, double mass_kg,
                          const Eigen::Vector3d& gravity_mps2, const GraspJoint* joint = nullptr);

// Whether residuals are within eqs. 30-31's thresholds (held: exit_scale looser).
bool residuals_hold(const Residuals& r, const GraspParams& params, bool held);

GraspCheck evaluate_grasp(const HandContact* contacts, std::size_t count,
                          const Eigen::Vector3d& centroid_G, double mass_kg,
                          const Eigen::Vector3d& gravity_mps2, const GraspParams& params,
                          bool held, const GraspJoint* joint = nullptr);

}  // namespace vcockpit::physics
