#pragma once
// Rolling resistance at a touching pair (beyond the paper; MuJoCo's condim 6 rolling friction,
// per pair like Coulomb friction): a couple against the relative rolling angular velocity
//   w_roll = w_rel - (w_rel . n) n,   w_rel = w_b - w_a
// of magnitude mu_roll sum(N) (mu_roll a length, the lever of the deformed contact patch's
// pressure; the pair's value is the geometric mean of the materials', like mu), but never more
// than stops w_roll within the substep by itself: |tau| <= |w_roll| / (dt u . (I_a^-1 + I_b^-1) u),
// u = w_roll / |w_roll|. So it brings a rolling body to rest and never turns it back (an explicit
// couple of mu_roll N would overshoot a slow roll and rock the body about rest).
//
// Closed form: a solid sphere (I = 2/5 m r^2) rolling without slip on a level plane feels
// m g mu_roll about the contact, so (I + m r^2) dw/dt = -mu_roll m g and it decelerates at
//   a = mu_roll g / (r (1 + 2/5)),   stopping after v0^2 / (2 a)
// (tests/scenario/rolling_resistance_test.cpp).

#include <Eigen/Core>

#include "physics_node/physics/body.hpp"

namespace vcockpit::physics {

// The couple on body b (body a takes its opposite), N m. n_G: the pair's normal from a to b;
// N_sum: the pair's total normal force (N); mu_roll_m: the pair's coefficient (m); dt_s: the
// substep. Zero when nothing rolls, nothing presses, or neither body can turn.
Eigen::Vector3d rolling_torque_on_b_G(const ContactBody& A, const ContactBody& B,
                                      const Eigen::Vector3d& n_G, double N_sum, double mu_roll_m,
                                      double dt_s);

}  // namespace vcockpit::physics
