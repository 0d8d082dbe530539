#pragma once
// What the narrowphase reports. Bodies are numbered objects first (0 .. N-1, the scene's order),
// then the hand's links (N + Link index). The normal points from body_a to body_b (FCL's
// convention), so body_b is pushed along +n and body_a along -n.

#include <Eigen/Core>

namespace vcockpit::physics {

struct ContactPoint {
  int body_a = -1;
  int body_b = -1;                                // body_a < body_b
  Eigen::Vector3d p_G = Eigen::Vector3d::Zero();  // contact point in world (m)
  Eigen::Vector3d n_G = Eigen::Vector3d::UnitZ(); // unit normal, from a to b
  double depth_m = 0.0;                           // penetration depth (m), > 0
};

// A contact point and what the step's solve applied there (eqs. 11-17): the observation the
// grasp test (eqs. 30-31), the controls' pushers and the adapters read.
struct AppliedContact {
  ContactPoint contact;
  Eigen::Vector3d F_on_b_G = Eigen::Vector3d::Zero();  // total contact force on body b (N)
  double normal_N = 0.0;
  bool sliding = false;
};

}  // namespace vcockpit::physics
