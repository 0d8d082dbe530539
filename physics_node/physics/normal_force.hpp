#pragma once
// The normal force of a contact, paper eqs. 11-14, and the normal dashpot beyond the paper:
//   N = k_pt d + c_pt d_dot, never pulling (N >= 0).
// k_pt is the pair's series stiffness k1 k2 / (k1 + k2) (eqs. 11-14) shared among the points the
// narrowphase reported for the pair, so a resting depth is m g / k_eff however many points;
// c_pt comes from the damping ratio, the pair's stiffness and its effective mass (pure springs
// never come to rest under eq. 24).

#include "physics_node/physics/body.hpp"

namespace vcockpit::physics {

// The spring and dashpot of one of a pair's points.
struct NormalPair {
  double k_pt = 0.0;  // N/m per point
  double c_pt = 0.0;  // N s/m per point
};

// Eqs. 11-14: the pair's series stiffness and its dashpot, shared among point_count points.
NormalPair normal_pair(const ContactBody& A, const ContactBody& B, int point_count);

// Eqs. 11-14 with the dashpot: the normal force (N) at depth d (m) when body b moves along +n at
// v_n (m/s) relative to a; penetration grows when b moves toward a, i.e. against +n.
double normal_force_N(const NormalPair& k, double depth_m, double v_n_mps);

}  // namespace vcockpit::physics
