#include "physics_node/physics/rolling_resistance.hpp"

#include <algorithm>

namespace vcockpit::physics {
namespace {

// u . I_G^-1 u for a body's world inverse inertia R I_O^-1 R^T (0 for an immovable body).
double inverse_inertia_along(const ContactBody& body, const Eigen::Vector3d& u_G) {
  const Eigen::Vector3d u_O = body.X_GB.linear().transpose() * u_G;
  return u_O.dot(body.inv_I_O * u_O);
}

// The couple on b against the relative turning w_part, at most limit_Nm and at most what stops
// w_part within dt on its own.
Eigen::Vector3d bounded_couple(const ContactBody& A, const ContactBody& B,
                               const Eigen::Vector3d& w_part, double limit_Nm, double dt_s) {
  const double rate_radps = w_part.norm();
  if (!(limit_Nm > 0.0) || !(rate_radps > 0.0)) return Eigen::Vector3d::Zero();
  const Eigen::Vector3d u = w_part / rate_radps;
  const double inverse_inertia = inverse_inertia_along(A, u) + inverse_inertia_along(B, u);
  if (!(inverse_inertia > 0.0)) return Eigen::Vector3d::Zero();
  const double stopping_Nm = rate_radps / (inverse_inertia * dt_s);
  return -std::min(limit_Nm, stopping_Nm) * u;
}

}  // namespace

Eigen::Vector3d resistance_couple_on_b_G(const ContactBody& A, const ContactBody& B,
                                         const Eigen::Vector3d& n_G, double N_sum,
                                         double mu_roll_m, double mu_spin_m, double dt_s) {
  if (!(N_sum > 0.0)) return Eigen::Vector3d::Zero();
  const Eigen::Vector3d w_rel = B.w_G - A.w_G;
  const Eigen::Vector3d w_spin = w_rel.dot(n_G) * n_G;
  return bounded_couple(A, B, w_rel - w_spin, mu_roll_m * N_sum, dt_s) +
         bounded_couple(A, B, w_spin, mu_spin_m * N_sum, dt_s);
}

}  // namespace vcockpit::physics
