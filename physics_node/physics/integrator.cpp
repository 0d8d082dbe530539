#include "physics_node/physics/integrator.hpp"

#include <cmath>

namespace vcockpit::physics {
namespace {

// Newton steps of the midpoint rule: quadratic convergence from w0 takes two or three steps at
// |w| dt < 0.1 (a cockpit's spins); the cap only bounds a pathological case (|w| dt ~ 1, which the
// body check's spin limit does not reach at the scene's step).
constexpr int kMaxNewtonSteps = 8;
// A Newton step this small relative to |w_m| leaves an error of its square: converged.
constexpr double kNewtonTolerance = 1e-14;

Eigen::Matrix3d cross_matrix(const Eigen::Vector3d& a) {
  Eigen::Matrix3d m;
  m << 0.0, -a.z(), a.y(), a.z(), 0.0, -a.x(), -a.y(), a.x(), 0.0;
  return m;
}

}  // namespace

Eigen::Quaterniond rotation_increment(const Eigen::Vector3d& w_G, double dt_s) {
  const Eigen::Vector3d phi = w_G * dt_s;
  const double angle = phi.norm();
  if (angle < 1e-12) return Eigen::Quaterniond(1.0, 0.5 * phi.x(), 0.5 * phi.y(), 0.5 * phi.z()).normalized();
  return Eigen::Quaterniond(Eigen::AngleAxisd(angle, phi / angle));
}

Eigen::Vector3d gyroscopic_midpoint_O(const Eigen::Vector3d& w0_O, const Eigen::Matrix3d& I_O,
                                      double dt_s) {
  // G(w) = 2 I (w - w0) + dt w x I w = 0;  dG/dw = 2 I + dt ([w]x I - [I w]x)
  Eigen::Vector3d w = w0_O;
  for (int k = 0; k < kMaxNewtonSteps; ++k) {
    const Eigen::Vector3d Iw = I_O * w;
    const Eigen::Vector3d G = 2.0 * (Iw - I_O * w0_O) + dt_s * w.cross(Iw);
    if (G.isZero(0.0)) break;  // no gyroscopic term (a sphere, a principal axis), or converged
    const Eigen::Matrix3d J = 2.0 * I_O + dt_s * (cross_matrix(w) * I_O - cross_matrix(Iw));
    const Eigen::Vector3d step = J.inverse() * G;
    w -= step;
    if (step.norm() <= kNewtonTolerance * w.norm()) break;
  }
  return w;
}

void integrate_body(BodyState& body, const Eigen::Vector3d& F_G, const Eigen::Vector3d& M_G,
                    double mass_kg, const Eigen::Matrix3d& I_O, const Eigen::Matrix3d& I_O_inv,
                    double dt_s) {
  const Eigen::Quaterniond q0(body.X_GO.linear());
  const Eigen::Matrix3d R0 = body.X_GO.linear();
  body.v_G += F_G * (dt_s / mass_kg);
  // in the body frame, where I_O is constant: the torque's impulse, then the torque-free turn
  const Eigen::Vector3d w_star_O = R0.transpose() * body.w_G + I_O_inv * (R0.transpose() * M_G) * dt_s;
  const Eigen::Vector3d w_mid_O = gyroscopic_midpoint_O(w_star_O, I_O, dt_s);
  const Eigen::Vector3d w_end_O = 2.0 * w_mid_O - w_star_O;
  body.X_GO.translation() += body.v_G * dt_s;
  const Eigen::Quaterniond q = (rotation_increment(R0 * w_mid_O, dt_s) * q0).normalized();
  body.X_GO.linear() = q.toRotationMatrix();
  body.w_G = body.X_GO.linear() * w_end_O;
}

void integrate_position(BodyState& body, const Eigen::Vector3d& v_pos, const Eigen::Vector3d& w_pos,
                        const Eigen::Vector3d& v_end, const Eigen::Vector3d& w_end,
                        const Eigen::Matrix3d& I_O, double dt_s) {
  const Eigen::Quaterniond q0(body.X_GO.linear());
  const Eigen::Matrix3d R0 = body.X_GO.linear();
  const Eigen::Vector3d w_star_O = R0.transpose() * w_pos;
  const Eigen::Vector3d w_mid_O = gyroscopic_midpoint_O(w_star_O, I_O, dt_s);
  // the relax pass's change of spin, in the body frame at the step's start
  const Eigen::Vector3d w_end_O = 2.0 * w_mid_O - w_star_O + R0.transpose() * (w_end - w_pos);
  body.X_GO.translation() += v_pos * dt_s;
  const Eigen::Quaterniond q = (rotation_increment(R0 * w_mid_O, dt_s) * q0).normalized();
  body.X_GO.linear() = q.toRotationMatrix();
  body.v_G = v_end;
  body.w_G = body.X_GO.linear() * w_end_O;
}

void finite_difference_velocity(const Eigen::Isometry3d& before, const Eigen::Isometry3d& now,
                                double dt_s, Eigen::Vector3d& v_G, Eigen::Vector3d& w_G) {
  v_G = (now.translation() - before.translation()) / dt_s;
  const Eigen::AngleAxisd turn(now.linear() * before.linear().transpose());
  w_G = turn.axis() * (turn.angle() / dt_s);
}

}  // namespace vcockpit::physics
