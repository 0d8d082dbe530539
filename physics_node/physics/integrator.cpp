#include "physics_node/physics/integrator.hpp"

#include <cmath>

namespace vcockpit::physics {

Eigen::Quaterniond rotation_increment(const Eigen::Vector3d& w_G, double dt_s) {
  const Eigen::Vector3d phi = w_G * dt_s;
  const double angle = phi.norm();
  if (angle < 1e-12) return Eigen::Quaterniond(1.0, 0.5 * phi.x(), 0.5 * phi.y(), 0.5 * phi.z()).normalized();
  return Eigen::Quaterniond(Eigen::AngleAxisd(angle, phi / angle));
}

void integrate_body(BodyState& body, const Eigen::Vector3d& F_G, const Eigen::Vector3d& M_G,
                    double mass_kg, const Eigen::Matrix3d& I_O, const Eigen::Matrix3d& I_O_inv,
                    double dt_s) {
  const Eigen::Matrix3d R = body.X_GO.linear();
  body.v_G += F_G * (dt_s / mass_kg);
  // in the body frame: I_G w = R I_O R^T w, and I_G^-1 x = R I_O^-1 R^T x
  const Eigen::Vector3d gyroscopic = body.w_G.cross(R * (I_O * (R.transpose() * body.w_G)));
  body.w_G += R * (I_O_inv * (R.transpose() * (M_G - gyroscopic))) * dt_s;
  body.X_GO.translation() += body.v_G * dt_s;
  const Eigen::Quaterniond q =
      (rotation_increment(body.w_G, dt_s) * Eigen::Quaterniond(R)).normalized();
  body.X_GO.linear() = q.toRotationMatrix();
}

void finite_difference_velocity(const Eigen::Isometry3d& before, const Eigen::Isometry3d& now,
                                double dt_s, Eigen::Vector3d& v_G, Eigen::Vector3d& w_G) {
  v_G = (now.translation() - before.translation()) / dt_s;
  const Eigen::AngleAxisd turn(now.linear() * before.linear().transpose());
  w_G = turn.axis() * (turn.angle() / dt_s);
}

}  // namespace vcockpit::physics
