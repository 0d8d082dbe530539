#include "physics_node/physics/rolling_resistance.hpp"

#include <algorithm>

namespace vcockpit::physics {
namespace {

// u . I_G^-1 u for a body's world inverse inertia R I_O^-1 R^T (0 for an immovable body).
double inverse_inertia_along(const ContactBody& body, const Eigen::Vector3d& u_G) {
  const Eigen::Vector3d u_O = body.X_GB.linear().transpose() * u_G;
  return u_O.dot(body.inv_I_O * u_O);
}

}  // namespace

Eigen::Vector3d rolling_torque_on_b_G(const ContactBody& A, const ContactBody& B,
                                      const Eigen::Vector3d& n_G, double N_sum, double mu_roll_m,
                                      double dt_s) {
  if (!(mu_roll_m > 0.0) || !(N_sum > 0.0)) return Eigen::Vector3d::Zero();
  const Eigen::Vector3d w_rel = B.w_G - A.w_G;
  const Eigen::Vector3d w_roll = w_rel - w_rel.dot(n_G) * n_G;
  const double rate_radps = w_roll.norm();
  if (!(rate_radps > 0.0)) return Eigen::Vector3d::Zero();
  const Eigen::Vector3d u = w_roll / rate_radps;
  const double inverse_inertia = inverse_inertia_along(A, u) + inverse_inertia_along(B, u);
  if (!(inverse_inertia > 0.0)) return Eigen::Vector3d::Zero();
  // the couple that would stop w_roll within this substep on its own: the most it may be
  const double stopping_Nm = rate_radps / (inverse_inertia * dt_s);
  return -std::min(mu_roll_m * N_sum, stopping_Nm) * u;
}

}  // namespace vcockpit::physics
