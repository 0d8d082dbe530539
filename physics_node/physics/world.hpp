#pragma once
// One world step (paper §4, Box2D's b2World_Step in spirit), in named, timed stages:
//   proxy goal -> hand kinematics -> broadphase -> narrowphase -> proxy hand -> virtual forces
//   -> motion -> body check -> grasp test on the step's contacts: attach (eqs. 28-29) or release.
// The contact springs of eqs. 11-19 are soft constraints (contact_solver.hpp), stable at the full
// step: one collision and one solve a step, whatever the stiffness. The world orchestrates; each
// stage is a system of its own file.
//
// Deterministic: fixed steps, no clock in the results (stage timings are observations only),
// every container iterated in a fixed order. The same scene and inputs give bit-identical states.
//
// Constant model, mutable state (MuJoCo's mjModel / mjData): the Scene never changes; a
// WorldState (world_state.hpp) holds everything that carries from step to step, and the rest
// of the world is per-step scratch. state() / restore() take and put back that state.
//
// The stages live in their own files: collision and manifold_clipper (contacts), proxy_hand (the
// hand that stops at surfaces), contact_solver with normal_force / friction_force (eqs. 11-19),
// integrator (eqs. 20-25),
// control_system (the cockpit's controls), body_check, grasp and grasp_tracker (eqs. 28-31).

#include <Eigen/Geometry>

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "physics_node/physics/body.hpp"
#include "physics_node/physics/body_check.hpp"
#include "physics_node/physics/broadphase.hpp"
#include "physics_node/physics/collision.hpp"
#include "physics_node/physics/contact_solver.hpp"
#include "physics_node/physics/control_system.hpp"
#include "physics_node/physics/grasp.hpp"
#include "physics_node/physics/grasp_tracker.hpp"
#include "physics_node/physics/proxy_hand.hpp"
#include "physics_node/physics/scene.hpp"
#include "physics_node/physics/sleep.hpp"
#include "physics_node/physics/world_state.hpp"

namespace vcockpit::physics {

// In the order a step runs them; each is timed where it runs and nowhere else.
enum class Stage : uint8_t {
  kProxyGoal, kHandKinematics, kBroadphase, kNarrowphase, kProxyHand, kForces, kIntegrate,
  kBodyCheck, kGrasp, kCount
};
constexpr int kStageCount = static_cast<int>(Stage::kCount);
const char* stage_name(Stage stage);

struct StageTimes {
  std::array<int64_t, kStageCount> ns{};  // wall time per stage over the last step
  bool timed = true;  // the last step was timed (World::set_stage_timing_every)
};

// Hand-object penetration over the last step (m), and the deepest link in a static object.
struct PenetrationStats {
  double max_m = 0.0;
  double sum_m = 0.0;
  int points = 0;
  double static_max_m = 0.0;
};

class World {
 public:
  explicit World(Scene scene);
  ~World();

  // Hands are numbered 0 .. hand_count() - 1 in the scene's order (Scene::hands); hand_id(h) is
  // the id the topics use (0 right, 1 left). Accessors taking a hand default to the first.
  int hand_count() const { return static_cast<int>(hands_.size()); }
  int hand_id(int hand = 0) const { return hands_[static_cast<std::size_t>(hand)].hand_id; }
  // The hand with topic id `hand_id`, or -1.
  int hand_index(int hand_id) const;

  // Hand `hand` from now on (reached by the next step).
  void set_hand_input(const HandInput& input, int hand = 0);
  void step();

  // Everything that carries from step to step; a world restored to it (from this world or
  // another of the same scene) steps bit-identically to the one it was taken from. The state
  // must come from a world of the same scene (checked: sizes).
  const WorldState& state() const { return state_; }
  void restore(const WorldState& state);

  const Scene& scene() const { return scene_; }
  // A control's joint as the grasp test sees it (nullptr: a free object).
  const GraspJoint* grasp_joint_of(int object) const { return controls_.grasp_joint_of(object); }
  int64_t time_ns() const { return state_.time_ns; }
  uint64_t step_count() const { return state_.steps; }
  bool hand_active(int hand = 0) const {
    return !hands_.empty() && state_.hands[static_cast<std::size_t>(hand)].active;
  }

  const std::vector<BodyState>& bodies() const { return state_.bodies; }
  // The hand that touches the world (the proxy's, when the scene has one): what is drawn.
  const Eigen::Isometry3d& X_GH(int hand = 0) const { return hand_state(hand).X_GH; }
  const std::array<Eigen::Isometry3d, kLinkCount>& X_GL(int hand = 0) const {
    return hand_state(hand).X_GL;
  }
  // The tracked hand's links (of the input last set: at the end of the last step until the next
  // input is set), and how far the farthest link origin or fingertip of the proxy is from them
  // (m; 0 without a proxy). Computed on demand; a read between steps changes no step.
  bool has_proxy() const { return !hands_.empty() && hands_[0].proxy.has_value(); }
  const std::array<Eigen::Isometry3d, kLinkCount>& tracked_X_GL(int hand = 0) const {
    observe_tracked_hand(hand);
    const HandSim& sim = hands_[static_cast<std::size_t>(hand)];
    return sim.proxy ? sim.tracked_X_GL : hand_state(hand).X_GL;
  }
  double tracked_offset_m(int hand = 0) const {
    observe_tracked_hand(hand);
    return hands_[static_cast<std::size_t>(hand)].tracked_offset_m;
  }
  // Pose of the held object in hand `hand`'s frame (eq. 28), valid while that hand holds it.
  const Eigen::Isometry3d& X_HO(int object, int hand = 0) const {
    return hand_state(hand).grasp[static_cast<std::size_t>(object)].X_HO;
  }

  // Sets control `control` to its position `position` (a flight model's or an instructor's
  // command): the coordinate goes to the position's (a latching button's latch with it), at
  // rest, and the change is a control event caused by the command at the next step. Refused
  // (false) for an unknown control or position, and while a hand holds the control: the physics
  // stays the authority.
  bool command_control(int control, int position);

  // An instructor's reset: the objects and controls as `saved` has them (the scene's start, or
  // a checkpoint), each at rest or moving as it was then. Unlike restore(), time goes on and
  // the hands stay where their gloves put them: what they held is let go (a RELEASE "scene
  // reset" in step_events()), and a control whose position changes reports it as commanded
  // (control_events()); both lists are this call's until the next step. An object put back round
  // a hand that stands where it was is passed through until the hand is clear of it
  // (GraspHold::passing_through), as by a hand that appears inside one. `saved` must be a state
  // of this scene (asserted).
  void reset_objects(const WorldState& saved);

  // Observations of the last step (empty after a restore until the next step).
  const std::vector<GraspEvent>& step_events() const { return events_; }
  const std::vector<ControlEvent>& control_events() const { return controls_.events(); }
  const std::vector<AppliedContact>& contacts() const { return applied_; }
  const StageTimes& stage_times() const { return stage_times_; }
  // Times the stages of one step in `steps` (1, the default: every step): two clock reads per
  // stage cost a few per cent of a small scene's step, which a run as fast as it can go (the
  // offline runner) need not pay. A timed step reports its times multiplied by `steps`, the
  // others none, so sums over a run estimate its totals.
  void set_stage_timing_every(int steps);
  // over every hand
  const PenetrationStats& hand_penetration() const { return penetration_; }

  // Bodies found broken after a step and put back (body_check.hpp): every object ever found,
  // with its count, and those found for the first time in the last step (for the adapters to
  // name once). Diagnostics of this world: restore() keeps them.
  const std::vector<BodyFault>& body_faults() const { return body_check_.faults(); }
  const std::vector<BodyFault>& step_faults() const { return body_check_.new_faults(); }

 private:
  // One simulated hand: its model's id, proxy and per-step scratch (its state is in
  // WorldState::hands).
  struct HandSim {
    int hand_id = 0;
    uint8_t holder_bit = 1;  // BodyState::holders
    std::optional<ProxyHand> proxy;  // a scene with proxy.enabled
    std::vector<uint8_t> held_mask;      // 1 for the objects it held at the start of this step
    bool holds_any = false;              // ... any of them
    std::vector<uint32_t> resting_links;  // GraspHold::resting_links at the start of this step
    std::array<Eigen::Isometry3d, kLinkCount> X_GL_before;  // the links one step ago
    HandLinkPoses link_poses;
    // this hand's forward kinematics: the proxy now, the tracked hand and the goal, each once a
    // step (the grasp stage's view of the glove is const)
    mutable std::optional<hand::KinematicsMemo> fk;
    HandLinkPoses proxy_prev_links;  // the proxy's links at the start of this step, in H
    ProxyPose proxy_prev;            // the proxy at the start of this step
    ProxyPose proxy_goal;            // where the proxy heads over this step
    bool proxy_prev_links_valid = false;  // false after a restore: recomputed from the state
    std::vector<ContactPoint> contacts;     // its share of this step's contacts (the proxy's)
    std::vector<ContactPoint> hand_static;  // its links against static objects
    std::vector<HandContact> on_object;     // the grasp stage's: its contacts on one object
    mutable std::array<Eigen::Isometry3d, kLinkCount> tracked_X_GL;
    mutable double tracked_offset_m = 0.0;
    mutable bool tracked_observed = false;
  };

  const HandState& hand_state(int hand) const { return state_.hands[static_cast<std::size_t>(hand)]; }
  void aim_proxies(bool holding);  // each proxy's goal for the step; holding: a hand holds an object
  void advance(double dt_s);       // the step's motion, collision, proxies, solve and integration
  void move_hand(int hand);
  void place_hand(int hand, const Eigen::Isometry3d& X_GH, const JointAngles& q_rad);
  // The proxies after the narrowphase: each hand's share of the contacts, constrained, then
  // put back in order.
  void constrain_proxies(double dt_s);
  void constrain_proxy(int hand, double dt_s);
  void observe_tracked_hand(int hand) const;  // on demand: one forward kinematics a step
  // HandState::finger_pull_G at the end of a step, from its contacts.
  Eigen::Vector3d finger_pull_G(int hand) const;
  // The links of hand `hand`'s glove (tracked) hand that overlap `object` now (bit l); 0 unless
  // that hand is clearing it after a release (GraspHold::hand_clearing), the only time they
  // matter.
  uint32_t glove_links_inside(int hand, int object, const GraspHold& hold) const;
  // At a hand's first input, or after a reset: each object that is not static and that one of
  // its links overlaps is one it may pass through (GraspHold::passing_through).
  void note_objects_around(int hand);
  // After the narrowphase: once a hand's contacts with an object it passes through are none or
  // no deeper than ProxyParams::pass_through_depth_m, it is clear of it, and they stay, as any
  // contact (a hand that appears touching an object pushes it out as one that moved there);
  // until then they are dropped (neither the proxy nor the solver sees them).
  void pass_through();
  void count_passing_through();  // passing_through_ from the state
  // The links of the tracked hand, posed on the proxy's wrist, within grasp.release_gap_m of a
  // held object (HandOnObject::tracked_links_near): the grip the pilot's hand makes round it,
  // whatever the lag of the proxy's wrist. For a held control, a link where the tracked hand
  // is, carried back by the joint motion the control has yet to make towards that hand, counts
  // too (the proxy's wrist, catching up, does not move round the joint).
  // Only the links the verdict needs are measured, tips first: the opposer's (the thumb's, or the
  // palm) until one is near, then the opposed fingers' until one is near.
  uint32_t tracked_links_near(int hand, int object, const GraspHold& hold) const;
  // At a grasp: how far each link of the tracked hand, posed as tracked_links_near poses it, is
  // off the object (GraspHold::grip_gap_m).
  void note_grip_gaps(int hand, int object, GraspHold& hold) const;
  // Where a held object is: eq. 29 for one hand, the mean of both hands' held poses for two.
  Eigen::Isometry3d held_pose(int object) const;
  void move_held_objects(double dt_s);
  void build_contact_bodies();
  void forget_anchors_of_recovered_bodies();
  void integrate(double dt_s);  // positions from the solver's velocities
  // Sleeping (sleep.hpp): the broadphase told which objects sleep; the islands a contact of
  // this step reaches woken (true if any woke); after a step, which objects may sleep and
  // the sleep tracker's update.
  void tell_sleepers();
  bool wake_touched();
  void update_sleep();
  void grasp_stage();
  void name_holders();  // BodyState::held_by from holders
  int holder_of(const BodyState& body) const;  // the first hand holding it, or -1

  // the model and the stages: built once; what they keep between steps (sweep orders, work
  // space) never changes a result, which is why a restored world steps like the original
  Scene scene_;
  CollisionWorld collision_;
  SoftContactSolver soft_;
  std::vector<uint8_t> touched_;     // the dynamic bodies the solver moved this step
  std::vector<SolverJoint> joints_;  // the controls in a contact, as the solver's joints
  GraspTracker grasp_tracker_;
  BodyCheck body_check_;
  SleepTracker sleep_;
  std::vector<HandSim> hands_;  // per hand; never resized after construction (proxies point in)
  int object_count_;
  int64_t step_ns_;
  std::vector<Eigen::Matrix3d> I_O_inv_;  // inverse body-frame inertia, dynamic objects

  WorldState state_;
  ControlSystem controls_;  // moves state_'s controls (after state_: it keeps a reference)

  // scratch: rebuilt every step before it is read
  std::vector<Eigen::Isometry3d> X_GO_;         // collision input, all objects
  std::vector<uint8_t> held_mask_;              // 1 for the objects any hand held at the start of this step
  std::vector<uint8_t> may_sleep_;              // per object, at the end of a step (update_sleep)
  std::vector<double> deepest_in_;              // pass_through's, per hand and object (m; -1 apart)
  // the holds with GraspHold::passing_through set, derived from the state (kept by
  // count_passing_through after each change: a hand's first input, a reset, pass_through and
  // restore) so that a step without any scans none
  int passing_through_ = 0;
  std::vector<BodyState> start_bodies_;         // the bodies at the start of this step
  std::vector<HandOnObject> on_object_;         // the grasp stage's, per hand
  std::vector<ContactPoint> contacts_;
  std::vector<ContactPoint> hand_static_;  // every hand's links against static objects
  std::vector<ContactPoint> merged_;       // the contacts no proxy takes
  std::vector<const std::vector<ContactPoint>*> merge_lists_;  // merged_ and each hand's share
  std::vector<ContactBody> contact_bodies_;
  // observations of the last step
  std::vector<AppliedContact> applied_;
  std::vector<GraspEvent> events_;
  StageTimes stage_times_;
  int stage_timing_every_ = 1;
  PenetrationStats penetration_;
};

}  // namespace vcockpit::physics
