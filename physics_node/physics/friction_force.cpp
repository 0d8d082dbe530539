#include "physics_node/physics/friction_force.hpp"

#include <algorithm>
#include <cmath>

namespace vcockpit::physics {

PairFriction pair_friction(const ContactBody& A, const ContactBody& B) {
  const Material& ma = *A.material;
  const Material& mb = *B.material;
  PairFriction out;
  out.mu_s = std::sqrt(ma.mu_s * mb.mu_s);
  out.mu_d = std::min(std::sqrt(ma.mu_d * mb.mu_d), out.mu_s);
  out.mu_roll_m = std::sqrt(ma.mu_roll_m * mb.mu_roll_m);
  out.mu_spin_m = std::sqrt(ma.mu_spin_m * mb.mu_spin_m);
  return out;
}

}  // namespace vcockpit::physics
