#pragma once
// The grasp tracker (paper §4.4, and what DESIGN.md adds against the chatter the paper
// describes): per object, its grasp state for each hand and the decision to attach or release it.
//   attach   the stable-grasp test holds (grasp.hpp), the glove is tracked and the re-grab
//            cooldown since the object's last release has passed: X_HO = X_GH^-1 X_GO (eq. 28),
//            and the object follows the hand, X_GO = X_GH X_HO (eq. 29, the world's motion stage);
//   release  (hold_rule kTrackedGrip, the project's) the tracked hand's grip has failed for
//            release_delay_s in a row and the object has been held for min_hold_s: the glove's
//            gripping fingers opened by release_opening_share of their flexion at the grasp, or
//            the tracked thumb (the palm, when it opposed) or every finger opposed at the grasp
//            is release_gap_m farther from the object's surface than at the grasp; at once
//            when the glove is lost. The proxy's contact forces on an attached object do not
//            let go of it: its fingers keep closing onto a body that cannot move to balance
//            them. (kContactTest, the paper's: the stable-grasp test at its looser held
//            thresholds fails instead.) The object leaves with the hand's motion over
//            velocity_window_s (its held poses), so it can be set down or thrown without a
//            jump; a hand slower than settle_speed_mps over settle_window_s is setting it
//            down, and that window's mean is taken instead.
// With several hands, a hand's contacts count only for its own test, and:
//   handover  an object one hand holds that another hand's own test holds (unheld thresholds)
//             goes to that hand in the same step: RELEASE "handed over" by the first, GRASP by
//             the second, the object where it is (no jump);
//   two hands an object no hand holds, that no hand's test holds alone but two hands' do
//             together (eqs. 30-31 over both hands' contacts, each hand meeting the gesture rule
//             on its own), is held by both: it follows both (the world's motion stage). Each hand
//             keeps its own gesture and release rules; when one lets go the other keeps it if
//             its own test (held thresholds) holds alone, else lets go in the same step.
// Events are data: the figures behind each decision. Adapters put them in words
// (physics_node/io/grasp_event_text.hpp).

#include <Eigen/Geometry>
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "physics_node/physics/body.hpp"
#include "physics_node/physics/grasp.hpp"
#include "physics_node/physics/scene.hpp"

namespace vcockpit::physics {

struct GraspEvent {
  int64_t t_ns = 0;
  bool grasp = true;  // false: release
  int hand_id = 0;
  int object = -1;
  GraspReason reason = GraspReason::kStableGrasp;
  // the other hand in a handover (where the object went to or came from) or a two-handed hold
  // (the hand holding it too); -1: none
  int other_hand_id = -1;
  // the stable-grasp test at the decision (for a lost glove: of the last contacts)
  int contacts = 0;  // hand links touching the object
  bool thumb_touching = false;
  bool palm_opposes = false;         // no thumb: the palm opposed the fingers (power grasp)
  double min_thumb_angle_deg = 0.0;  // smallest thumb-finger normal angle (180: no finger)
  double best_opposition_deg = 0.0;  // largest thumb- or palm-finger normal angle
  double residual_force_N = 0.0;     // eq. 30's |sum F|
  double residual_torque_Nm = 0.0;   // eq. 31's |sum M|
};

// One object's grasp state, carried from step to step.
struct GraspHold {
  Eigen::Isometry3d X_HO = Eigen::Isometry3d::Identity();  // eq. 28, valid while held
  int64_t held_since_ns = 0;
  int64_t failing_since_ns = -1;           // the test has failed since then; -1: it holds
  int64_t released_at_ns = INT64_MIN / 2;  // long ago: no cooldown at the start
  std::vector<Eigen::Isometry3d> history;  // pose at the last steps while held (ring)
  std::size_t history_next = 0;
  std::size_t history_count = 0;
  // the tracked fingers that gripped it (bit f) and each one's flexion at the grasp (rad)
  uint8_t grip_fingers = 0;
  std::array<double, kFingerCount> grip_flexion_rad{};
  // ... and each one's greatest flexion since (rad): a grasp is taken while the hand is still
  // closing, and the grip it opens from is the tightest it closed to
  std::array<double, kFingerCount> grip_tightest_rad{};
  // the fingers opposed to the thumb (or the palm, palm_opposed) at the grasp (bit f): the grip
  // the tracked hand must keep (hold_rule kTrackedGrip)
  uint8_t opposed_fingers = 0;
  bool palm_opposed = false;
  // How far each link of the tracked hand, posed on the proxy's wrist, was off the object's
  // surface at the grasp (m; 0 touching or in it). A glove's calibration puts its thumb a few mm
  // off where the proxy's touches, and noise moves it a few more: the tracked thumb or finger
  // leaves when it is release_gap_m farther off than it gripped (World::tracked_links_near).
  std::array<double, kLinkCount> grip_gap_m{};
  // The links (bit l) the proxy keeps a hair off it (ProxyHand::depth_limit_m) after a release:
  // those that touched it, and those whose glove link passes through it during the regrab
  // cooldown; after the cooldown, if the glove has opened from its grip (release_opening_deg),
  // those whose glove link is still in it. The grip's squeeze is the pilot's and goes when the
  // hand lets go: kept, the last finger's penalty depth shoved the released object away (a
  // set-down ball rolled off the console). And a glove's finger that opens through where the
  // object is (a thumb swinging back past a ball) is not pushing it: its proxy, held back
  // behind the object, shoved it as soon as the cooldown ended.
  uint32_t resting_links = 0;
  // From a release until resting_links ends after the cooldown (the glove is clear of it).
  bool hand_clearing = false;
  // Handed over to the other hand: this hand takes it again only once it has let go of it (no
  // contact, or its glove opened from the grip): a grip that lingers past the cooldown would
  // take it straight back.
  bool handed_over = false;
  // This hand appeared inside it: some link of its first input was in it, or it was put back
  // round the hand (World::reset_objects). A tracker that starts with the hand through an object
  // (a hand resting where a virtual object stands) must not fling it: the solver pushed it out
  // of 5 cm of hand in one step (3.5 m/s). The hand passes through it, as the glove's does,
  // until its links are in it no deeper than ProxyParams::pass_through_depth_m (World::
  // pass_through; at once for a hand that appears only touching it); a hand that only partly
  // passed would be pushed by the links inside onto the object with those outside.
  bool passing_through = false;
};

// A hand at the end of a step, as the decisions see it.
struct HandNow {
  int64_t t_ns = 0;
  bool tracking = true;
  Eigen::Isometry3d X_GH = Eigen::Isometry3d::Identity();
  const JointAngles* tracked_q_rad = nullptr;  // the glove's joints (null: not known)
  int hand_id = 0;        // on the topics: 0 right, 1 left
  uint8_t holder_bit = 1;  // its bit in BodyState::holders
};

// The most hands a world simulates (BodyState::holders has a bit per hand).
inline constexpr std::size_t kMaxHands = 8;

// One hand's part in one object's step.
struct HandOnObject {
  HandNow hand;
  const HandContact* contacts = nullptr;  // this hand's links on the object (this step)
  std::size_t count = 0;
  // the links of this hand's glove (tracked) hand that overlap the object now (bit l; needed
  // only while hold->hand_clearing)
  uint32_t glove_links_inside = 0;
  // the links of the tracked hand, posed on the proxy's wrist (the hand's shape, not its lag),
  // no more than release_gap_m farther off the object's surface than at the grasp (bit l;
  // GraspHold::grip_gap_m), or, for a control, where the tracked hand is against the control
  // as it would move it (World::tracked_links_near); known only while this hand holds it and
  // hold_rule is kTrackedGrip, and measured only as far as the verdict needs (the first near link of the thumb or palm, and of one opposed finger)
  bool grip_known = false;
  uint32_t tracked_links_near = 0;
  GraspHold* hold = nullptr;  // this hand's grasp state of the object
};

// A finger's flexion: the sum of its flexion joints' angles (rad), abduction left out.
double finger_flexion_rad(const JointAngles& q_rad, Finger finger);

class GraspTracker {
 public:
  // `hand_mu_s`: the hand material's static friction (a two-handed hold's friction reserve).
  GraspTracker(const GraspParams& params, double step_s, const Eigen::Vector3d& gravity_mps2,
               double hand_mu_s = 1.0);

  // An object's state at the start: a ring of held poses over the velocity window if dynamic.
  GraspHold initial_hold(const ObjectSpec& o) const;

  // One object's step: the stable-grasp test of the hand's contacts on it (eqs. 30-31 and the
  // gesture), then the decision. Objects neither held nor touched are left alone.
  // `glove_links_inside` (bit l): the links of the glove's (tracked) hand that overlap the
  // object now (needed only while hold.hand_clearing).
  // `joint`: the object is a control's part, tested on its joint (grasp.hpp).
  void update(int object, const ObjectSpec& o, const HandContact* contacts, std::size_t count,
              const HandNow& hand, uint32_t glove_links_inside, GraspHold& hold, BodyState& body,
              std::vector<GraspEvent>& events, const GraspJoint* joint = nullptr) const;
  // The same for every hand at once (`hands`, in the world's hand order, each with its own
  // contacts and grasp state): the single-hand rules per hand, plus the handover and the
  // two-handed hold (above). A control (`joint`) is held by one hand at a time (handed over,
  // never held with two).
  void update_hands(int object, const ObjectSpec& o, HandOnObject* hands, std::size_t hand_count,
                    BodyState& body, std::vector<GraspEvent>& events,
                    const GraspJoint* joint = nullptr) const;

  // The attach/release decision for one dynamic object given its test: attaches (eq. 28) or
  // releases it, appending the event. (`h.contacts` are not read: `check` is their test.)
  void decide(int object, const GraspCheck& check, const HandOnObject& h, BodyState& body,
              std::vector<GraspEvent>& events) const;
  // The same for a hand whose tracked grip is not known (its held test alone decides).
  void decide(int object, const GraspCheck& check, const HandNow& hand, GraspHold& hold,
              BodyState& body, std::vector<GraspEvent>& events) const;

  // After the step's decisions: a held object's pose into its ring (for its release velocity).
  void record_held_pose(GraspHold& hold, const BodyState& body) const;

 private:
  void attach(int object, const GraspCheck& check, const HandNow& hand, GraspHold& hold,
              BodyState& body, std::vector<GraspEvent>& events, int other_hand_id = -1) const;
  // While another hand still holds it, the object keeps following that hand: no velocity of
  // its own.
  void release(int object, GraspReason reason, const GraspCheck& check, const HandNow& hand,
               GraspHold& hold, BodyState& body, std::vector<GraspEvent>& events,
               int other_hand_id = -1) const;
  // The cooldown's resting links after a release (GraspHold::resting_links), before the test.
  void clear_hand(const HandOnObject& h, bool held) const;
  // After the decisions: a hand that let go this step names the links that touched it.
  static void note_let_go(const HandOnObject& h);
  bool may_take(const HandOnObject& h) const;  // tracked and past its cooldown
  // The verdict of a held hand's own rules this step (glove lost and hand opened first), and
  // whether it has failed long enough to let go.
  GraspReason held_verdict(const HandOnObject& h, const GraspCheck& check) const;
  // Raises each finger's grip_tightest_rad to the glove's flexion now.
  static void note_tightest_grip(const HandOnObject& h);
  bool failed_long_enough(const HandOnObject& h, GraspReason verdict) const;
  // Eqs. 30-31 over both hands' contacts, less what their static friction could still add: the
  // force and torque residuals that the contacts' friction cones (at their normal forces now)
  // could not take up. Two hands round a resting bar carry no weight yet (the panel does), and
  // held, the object moves with the hands and its contacts' friction no longer carries its
  // weight; the grips' normal forces, and so what they could carry, are there in both.
  Residuals two_hand_residuals(const HandOnObject& a, const HandOnObject& b, const BodyState& body,
                               const ObjectSpec& o) const;
  void update_held_by_one(int object, HandOnObject* hands, std::size_t hand_count,
                          std::size_t holder, const GraspCheck* checks, BodyState& body,
                          std::vector<GraspEvent>& events) const;
  void update_free(int object, const ObjectSpec& o, HandOnObject* hands, std::size_t hand_count,
                   const GraspCheck* checks, BodyState& body, std::vector<GraspEvent>& events,
                   const GraspJoint* joint) const;
  void update_two_handed(int object, const ObjectSpec& o, HandOnObject* hands,
                         std::size_t hand_count, const GraspCheck* checks, BodyState& body,
                         std::vector<GraspEvent>& events) const;
  // The held object's velocity over the last `span_steps` steps of its held poses (fewer if it
  // has not been held that long; at least two poses).
  void held_velocity(const GraspHold& hold, std::size_t span_steps, Eigen::Vector3d& v_G,
                     Eigen::Vector3d& w_G) const;
  // The gripping fingers' mean flexion at the grasp and how far they have opened from it (rad);
  // zeros when the glove's joints or the grip are not known.
  struct GripFlexion {
    double at_grasp_rad = 0.0;
    double opening_rad = 0.0;
    double from_tightest_rad = 0.0;  // how far they have opened from the tightest since
  };
  static GripFlexion grip_flexion(const HandNow& hand, const GraspHold& hold);
  // The glove opened from its grip: by release_opening_share of the grasp's flexion and by at
  // least release_opening_deg.
  bool hand_opened(const HandNow& hand, const GraspHold& hold) const;
  // The tracked hand's grip on a held object (kTrackedGrip): kStableGrasp while its thumb (or
  // opposing palm) and one finger opposed at the grasp stay within release_gap_m.
  GraspReason tracked_grip_verdict(const HandOnObject& h) const;
  GraspEvent event(int object, bool grasp, GraspReason reason, const GraspCheck& check,
                   const HandNow& hand, int other_hand_id) const;

  GraspParams params_;
  double step_s_;
  Eigen::Vector3d gravity_mps2_;
  double hand_mu_s_;
  std::size_t velocity_span_;  // steps of the release velocity's window
  std::size_t settle_span_;    // ... and of the settle window
  std::size_t window_;         // poses in the release-velocity ring: the longer span + 1
  int64_t regrab_cooldown_ns_;
  int64_t release_delay_ns_;
  int64_t min_hold_ns_;
};

}  // namespace vcockpit::physics
