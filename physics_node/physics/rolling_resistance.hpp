#pragma once
// Rolling and spinning resistance at a touching pair (beyond the paper; MuJoCo's condim 6:
// rolling and torsional friction, per pair like Coulomb friction). The pair's relative angular
// velocity w_rel = w_b - w_a splits into
//   rolling   w_roll = w_rel - (w_rel . n) n   (turning across the normal)
//   spinning  w_spin = (w_rel . n) n           (turning about it)
// and each meets a couple against it of magnitude mu N, mu_roll_m and mu_spin_m lengths (the
// lever of the contact patch's pressure; each pair's the geometric mean of its materials', like
// mu), but never more than stops that part within the substep by itself:
//   |tau| <= |w_part| / (dt u . (I_a^-1 + I_b^-1) u),  u = w_part / |w_part|.
// So it brings a rolling or spinning body to rest and never turns it back (an explicit couple
// of mu N would overshoot a slow roll and rock the body about rest). A single-point contact (a
// ball) has no other resistance to spinning: the stick springs act at the point itself.
//
// Closed form: a solid sphere (I = 2/5 m r^2) rolling without slip on a level plane feels
// m g mu_roll about the contact, so (I + m r^2) dw/dt = -mu_roll m g and it decelerates at
//   a = mu_roll g / (r (1 + 2/5)),   stopping after v0^2 / (2 a)
// (tests/scenario/rolling_resistance_test.cpp).

#include <Eigen/Core>

#include "physics_node/physics/body.hpp"

namespace vcockpit::physics {

// The couple on body b (body a takes its opposite), N m. n_G: the pair's normal from a to b;
// N_sum: the pair's total normal force (N); mu_roll_m, mu_spin_m: the pair's coefficients (m);
// dt_s: the substep. Zero when nothing turns, nothing presses, or neither body can turn.
Eigen::Vector3d resistance_couple_on_b_G(const ContactBody& A, const ContactBody& B,
                                         const Eigen::Vector3d& n_G, double N_sum,
                                         double mu_roll_m, double mu_spin_m, double dt_s);

}  // namespace vcockpit::physics
