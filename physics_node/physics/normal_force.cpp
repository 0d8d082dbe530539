#include "physics_node/physics/normal_force.hpp"

#include <algorithm>
#include <cmath>

namespace vcockpit::physics {

NormalPair normal_pair(const ContactBody& A, const ContactBody& B, int point_count) {
  const Material& ma = *A.material;
  const Material& mb = *B.material;
  const double k_pair = pair_stiffness(ma, mb);
  // effective mass of the relative motion: a body that does not move counts as infinitely heavy
  double m_eff = 0.0;
  if (A.mass_for_damping > 0 && B.mass_for_damping > 0) {
    m_eff = A.mass_for_damping * B.mass_for_damping / (A.mass_for_damping + B.mass_for_damping);
  } else {
    m_eff = std::max(A.mass_for_damping, B.mass_for_damping);
  }
  const double zeta = 0.5 * (ma.damping_ratio + mb.damping_ratio);
  const double c_pair = 2.0 * zeta * std::sqrt(k_pair * m_eff);
  NormalPair out;
  out.k_pt = k_pair / point_count;
  out.c_pt = c_pair / point_count;
  return out;
}

double normal_force_N(const NormalPair& k, double depth_m, double v_n_mps) {
  return std::max(0.0, k.k_pt * depth_m - k.c_pt * v_n_mps);
}

}  // namespace vcockpit::physics
