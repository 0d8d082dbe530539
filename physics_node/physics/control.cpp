#include "physics_node/physics/control.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace vcockpit::physics {

namespace {

constexpr double kPi = 3.14159265358979323846;
// A gate or stop that held the coordinate leaves it this far on the side it came from, so the
// next step knows which side that is.
constexpr double kGateSide = 1e-9;

double sign(double x) { return x > 0.0 ? 1.0 : (x < 0.0 ? -1.0 : 0.0); }

// One detent's restoring force at offset x from it: -strength sin(pi x / half_width) within the
// half width (its peak halfway), nothing beyond.
double detent_force(const Detent& d, double x) {
  if (d.half_width <= 0.0 || std::abs(x) >= d.half_width) return 0.0;
  return -d.strength * std::sin(kPi * x / d.half_width);
}

// ... and its stiffness there, -d(force)/dx
double detent_stiffness(const Detent& d, double x) {
  if (d.half_width <= 0.0 || std::abs(x) >= d.half_width) return 0.0;
  return d.strength * kPi / d.half_width * std::cos(kPi * x / d.half_width);
}

}  // namespace

const char* control_kind_name(ControlKind kind) {
  switch (kind) {
    case ControlKind::kPushButton: return "push_button";
    case ControlKind::kToggle: return "toggle";
    case ControlKind::kRotary: return "rotary";
    case ControlKind::kLever: return "lever";
    case ControlKind::kGuard: return "guard";
  }
  return "?";
}

const char* control_cause_name(ControlCause cause) {
  switch (cause) {
    case ControlCause::kPushed: return "pushed";
    case ControlCause::kGrasped: return "grasped";
    case ControlCause::kCommanded: return "commanded";
    case ControlCause::kMechanism: return "mechanism";
    case ControlCause::kObject: return "object";
  }
  return "?";
}

Eigen::Isometry3d joint_motion(JointKind joint, double q) {
  Eigen::Isometry3d M = Eigen::Isometry3d::Identity();
  if (joint == JointKind::kPrismatic) {
    M.translation().z() = q;
  } else {
    M.linear() = Eigen::AngleAxisd(q, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  }
  return M;
}

Eigen::Isometry3d control_body_pose(const ControlSpec& c, double q) {
  return c.X_GJ * joint_motion(c.joint, q) * c.X_JO;
}

Eigen::Isometry3d joint_motion_G(const ControlSpec& c, double q_from, double q_to) {
  // X_GJ M(q_to) M(q_from)^-1 X_GJ^-1, and M(q_to) M(q_from)^-1 = M(q_to - q_from) for a turn
  // or a slide along one axis
  return c.X_GJ * joint_motion(c.joint, q_to - q_from) * c.X_GJ.inverse();
}

double joint_inertia(const ControlSpec& c, double mass_kg, const Eigen::Matrix3d& I_O) {
  if (c.joint == JointKind::kPrismatic) return mass_kg;
  const Eigen::Matrix3d& R_JO = c.X_JO.linear();
  const double I_axis = (R_JO * I_O * R_JO.transpose())(2, 2);
  const Eigen::Vector3d r = c.X_JO.translation();
  return I_axis + mass_kg * (r.x() * r.x() + r.y() * r.y());  // parallel axis
}

double generalised_force(const ControlSpec& c, const Eigen::Vector3d& c_G,
                         const Eigen::Vector3d& F_G, const Eigen::Vector3d& M_G) {
  const Eigen::Vector3d a = joint_axis_G(c);
  if (c.joint == JointKind::kPrismatic) return a.dot(F_G);
  return a.dot(M_G + (c_G - joint_origin_G(c)).cross(F_G));
}

// The detents acting at q, each with q's offset from it: a continuous knob's one detent repeats.
template <class F>
void for_each_detent(const ControlSpec& c, double q, F f) {
  if (c.detent_period > 0.0 && !c.detents.empty()) {
    f(c.detents.front(), std::remainder(q - c.detents.front().q, c.detent_period));
  } else {
    for (const Detent& d : c.detents) f(d, q - d.q);
  }
}

double mechanism_force(const ControlSpec& c, double q) {
  double Q = 0.0;
  for_each_detent(c, q, [&](const Detent& d, double x) { Q += detent_force(d, x); });
  if (c.snap > 0.0) Q += c.snap * sign(q - c.snap_centre);  // over-centre: toward the nearer end
  return Q;
}

double mechanism_stiffness(const ControlSpec& c, double q) {
  double k = 0.0;
  for_each_detent(c, q, [&](const Detent& d, double x) { k += detent_stiffness(d, x); });
  return k;
}

double spring_rest(const ControlSpec& c, const ControlState& s) {
  return c.latching && s.latched ? c.latch_q : c.q_rest;
}

double reachable_q(const ControlSpec& c, double q_from, double q_to, uint32_t gates_open) {
  double q = q_to;
  if (c.limited) q = std::clamp(q, c.q_min, c.q_max);
  for (std::size_t g = 0; g < c.gates.size(); ++g) {
    if ((gates_open >> g & 1u) != 0) continue;
    const double gate = c.gates[g].q;
    if (q_from < gate && q > gate) q = gate - kGateSide;       // the nearest closed gate wins:
    else if (q_from > gate && q < gate) q = gate + kGateSide;  // q only shrinks toward q_from
    else if (q_from == gate) q = gate;  // in the gate's notch (set there, or commanded): lift to leave
  }
  return q;
}

SpringDamperState spring_damper_step(double M, double c, double k, double F, double x0, double v0,
                                     double t) {
  // M x'' + c x' + k x = F, exactly: about the equilibrium x_eq = F / k the motion is the free
  // response of the damped oscillator; without a spring, the damper's exponential approach to
  // the terminal velocity F / c (or constant acceleration when c = 0 too)
  if (k <= 0.0) {
    if (c <= 0.0) return {x0 + v0 * t + 0.5 * F / M * t * t, v0 + F / M * t};
    const double v_inf = F / c;
    const double decay = std::exp(-c / M * t);
    const double v = v_inf + (v0 - v_inf) * decay;
    return {x0 + v_inf * t + (v0 - v_inf) * (M / c) * (1.0 - decay), v};
  }
  const double x_eq = F / k;
  const double y0 = x0 - x_eq;
  const double w0 = std::sqrt(k / M);
  const double zeta = c / (2.0 * std::sqrt(k * M));
  double y = 0.0, v = 0.0;
  if (zeta < 1.0 - 1e-9) {
    const double wd = w0 * std::sqrt(1.0 - zeta * zeta);
    const double e = std::exp(-zeta * w0 * t);
    const double cs = std::cos(wd * t), sn = std::sin(wd * t);
    const double B = (v0 + zeta * w0 * y0) / wd;
    y = e * (y0 * cs + B * sn);
    v = e * ((B * wd - zeta * w0 * y0) * cs - (y0 * wd + zeta * w0 * B) * sn);
  } else if (zeta > 1.0 + 1e-9) {
    const double root = w0 * std::sqrt(zeta * zeta - 1.0);
    const double r1 = -zeta * w0 + root, r2 = -zeta * w0 - root;
    const double A = (v0 - r2 * y0) / (r1 - r2);
    const double B = y0 - A;
    const double e1 = std::exp(r1 * t), e2 = std::exp(r2 * t);
    y = A * e1 + B * e2;
    v = A * r1 * e1 + B * r2 * e2;
  } else {  // critically damped
    const double e = std::exp(-w0 * t);
    const double B = v0 + w0 * y0;
    y = (y0 + B * t) * e;
    v = (B - w0 * (y0 + B * t)) * e;
  }
  return {x_eq + y, v};
}

ControlStepFree free_control_step(const ControlSpec& c, double M, double Q_ext, double dt_s,
                                  const ControlState& s) {
  // the spring and damper exactly (a released button returns as its mass-spring-damper does, at
  // any step), the rest of the generalised force held over the step
  const double rest = spring_rest(c, s);
  double Q = Q_ext + mechanism_force(c, s.q);
  // Coulomb friction: a control at rest stays while the net force is within it; a moving one
  // feels it against its motion, and stops rather than turn back within the step
  const double net_at_rest = Q - c.stiffness * (s.q - rest);
  if (s.qd == 0.0 && std::abs(net_at_rest) <= c.friction) return {s.q, 0.0, false};
  const double direction = s.qd != 0.0 ? sign(s.qd) : sign(net_at_rest);
  Q -= direction * c.friction;
  // a detent's restoring slope joins the spring, integrated exactly too: held over the step
  // it added energy every swing, and a light toggle (a few grams on 0.04 N m) rang up until it
  // jumped out of its detent. Its force at s.q stays explicit; only the slope is implicit.
  const double k_mechanism = std::max(0.0, mechanism_stiffness(c, s.q));
  const double k = c.stiffness + k_mechanism;
  const SpringDamperState next =
      spring_damper_step(M, c.damping, k, Q - c.stiffness * (s.q - rest), 0.0, s.qd, dt_s);
  double qd = next.v;
  if (c.friction > 0.0 && sign(qd) == -direction) qd = 0.0;
  return {s.q + next.x, qd, true};
}

int mechanism_steps(const ControlSpec& c, double M, double qd, double dt_s) {
  if (c.detents.empty() || !(M > 0.0)) return 1;
  double k_peak = 0.0;
  double half_width = std::numeric_limits<double>::infinity();
  for (const Detent& d : c.detents) {
    if (!(d.half_width > 0.0)) continue;
    k_peak = std::max(k_peak, d.strength * kPi / d.half_width);
    half_width = std::min(half_width, d.half_width);
  }
  if (!(k_peak > 0.0)) return 1;
  const double by_stiffness = std::sqrt((c.stiffness + k_peak) / M) * dt_s / 0.5;
  const double by_speed = std::abs(qd) * dt_s / (0.25 * half_width);
  const double steps = std::ceil(std::max(by_stiffness, by_speed));
  if (!(steps > 1.0)) return 1;  // (NaN too)
  return static_cast<int>(std::min(steps, static_cast<double>(kMaxMechanismSteps)));
}

ControlStepFree free_control_motion(const ControlSpec& c, double M, double Q_ext, double dt_s,
                                    const ControlState& s) {
  const int n = mechanism_steps(c, M, s.qd, dt_s);
  if (n == 1) return free_control_step(c, M, Q_ext, dt_s, s);
  ControlState at = s;
  ControlStepFree out{s.q, s.qd, false};
  for (int i = 0; i < n; ++i) {
    const ControlStepFree next = free_control_step(c, M, Q_ext, dt_s / n, at);
    if (!next.moved) break;  // at rest within its friction: it stays
    at.q = next.q;
    at.qd = next.qd;
    out = {next.q, next.qd, true};
  }
  return out;
}

void integrate_control(const ControlSpec& c, double M, double Q_ext, double dt_s,
                       uint32_t gates_open, ControlState& s) {
  const int n = mechanism_steps(c, M, s.qd, dt_s);
  for (int i = 0; i < n; ++i) {
    const ControlStepFree next = free_control_step(c, M, Q_ext, dt_s / n, s);
    if (!next.moved) return;  // at rest within its friction: it stays
    const double q = reachable_q(c, s.q, next.q, gates_open);
    s.qd = q != next.q ? 0.0 : next.qd;  // a stop or a gate: inelastic
    s.q = q;
  }
}

double control_travel_per_force(const ControlSpec& c, double M, const ControlState& s, double dt_s) {
  const double k = c.stiffness + std::max(0.0, mechanism_stiffness(c, s.q));
  return spring_damper_step(M, c.damping, k, 1.0, 0.0, 0.0, dt_s).x;
}

bool update_position(const ControlSpec& c, ControlState& s) {
  int inside = -1;
  for (std::size_t i = 0; i < c.positions.size(); ++i) {
    const ControlPosition& p = c.positions[i];
    // a continuous knob's positions repeat with its detent: q is in one if q - k period is
    double q = s.q;
    if (c.detent_period > 0.0) q -= std::ceil((q - p.enter_hi) / c.detent_period) * c.detent_period;
    if (q >= p.enter_lo && q <= p.enter_hi) {
      inside = static_cast<int>(i);
      break;
    }
  }
  const int before = s.position;
  if (c.latching) {
    // positions[0]: released (re-arms), positions[1]: pressed (toggles the latch on entry)
    if (inside == 1 && !s.pressed) {
      s.pressed = true;
      s.latched = !s.latched;
    } else if (inside == 0) {
      s.pressed = false;
    }
    s.position = s.latched ? 1 : 0;
  } else if (inside >= 0) {
    s.position = inside;
  }
  return s.position != before;
}

double grasped_q(const ControlSpec& c, const ControlState& s, const Eigen::Isometry3d& X_GH,
                 const Eigen::Vector3d& p_held_H) {
  const Eigen::Vector3d a = joint_axis_G(c);
  if (c.kind == ControlKind::kRotary && c.joint == JointKind::kRevolute) {
    // the twist of the hand's rotation since the grasp about the axis (swing-twist)
    const Eigen::Quaterniond turn(X_GH.linear() * s.X_GH_grasp.linear().transpose());
    const double along = a.dot(turn.vec());
    return s.q_grasp + 2.0 * std::atan2(along, turn.w());
  }
  const Eigen::Vector3d p0 = s.X_GH_grasp * p_held_H;
  const Eigen::Vector3d p1 = X_GH * p_held_H;
  if (c.joint == JointKind::kPrismatic) return s.q_grasp + a.dot(p1 - p0);
  // a lever: the angle the held point turned about the axis
  const Eigen::Vector3d o = joint_origin_G(c);
  Eigen::Vector3d u0 = p0 - o, u1 = p1 - o;
  u0 -= a.dot(u0) * a;
  u1 -= a.dot(u1) * a;
  if (u0.squaredNorm() == 0.0 || u1.squaredNorm() == 0.0) return s.q_grasp;
  return s.q_grasp + std::atan2(a.dot(u0.cross(u1)), u0.dot(u1));
}

double grasped_lift_m(const ControlSpec& c, const ControlState& s, const Eigen::Isometry3d& X_GH,
                      const Eigen::Vector3d& p_held_H) {
  const Eigen::Vector3d p0 = s.X_GH_grasp * p_held_H;
  const Eigen::Vector3d p1 = X_GH * p_held_H;
  if (c.joint == JointKind::kPrismatic) return c.X_GJ.linear().col(0).dot(p1 - p0);
  const Eigen::Vector3d a = joint_axis_G(c);
  const Eigen::Vector3d o = joint_origin_G(c);
  auto radial = [&](const Eigen::Vector3d& p) {
    const Eigen::Vector3d u = p - o;
    return (u - a.dot(u) * a).norm();
  };
  return radial(p1) - radial(p0);
}

}  // namespace vcockpit::physics
