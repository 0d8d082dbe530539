#include "physics_node/physics/soft_constraint.hpp"

#include <cmath>

namespace vcockpit::physics {

double dashpot_restitution(double zeta) {
  if (!(zeta < 1.0)) return 0.0;
  if (!(zeta > 0.0)) return 1.0;
  const double s = std::sqrt(1.0 - zeta * zeta);
  const double phase = zeta < 1.0 / std::sqrt(2.0)
                           ? M_PI - std::atan(2.0 * zeta * s / (1.0 - 2.0 * zeta * zeta))
                           : std::atan(2.0 * zeta * s / (2.0 * zeta * zeta - 1.0));
  return std::exp(-zeta / s * phase);
}

}  // namespace vcockpit::physics
