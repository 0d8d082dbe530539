#include "physics_node/physics/contact_sums.hpp"

#include <Eigen/Geometry>

namespace vcockpit::physics {

Eigen::Vector3d contact_force_G(double N, const Eigen::Vector3d& n_G,
                                const Eigen::Vector3d& f_t_G) {
  return N * n_G + f_t_G;
}

Eigen::Vector3d torque_about_centroid_G(const Eigen::Vector3d& p_G, const Eigen::Vector3d& c_G,
                                        const Eigen::Vector3d& F_G) {
  return (p_G - c_G).cross(F_G);
}

void add_contact_to_sums(int a, int b, const ContactBody& A, const ContactBody& B,
                         const Eigen::Vector3d& p_G, const Eigen::Vector3d& F_on_b_G,
                         std::vector<Eigen::Vector3d>& F_G, std::vector<Eigen::Vector3d>& M_G) {
  const Eigen::Vector3d& F = F_on_b_G;
  F_G[b] += F;
  M_G[b] += torque_about_centroid_G(p_G, B.X_GB.translation(), F);
  F_G[a] -= F;
  M_G[a] -= torque_about_centroid_G(p_G, A.X_GB.translation(), F);
}

Eigen::Vector3d total_force_G(const Eigen::Vector3d& F_contacts_G, double mass_kg,
                              const Eigen::Vector3d& gravity_mps2) {
  return F_contacts_G + mass_kg * gravity_mps2;
}

}  // namespace vcockpit::physics
