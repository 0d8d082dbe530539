#pragma once
// The sums over a body's contacts, paper eqs. 18-19 with DESIGN.md's reading:
//   eq. 18  F = sum(N n + f tau) + m g
//   eq. 19  M = sum(r x F_i), r from the centroid to the contact point (the paper's F x r with r
//           from the contact to the centroid)
// Forces act on body b along +n and on body a opposite.

#include <Eigen/Core>
#include <vector>

#include "physics_node/physics/body.hpp"

namespace vcockpit::physics {

// Eq. 18's term of one contact: its force on body b, N n + f_t (N).
Eigen::Vector3d contact_force_G(double N, const Eigen::Vector3d& n_G, const Eigen::Vector3d& f_t_G);

// Eq. 19's term of one contact: the torque of F_G at p_G about the centroid c_G, r x F (N m).
Eigen::Vector3d torque_about_centroid_G(const Eigen::Vector3d& p_G, const Eigen::Vector3d& c_G,
                                        const Eigen::Vector3d& F_G);

// Eqs. 18-19: adds one contact's force (F_on_b_G on b, its opposite on a) at p_G to the bodies'
// force sums F_G and torque sums M_G about their centroids.
void add_contact_to_sums(int a, int b, const ContactBody& A, const ContactBody& B,
                         const Eigen::Vector3d& p_G, const Eigen::Vector3d& F_on_b_G,
                         std::vector<Eigen::Vector3d>& F_G, std::vector<Eigen::Vector3d>& M_G);

// Eq. 18: the total force on a free body, its contacts' sum plus its weight m g.
Eigen::Vector3d total_force_G(const Eigen::Vector3d& F_contacts_G, double mass_kg,
                              const Eigen::Vector3d& gravity_mps2);

}  // namespace vcockpit::physics
