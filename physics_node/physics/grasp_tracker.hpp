#pragma once
// The grasp tracker (paper §4.4, and what DESIGN.md adds against the chatter the paper
// describes): per object, its grasp state and the decision to attach or release it.
//   attach   the stable-grasp test holds (grasp.hpp), the glove is tracked and the re-grab
//            cooldown since the object's last release has passed: X_HO = X_GH^-1 X_GO (eq. 28),
//            and the object follows the hand, X_GO = X_GH X_HO (eq. 29, the world's motion stage);
//   release  the test (looser while held: hysteresis) has failed for release_delay_s in a row and
//            the object has been held for min_hold_s; at once when the glove is lost. The object
//            leaves with the hand's motion over velocity_window_s (its held poses), so it can be
//            set down or thrown without a jump; a hand slower than settle_speed_mps over
//            settle_window_s is setting it down, and that window's mean is taken instead.
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
  // the tracked fingers that gripped it (bit f) and each one's tightest flexion while held (rad)
  uint8_t grip_fingers = 0;
  std::array<double, kFingerCount> grip_flexion_rad{};
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
};

// The hand at the end of a step, as the decisions see it.
struct HandNow {
  int64_t t_ns = 0;
  bool tracking = true;
  Eigen::Isometry3d X_GH = Eigen::Isometry3d::Identity();
  const JointAngles* tracked_q_rad = nullptr;  // the glove's joints (null: not known)
};

// A finger's flexion: the sum of its flexion joints' angles (rad), abduction left out.
double finger_flexion_rad(const JointAngles& q_rad, Finger finger);

class GraspTracker {
 public:
  GraspTracker(const GraspParams& params, double step_s, const Eigen::Vector3d& gravity_mps2,
               int hand_id);

  int hand_id() const { return hand_id_; }

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

  // The attach/release decision for one dynamic object given its test: attaches (eq. 28) or
  // releases it, appending the event.
  void decide(int object, const GraspCheck& check, const HandNow& hand, GraspHold& hold,
              BodyState& body, std::vector<GraspEvent>& events) const;

  // After the step's decisions: a held object's pose into its ring (for its release velocity).
  void record_held_pose(GraspHold& hold, const BodyState& body) const;

 private:
  void attach(int object, const GraspCheck& check, const HandNow& hand, GraspHold& hold,
              BodyState& body, std::vector<GraspEvent>& events) const;
  void release(int object, GraspReason reason, const GraspCheck& check, const HandNow& hand,
               GraspHold& hold, BodyState& body, std::vector<GraspEvent>& events) const;
  // The held object's velocity over the last `span_steps` steps of its held poses (fewer if it
  // has not been held that long; at least two poses).
  void held_velocity(const GraspHold& hold, std::size_t span_steps, Eigen::Vector3d& v_G,
                     Eigen::Vector3d& w_G) const;
  // How far the gripping fingers opened (rad, mean over them), raising their tightest closure.
  double grip_opening_rad(const HandNow& hand, GraspHold& hold) const;
  GraspEvent event(int object, bool grasp, GraspReason reason, const GraspCheck& check,
                   const HandNow& hand) const;

  GraspParams params_;
  double step_s_;
  Eigen::Vector3d gravity_mps2_;
  int hand_id_;
  std::size_t velocity_span_;  // steps of the release velocity's window
  std::size_t settle_span_;    // ... and of the settle window
  std::size_t window_;         // poses in the release-velocity ring: the longer span + 1
  int64_t regrab_cooldown_ns_;
  int64_t release_delay_ns_;
  int64_t min_hold_ns_;
};

}  // namespace vcockpit::physics
