#pragma once
// A control's body as the soft contact solver sees it (contact_solver.hpp): a body on one joint
// (control.hpp), whose velocity is its coordinate's rate qd times the joint's twist. An impulse P
// at a point p changes qd by mobility * J(p, P), where J is the impulse's generalised part along
// the joint: a . P (prismatic) or a . ((p - o) x P) (revolute, o on the axis, a its direction).
//
// The rate here is the coordinate's mean rate over the step, (q_end - q) / h: what the solver's
// positions move with (a free body's x += h v_end). The control moves by its exact spring-damper
// step (integrate_control), in which a force Q held over h moves q by X Q, not h^2 Q / M; so
// mobility = X / h^2 per unit impulse (1 / (2 M) for a bare joint), and qd_free is its mean rate
// under gravity and its mechanism alone. With them the solver's end positions are where
// integrate_control then puts the control with the contacts' generalised impulse (its friction,
// detents and stops aside, which integrate_control keeps exact). docs/design/soft_contacts.md,
// section 1.

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>

namespace vcockpit::physics {

struct SolverJoint {
  int body = -1;  // the control's body (an object index)
  bool revolute = false;
  Eigen::Vector3d axis_G = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d origin_G = Eigen::Vector3d::Zero();    // on the axis
  Eigen::Vector3d centroid_G = Eigen::Vector3d::Zero();  // the body's centroid now
  double qd_free = 0.0;   // its mean rate over the step with no contact: gravity and mechanism
  double mobility = 0.0;  // mean rate per unit generalised impulse (1/kg or 1/(kg m^2))
  // the rates its stops and closed gates allow over the step (qd h reaches them)
  double qd_min = -std::numeric_limits<double>::infinity();
  double qd_max = std::numeric_limits<double>::infinity();
  double impulse = 0.0;  // the contacts' generalised impulse so far (N s or N m s)
  // out: the generalised impulse the control moves with over the step, as the biased sweeps left
  // it (the springs' push-out in it, as a free body's position has it; the relax sweeps only
  // settle the velocities the contact forces report)
  double move_impulse = 0.0;

  // J(p, u): the generalised part of a push u at p. A push the joint cannot take (a press on a
  // knob's face along its axis) is 0 exactly, not rounding noise: a rigid row divides by its
  // effective mass, and noise there is an impulse of 1e25 whose round-off turns the knob.
  double along(const Eigen::Vector3d& p_G, const Eigen::Vector3d& u) const {
    if (!revolute) return noise_free(axis_G.dot(u), u.norm());
    const Eigen::Vector3d lever = p_G - origin_G;
    return noise_free(axis_G.dot(lever.cross(u)), lever.norm() * u.norm());
  }
  // the generalised part of a couple L
  double along_couple(const Eigen::Vector3d& L) const {
    return revolute ? noise_free(axis_G.dot(L), L.norm()) : 0.0;
  }
  static double noise_free(double J, double size) { return std::abs(J) > 1e-9 * size ? J : 0.0; }
  // the rate with the impulse so far, as far as the stops let it go
  double qd() const { return std::clamp(qd_free + mobility * impulse, qd_min, qd_max); }
  // the body's centroid velocity and angular velocity at rate qd
  void velocity(double rate, Eigen::Vector3d& v_G, Eigen::Vector3d& w_G) const {
    if (revolute) {
      w_G = rate * axis_G;
      v_G = w_G.cross(centroid_G - origin_G);
    } else {
      v_G = rate * axis_G;
      w_G.setZero();
    }
  }
};

}  // namespace vcockpit::physics
