#pragma once
// Rigid-body motion (paper §4.3, eqs. 20-25, with eq. 22-23's typo fixed): semi-implicit Euler.
//   v_t = v_{t-1} + (F / m) dt                      (eqs. 20, 22: dv = F dt / m, added once)
//   w_t = w_{t-1} + I_G^-1 (M - w x I_G w) dt       (eqs. 21, 23, world inertia R I_O R^T and the
//                                                    gyroscopic term)
//   x_t = x_{t-1} + v_t dt                          (eq. 24: the new velocity moves the body)
//   q_t = exp(w_t dt) q_{t-1}, renormalised         (eq. 25 as a rotation)

#include <Eigen/Geometry>

#include "physics_node/physics/body.hpp"

namespace vcockpit::physics {

// I_O_inv: the inverse of I_O, computed once per body (the world inertia's inverse is then
// R I_O^-1 R^T: products, no factorisation per substep).
void integrate_body(BodyState& body, const Eigen::Vector3d& F_G, const Eigen::Vector3d& M_G,
                    double mass_kg, const Eigen::Matrix3d& I_O, const Eigen::Matrix3d& I_O_inv,
                    double dt_s);

// Rotation by the rotation vector w dt (exponential map), exact for any angle.
Eigen::Quaterniond rotation_increment(const Eigen::Vector3d& w_G, double dt_s);

// Velocity of a frame from two poses dt apart (eq. 15 for a tracked, kinematic body): what the
// hand's links and a held object move at, and what a released object leaves with.
void finite_difference_velocity(const Eigen::Isometry3d& before, const Eigen::Isometry3d& now,
                                double dt_s, Eigen::Vector3d& v_G, Eigen::Vector3d& w_G);

}  // namespace vcockpit::physics
