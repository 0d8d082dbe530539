#pragma once
// Cockpit controls: articulated virtual objects on one degree of freedom (DESIGN.md, "Controls").
// A control's moving part is an object of the scene (it collides, is drawn and is hashed like any
// other); the control owns its motion. Its coordinate q (m along the axis for a prismatic joint,
// rad about it for a revolute one) moves under
//   - the virtual forces of eqs. 11-19 on its body, projected onto the joint: the generalised
//     force is their work along it, Q = F . a (prismatic) or a . (M_c + (c - o) x F) (revolute,
//     o on the axis, c the centroid), gravity included;
//   - its own mechanism: a spring toward q_rest (k), a damper (c), Coulomb friction, detents (a
//     restoring force of peak strength within half_width of each detent), an over-centre snap
//     (a constant force pushing away from snap_centre, toward the nearer end: bistable), the
//     travel limits and gates (stops that open only while a grasping hand lifts the lever);
// integrated like eqs. 20-25 on q, the linear spring and damper exactly (the closed-form motion
// of M q'' + c q' + k (q - q_rest) = Q over the step, the other forces held over it): a
// button's spring is stiff for its few grams (a period of ~10 ms), which an implicit Euler step
// of 1 ms would damp away.
// A grasped control follows the hand projected onto its degree of freedom (eq. 29 restricted to
// the joint): a rotary knob turns with the hand's rotation about its axis, a lever and a slider
// with the motion of the point of the hand that holds them.
//
// Its discrete position (a button's out/pressed or off/on, a switch's down/up, a selector's
// detent) changes with hysteresis: each position has a capture interval of q, and the position
// changes only when q enters another position's interval, so a coordinate that hovers at a
// threshold does not chatter.

#include <Eigen/Geometry>

#include <cstdint>
#include <string>
#include <vector>

namespace vcockpit::physics {

enum class JointKind : uint8_t { kPrismatic, kRevolute };

// The most named positions a control has (cockpit/control_info carries a fixed array of them).
inline constexpr int kMaxControlPositions = 8;

enum class ControlKind : uint8_t { kPushButton, kToggle, kRotary, kLever, kGuard };
const char* control_kind_name(ControlKind kind);

struct Detent {
  double q = 0.0;           // where it holds (m or rad)
  double strength = 0.0;    // peak restoring force (N) or torque (N m)
  double half_width = 0.0;  // it acts within this of q (m or rad)
};

// A stop at q that the coordinate crosses only while a grasping hand has lifted the lever by
// lift_m since it grasped it: pulled out along the lever, away from its pivot (revolute), or
// along X_GJ's x axis (prismatic).
struct Gate {
  double q = 0.0;
  double lift_m = 0.01;
};

// A discrete position: its name, and the interval of q in which the control takes it.
struct ControlPosition {
  std::string name;
  double q = 0.0;           // the nominal coordinate (commands go there)
  double enter_lo = 0.0;    // q in [enter_lo, enter_hi]: the control takes this position
  double enter_hi = 0.0;
};

struct ControlSpec {
  std::string name;
  ControlKind kind = ControlKind::kPushButton;
  JointKind joint = JointKind::kPrismatic;
  int body = -1;  // the object that moves (Scene::objects)
  // The joint frame at q = 0: its z axis is the joint's axis (the direction of positive q), its
  // origin on the axis; x is the lift direction of a gated lever. The body's centroid frame in
  // it at q = 0 is X_JO.
  Eigen::Isometry3d X_GJ = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d X_JO = Eigen::Isometry3d::Identity();
  bool limited = true;  // false: a continuous rotary (no travel limits)
  double q_min = 0.0;
  double q_max = 0.0;
  double q_initial = 0.0;
  double q_rest = 0.0;     // the spring's rest coordinate
  double stiffness = 0.0;  // N/m or N m/rad
  double damping = 0.0;    // N s/m or N m s/rad
  double friction = 0.0;   // Coulomb: N or N m
  double snap = 0.0;       // over-centre force or torque (0: none)
  double snap_centre = 0.0;
  std::vector<Detent> detents;
  double detent_period = 0.0;  // > 0: detents[0] repeats every period (a continuous knob's clicks)
  std::vector<Gate> gates;
  std::vector<ControlPosition> positions;  // ordered by q
  // A latching push button (push-on / push-off): each press that reaches the "pressed"
  // position's interval toggles the latch, and while latched the spring rests at latch_q.
  bool latching = false;
  double latch_q = 0.0;
  int lit_when = -1;  // the position in which its light (cap or annunciator) is lit; -1: never
  int light_object = -1;  // a static object of the scene that lights with it (an annunciator)
};

// What carries from step to step.
struct ControlState {
  double q = 0.0;
  double qd = 0.0;
  int position = 0;     // index into ControlSpec::positions
  bool latched = false;
  bool pressed = false;  // a latching button: inside its pressed interval (the latch toggles on entry)
  // The hand link whose push last drove it, and that motion's sign: a toggle pushed over its
  // hump or a guard past its snap centre finishes the move on its mechanism, and the change it
  // makes is still the push's, until the control stops or turns back (push_direction 0).
  int push_hand = -1;  // the world's hand index of push_link
  int push_link = -1;
  int push_direction = 0;
  // While a hand holds it: the hand's pose and q when it grasped (the projection's reference).
  Eigen::Isometry3d X_GH_grasp = Eigen::Isometry3d::Identity();
  double q_grasp = 0.0;
};

// Why a control's position changed.
enum class ControlCause : uint8_t { kPushed, kGrasped, kCommanded, kMechanism, kObject };
const char* control_cause_name(ControlCause cause);

// A change of a control's discrete position, with its cause: pushed by a hand link, turned or
// moved by a grasping hand, commanded (World::command_control), returned by its own mechanism
// (spring, snap, detent, gravity), or pushed by another object.
struct ControlEvent {
  int64_t t_ns = 0;
  int control = -1;
  int from = 0;  // position indices (ControlSpec::positions)
  int to = 0;
  ControlCause cause = ControlCause::kMechanism;
  int hand_id = -1;  // pushed or grasped: the hand
  int link = -1;     // pushed: the link that pushed hardest (hand::Link)
};

// The joint's motion at q: Tz(q) (prismatic) or Rz(q) (revolute) in the joint frame.
Eigen::Isometry3d joint_motion(JointKind joint, double q);
// The control's body pose at q: X_GJ * joint_motion(q) * X_JO.
Eigen::Isometry3d control_body_pose(const ControlSpec& c, double q);
// The rigid motion in G that takes the control's body from where it is at q_from to where it is
// at q_to: a turn by q_to - q_from about the joint's axis through its origin (revolute), or a
// slide by it along the axis (prismatic). X * control_body_pose(c, q_from) is
// control_body_pose(c, q_to).
Eigen::Isometry3d joint_motion_G(const ControlSpec& c, double q_from, double q_to);
// The joint's axis and a point on it, in the world.
inline Eigen::Vector3d joint_axis_G(const ControlSpec& c) { return c.X_GJ.linear().col(2); }
inline Eigen::Vector3d joint_origin_G(const ControlSpec& c) { return c.X_GJ.translation(); }

// The body's inertia along the joint: its mass (prismatic) or its moment of inertia about the
// axis (revolute: I about the centroid projected on the axis, plus m r^2 of the centroid's
// distance r from it).
double joint_inertia(const ControlSpec& c, double mass_kg, const Eigen::Matrix3d& I_O);

// The generalised force of a force F_G and couple M_G (about the centroid c_G) on the body.
double generalised_force(const ControlSpec& c, const Eigen::Vector3d& c_G,
                         const Eigen::Vector3d& F_G, const Eigen::Vector3d& M_G);

// The mechanism's own force at q, spring and damper left out (they are integrated implicitly):
// detents and the over-centre snap.
double mechanism_force(const ControlSpec& c, double q);

// The spring's rest coordinate now (a latched button rests at latch_q).
double spring_rest(const ControlSpec& c, const ControlState& s);

// The exact motion over t of M x'' + c x' + k x = F (constant F): x and its velocity.
struct SpringDamperState {
  double x = 0.0;
  double v = 0.0;
};
SpringDamperState spring_damper_step(double M, double c, double k, double F, double x0, double v0,
                                     double t);

// One step of the joint's motion law before its stops and gates: where the coordinate goes
// and its rate then; `moved` false when Coulomb friction holds it at rest (q, 0).
struct ControlStepFree {
  double q = 0.0;
  double qd = 0.0;
  bool moved = false;
};
ControlStepFree free_control_step(const ControlSpec& c, double M, double Q_ext, double dt_s,
                                  const ControlState& s);

// The mechanism's own steps within a step of dt_s from rate qd: a detent's force is held over a
// step (only its restoring slope is implicit), so a light knob that crosses a detent within one
// step is pushed by a force it has already passed, gains energy from nothing and spins on by
// itself. Steps short enough that its stiffest detent turns at most half a radian of its
// oscillation (omega h <= 0.5) and the coordinate moves at most a quarter of a detent's
// half-width; at most kMaxMechanismSteps. 1 for a control without detents.
constexpr int kMaxMechanismSteps = 32;
int mechanism_steps(const ControlSpec& c, double M, double qd, double dt_s);

// The free motion over dt_s (gravity and the mechanism, Q_ext held), in mechanism_steps, without
// stops: where the coordinate would go.
ControlStepFree free_control_motion(const ControlSpec& c, double M, double Q_ext, double dt_s,
                                    const ControlState& s);

// The joint's motion law over dt_s, in mechanism_steps, with generalised force Q_ext (contacts and
// gravity) held and joint inertia M: the spring and damper exactly, Coulomb friction (a control
// at rest stays while the net force is within it; a moving one stops rather than turn back), then
// the travel limits and the closed gates as inelastic stops. `gates_open`: the gates a grasping
// hand has lifted the lever over (bit g).
void integrate_control(const ControlSpec& c, double M, double Q_ext, double dt_s,
                       uint32_t gates_open, ControlState& s);

// How far the coordinate goes over dt_s per unit generalised force held over it from state s,
// the spring and damper (and a detent's slope) taken exactly, as integrate_control takes them:
// dt^2 / (2 M) for a bare joint. Linear in the force; friction, stops and gates left out. The soft
// contact solver couples a control's body through it (solver_joint.hpp).
double control_travel_per_force(const ControlSpec& c, double M, const ControlState& s, double dt_s);

// q clamped to the travel, and kept on its side of every closed gate that lies between q_from
// and it: what a grasped or commanded control can reach from q_from.
double reachable_q(const ControlSpec& c, double q_from, double q_to, uint32_t gates_open);

// The discrete position after q changed: the position whose interval q is in, or the same one
// when q is in none (hysteresis). A latching button toggles its latch on entering "pressed"
// (position 1) and reports off/on (positions 0/1) by its latch.
// Returns true when the reported position changed.
bool update_position(const ControlSpec& c, ControlState& s);

// The coordinate a grasping hand asks for: the control's q at the grasp moved by the hand's
// rotation about the axis (a rotary knob), or by the motion of the held point along the joint
// (prismatic: its displacement along the axis; a revolute lever: the angle it turned about the
// axis). `p_held_H`: the held point (the body's centroid at the grasp) in the hand frame.
double grasped_q(const ControlSpec& c, const ControlState& s, const Eigen::Isometry3d& X_GH,
                 const Eigen::Vector3d& p_held_H);
// How far the hand has lifted a grasped lever since the grasp (m): the held point's displacement
// away from the pivot (revolute) or along X_GJ's x axis (prismatic).
double grasped_lift_m(const ControlSpec& c, const ControlState& s, const Eigen::Isometry3d& X_GH,
                      const Eigen::Vector3d& p_held_H);

}  // namespace vcockpit::physics
