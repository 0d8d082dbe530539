#pragma once
// The proxy hand: the hand that touches the world follows the tracked hand through bounded
// coupling, so a real glove's hand that closes into an object or sinks into a panel does not
// drive the simulated one there. A god-object per link (Zilles & Salisbury 1995, carried to whole
// hands by Borst & Indugula 2005 and Jacobs & Froehlich 2011): the proxy goes where the tracked
// hand goes as far as the world lets it, and each step
//
//   1. heads for the tracked pose (moved by the fingers' pull, World::finger_pull_G) at bounded
//      speed (step_goal): the wrist at max_speed_mps / max_spin_radps, or
//      push_speed_mps while a link pushes a free object, so no hand motion imparts more than
//      about push_speed_mps to an object it pushes;
//   2. after the narrowphase at that tentative pose, holds each finger back (constrain) where
//      its own joints would take a link deeper than
//        static_depth_m into a static object, or
//        d_grip = grip_force_N / k_pair into any object (k_pair the hand-object series
//        stiffness, so the penalty force of eq. 11 a finger can apply is bounded), or
//        push_speed_mps * dt deeper in one step into a free object;
//      a finger's joints move by the largest fraction s in [0, 1] of their step that keeps those
//      limits, to first order in s (the depth change of each contact point along its normal);
//   3. bends each finger still beyond those depth limits back out (the first-order step of 2
//      can overshoot after a large joint motion, and the wrist can carry a finger into a
//      panel): a damped least-squares step of its joints along the depth gradient of its
//      contacts farthest beyond their limits, within the joints' ranges, so fingers wrapped
//      round a handle on a panel lie on the panel instead of lifting the whole hand;
//   4. then translates the whole proxy (wrist, links and the objects it holds) by the least
//      shift that brings every contact of theirs with a static object within static_depth_m and
//      with a free object within d_grip (Gauss-Seidel projection over the contact planes, which
//      is exact for one plane and converges for the corners of boxes).
//
// So a link never ends more than static_depth_m inside a static object, a held object's fingers
// stop at d_grip instead of closing into it (its grasp residual stays bounded), and an object
// squeezed between the hand and a panel feels at most grip_force_N per contact. The contact
// lists are updated to the pose the proxy ends at, so the forces and the grasp test (eqs. 30-31)
// act on the proxy's contacts.

#include <Eigen/Geometry>

#include <array>
#include <cstdint>
#include <vector>

#include "hand/kinematics_memo.hpp"
#include "physics_node/physics/contact.hpp"
#include "physics_node/physics/finger_jacobian.hpp"
#include "physics_node/physics/hand_names.hpp"
#include "physics_node/physics/scene.hpp"

namespace vcockpit::physics {

struct HandInput;

// How far a link that has let go of an object stands off it until the regrab cooldown ends.
inline constexpr double kLetGoClearance_m = 5e-4;

struct ProxyPose {
  Eigen::Isometry3d X_GH = Eigen::Isometry3d::Identity();
  JointAngles q_rad{};
};

// The farthest the fingers pull the wrist from the tracked one (ProxyParams::finger_pull_ratio):
// a tracked hand that has gone through an object does not drag the drawn one far off.
inline constexpr double kMaxFingerPull_m = 0.02;

// The most static surfaces the proxy keeps as resting on between steps.
inline constexpr int kMaxBlockingPlanes = 4;

// What constrain() did in one step.
struct ProxyConstraint {
  Eigen::Vector3d shift_G = Eigen::Vector3d::Zero();  // the proxy's translation out of contact
  bool pushing = false;         // a hand link or held object touches a free object
  bool fingers_held = false;    // some finger moved less than its step
};

class ProxyHand {
 public:
  // The proxy of the scene's hand `hand`; `scene` must outlive this. Its contact lists hold
  // this hand's links (bodies link_base + link, CollisionWorld's numbering) and no other hand's.
  explicit ProxyHand(const Scene& scene, int hand = 0);

  // The pose the proxy heads for over the coming step of `step_s`: the tracked hand, approached
  // at the free speeds, or the pushing speed when `pushing`.
  // The wrist's motion goes along, never into, the static surfaces in `blocking_out_G` (the last
  // step's constrain_wrist). While `holding`, the wrist moves as the tracked
  // hand does over the step (`tracked_from` to `tracked`) and closes its lag behind it at no
  // more than the pushing speed.
  // `fk` is this hand's forward kinematics (the goal's answer is kept there for the step).
  ProxyPose step_goal(const ProxyPose& now, const HandInput& tracked_from,
                      const HandInput& tracked, bool pushing, bool holding,
                      const std::vector<Eigen::Vector3d>& blocking_out_G, double step_s,
                      hand::KinematicsMemo& fk) const;

  // Holds the tentative `pose` (links X_HL in `links`, in the world X_GL) back from the contacts
  // the narrowphase found there (`contacts`: with dynamic objects; `hand_static`: with static
  // ones), as the header says, in two parts: the fingers (steps 2 and 3), after which the caller
  // recomputes `hand_static` at the new link poses when they moved (true), then the wrist
  // (step 4). `prev` and `prev_links` are the proxy one step ago; `held` flags the held
  // objects (1), which move with the wrist: the caller shifts them by shift_G. Both update pose,
  // links, X_GL and the contact lists (depths and points to first order, dropping contacts no
  // longer touching) to the pose the proxy ends at.
  bool constrain_fingers(const ProxyPose& prev, const HandLinkPoses& prev_links, ProxyPose& pose,
                         HandLinkPoses& links, std::array<Eigen::Isometry3d, kLinkCount>& X_GL,
                         const std::vector<uint8_t>& held, std::vector<ContactPoint>& contacts,
                         std::vector<ContactPoint>& hand_static, double dt_s);
  // `blocking_out_G` receives the directions out of the static surfaces the proxy (or an object
  // it holds) ends on at its depth limit: at most kMaxBlockingPlanes, no two alike.
  ProxyConstraint constrain_wrist(ProxyPose& pose, std::array<Eigen::Isometry3d, kLinkCount>& X_GL,
                                  const std::vector<uint8_t>& held,
                                  std::vector<ContactPoint>& contacts,
                                  std::vector<ContactPoint>& hand_static,
                                  std::vector<Eigen::Vector3d>& blocking_out_G);

  // Whether object `object` holds back a finger that meets it, so that the finger pulls the
  // wrist (ProxyParams::finger_pull_ratio, World::finger_pull_G): a loose dynamic object
  // weighing at least grip_force_N (a lighter one is pushed along), or the handle of a lever
  // that turns about a pivot (its joint holds it, and a hand closes round it as round a bar).
  // Not a knob, which fingertips pinch on their own, nor a button, a switch or a sliding lever's
  // knob (the gear's), which one finger pushes: a push needs no centring, and the pressing
  // gestures keep their events.
  bool holds_fingers_back(int object) const {
    return holds_fingers_back_[static_cast<std::size_t>(object)] != 0;
  }

  // How deep a link may go into object `object` (m): static_depth_m for a static one, d_grip
  // for a dynamic one.
  double depth_limit_m(int object) const { return depth_limit_m_[static_cast<std::size_t>(object)]; }
  // ... and link body `link_body` (a link or not: a held object): a link that has just let go
  // of an object (GraspHold::resting_links) stands off it by kLetGoClearance_m, so neither the
  // grip's penalty depth nor a contact's damping follows the released object.
  // On a held object the grip is balanced (balance_held_grips): of the thumb and palm on one
  // side and the fingers opposing them on the other, the side that could press harder along
  // the grip's axis goes in only as deep as lets it press as hard as the other.
  double depth_limit_m(int object, int link_body) const {
    if (!is_link(link_body)) return depth_limit_m(object);
    const auto o = static_cast<std::size_t>(object);
    const int l = link_body - link_base_;
    if (resting_links_ != nullptr && ((*resting_links_)[o] >> l & 1u) != 0)
      return -kLetGoClearance_m;
    const GripBalance& g = grip_balance_[o];
    return depth_limit_m(object) *
           (opposes_fingers(static_cast<Link>(l)) ? g.opposing_scale : g.finger_scale);
  }
  // For each held object (`held`: 1) in `contacts`, balances its grip for depth_limit_m: with
  // equal depths a thumb against two or three fingers presses half or a third as hard as they
  // do together, and an attached object cannot move to balance that (a thumb against three
  // fingers on the 250 g torch left 12-15 N of residual, eq. 30, and let it go mid-air). The
  // side with more to give (a grip force per thumb or palm link; per finger link, its share
  // along the axis the thumb and palm push on) is scaled down to the other's. constrain_fingers
  // calls it on every step's contacts.
  void balance_held_grips(const std::vector<ContactPoint>& contacts,
                          const std::vector<uint8_t>& held);

  // The links resting on each object (bit l), per object; null: none. Kept by the caller.
  void set_resting_links(const std::vector<uint32_t>* resting_links) { resting_links_ = resting_links; }

 private:
  bool is_link(int body) const { return body >= object_count_; }
  static bool opposes_fingers(Link link) {
    return link == Link::kPalm || link == Link::kThumbProximal || link == Link::kThumbMiddle ||
           link == Link::kThumbDistal;
  }

  // Scales each finger's joint motion from `now_rad` to `goal_rad` so that none of its links'
  // origins and its tip moves farther than `reach_m` (in the hand's frame): a finger catches up
  // with the tracked one at bounded speed, as the wrist does, so a finger that the world held
  // back and then lets go does not jump through a panel in one step.
  void limit_finger_speed(const JointAngles& now_rad, double reach_m, JointAngles& goal_rad,
                          hand::KinematicsMemo& fk) const;
  Link link_of(int body) const { return static_cast<Link>(body - link_base_); }
  void hold_back_fingers(const ProxyPose& prev, const HandLinkPoses& prev_links, ProxyPose& pose,
                         HandLinkPoses& links, std::array<Eigen::Isometry3d, kLinkCount>& X_GL,
                         const std::vector<uint8_t>& held, std::vector<ContactPoint>& contacts,
                         std::vector<ContactPoint>& hand_static, double dt_s,
                         ProxyConstraint& result);
  // Moves a held-back finger (at `share` of its step to `q_goal_rad`) on by what is left of its
  // step with the part that would take its binding contacts deeper taken out: the finger slides
  // along what stopped it toward the tracked one, as a god-object slides along a surface,
  // instead of sticking where it first touched.
  void slide_finger(Finger finger, double share, const JointAngles& q_goal_rad, ProxyPose& pose);
  void bend_out(ProxyPose& pose, HandLinkPoses& links,
                          std::array<Eigen::Isometry3d, kLinkCount>& X_GL,
                          std::vector<ContactPoint>& contacts,
                          std::vector<ContactPoint>& hand_static, ProxyConstraint& result);
  // Puts the links at `pose` (forward kinematics; `links` are those of the joint angles
  // `links_q_rad`) and carries every hand contact with its link.
  void move_links(const JointAngles& links_q_rad, const ProxyPose& pose, HandLinkPoses& links,
                  std::array<Eigen::Isometry3d, kLinkCount>& X_GL,
                  std::vector<ContactPoint>& contacts, std::vector<ContactPoint>& hand_static);
  void shift_out(std::array<Eigen::Isometry3d, kLinkCount>& X_GL, ProxyPose& pose,
                 const std::vector<uint8_t>& held, std::vector<ContactPoint>& contacts,
                 std::vector<ContactPoint>& hand_static, ProxyConstraint& result,
                 std::vector<Eigen::Vector3d>& blocking_out_G);
  // Gauss-Seidel passes over planes_ (only the panels' when `panels_only`) that grow `shift_G`
  // until each plane's contact is within its limit.
  void project_shift(bool panels_only, Eigen::Vector3d& shift_G) const;

  const Scene& scene_;
  const HandModel& hand_;
  const ProxyParams& params_;
  int object_count_;
  int link_base_;  // body of this hand's palm
  std::vector<double> depth_limit_m_;                        // per object
  const std::vector<uint32_t>* resting_links_ = nullptr;     // per object
  std::vector<uint8_t> dynamic_;                             // per object
  std::vector<uint8_t> holds_fingers_back_;                  // per object
  struct GripBalance {  // depth limit scales of a held object's grip, this step
    double opposing_scale = 1.0;  // thumb and palm
    double finger_scale = 1.0;    // index to little
  };
  std::vector<GripBalance> grip_balance_;  // per object
  std::array<std::array<bool, kJointCount>, kFingerCount> finger_joints_{};  // joints moving a finger
  std::array<FingerJoints, kFingerCount> finger_joint_list_{};  // the same, as indices in order

  // scratch
  struct Plane {
    Eigen::Vector3d out_G;  // the direction that takes the proxy out
    double depth_m;         // at zero shift
    double limit_m;
    bool blocking;          // a static surface: it blocks the wrist's next motion
  };
  std::vector<Plane> planes_;
  HandLinkPoses probe_links_;
  hand::FingerChainCache chain_;  // a finger's chain at its pose, for its Jacobian's probes
  struct ContactLimit {  // a finger contact as hold_back_fingers saw it
    const ContactPoint* contact;
    Link link;
    Finger finger;
    Eigen::Vector3d p_L;  // the contact point on its link
    double deepened_m;    // by the finger's step
    double allowed_m;     // how much deeper than before the step it may go
  };
  std::vector<ContactLimit> limits_;
  struct SlideRow {
    std::size_t limit;  // in limits_
    Eigen::Matrix<double, kMaxFingerJoints, 1> gradient_m;  // depth gained per radian of each finger joint
    double room_m;      // how much deeper it may go from the held-back pose
    bool active;        // in the slide's active set: projected off
  };
  std::vector<SlideRow> slide_rows_;
  std::vector<FingerPoint> slide_points_;  // the rows' contact points, for the Jacobian
  HandLinkPoses slide_links_;
};

}  // namespace vcockpit::physics
