#pragma once
// Rigid-body motion (paper §4.3, eqs. 20-25, with eq. 22-23's typo fixed).
//   v_t = v_{t-1} + (F / m) dt                      (eqs. 20, 22: dv = F dt / m, added once)
//   x_t = x_{t-1} + v_t dt                          (eq. 24: the new velocity moves the body)
// The rotation (eqs. 21, 23, 25) in the body frame O, where the inertia I_O is constant:
//   w*  = w_{t-1} + I_O^-1 R^T M dt                 (eqs. 21, 23: the torque's impulse)
//   I_O (w_t - w*) = -dt w_m x I_O w_m,  w_m = (w* + w_t) / 2
//                                                   (eq. 21's gyroscopic term w x I w, implicit:
//                                                    the implicit midpoint rule)
//   q_t = q_{t-1} exp(w_m dt), renormalised         (eq. 25 as a rotation, by the midpoint w)
// The paper's explicit w x I w dt feeds energy into any body spinning off its principal axes
// (a 60 g cylinder given 70.7 rad/s about an axis 45 deg off its own: 149 rad/s after 1 s, 24,896
// after 6 s). The midpoint rule keeps both quadratic invariants of a torque-free body, |L| and the
// kinetic energy, exactly (up to the Newton solve's tolerance and rounding): (L_t - L*) is
// perpendicular to L_m and to w_m. Where the gyroscopic term vanishes (a sphere, a spin about a
// principal axis) w_m = w_t = w* and this is the semi-implicit Euler step it always was.
// Bullet's computeGyroscopicImpulseImplicit_Body solves implicit Euler with one Newton step; that
// loses |L| by O(dt^2 w^2) per step (half of it in a minute at cockpit spins), so the midpoint
// rule here is solved to convergence (two or three Newton steps at cockpit spins).

#include <Eigen/Geometry>

#include "physics_node/physics/body.hpp"

namespace vcockpit::physics {

// I_O_inv: the inverse of I_O, computed once per body (no factorisation per step for it).
void integrate_body(BodyState& body, const Eigen::Vector3d& F_G, const Eigen::Vector3d& M_G,
                    double mass_kg, const Eigen::Matrix3d& I_O, const Eigen::Matrix3d& I_O_inv,
                    double dt_s);

// The positions over dt of a body whose velocities a contact solver has found (gravity and the
// contacts' impulses in them): x += v_pos dt, and the turn by the implicit midpoint rule from
// w_pos, as integrate_body does after its impulses. Its velocities become v_end and w_end (the
// solver's final ones, after its relax pass), with the gyroscopic change over the step added.
void integrate_position(BodyState& body, const Eigen::Vector3d& v_pos, const Eigen::Vector3d& w_pos,
                        const Eigen::Vector3d& v_end, const Eigen::Vector3d& w_end,
                        const Eigen::Matrix3d& I_O, double dt_s);

// The torque-free rotation over dt in the body frame by the implicit midpoint rule: the midpoint
// angular velocity w_m with I_O (2 w_m - 2 w0) + dt w_m x I_O w_m = 0, by Newton's method from
// w_m = w0. The end-of-step velocity is 2 w_m - w0.
Eigen::Vector3d gyroscopic_midpoint_O(const Eigen::Vector3d& w0_O, const Eigen::Matrix3d& I_O,
                                      double dt_s);

// Rotation by the rotation vector w dt (exponential map), exact for any angle.
Eigen::Quaterniond rotation_increment(const Eigen::Vector3d& w_G, double dt_s);

// Velocity of a frame from two poses dt apart (eq. 15 for a tracked, kinematic body): what the
// hand's links and a held object move at, and what a released object leaves with.
void finite_difference_velocity(const Eigen::Isometry3d& before, const Eigen::Isometry3d& now,
                                double dt_s, Eigen::Vector3d& v_G, Eigen::Vector3d& w_G);

}  // namespace vcockpit::physics
