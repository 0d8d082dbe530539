#pragma once
// What friction at a pair's contacts keeps (paper eqs. 15-17, DESIGN.md's reading): the pair's
// coefficients, and each point's stick anchor. The soft contact solver (contact_solver.hpp) runs
// the pair as one patch, sticking or sliding: while it sticks, each point's stick spring pulls it
// back to its anchor and the pair's total is capped at mu_s sum(N) (eq. 16); once that binds it
// slides at mu_d N against its motion (eq. 17) until its |v_t| is under epsilon (eq. 15's test).
// Capping per point would let the lightly loaded points of a rocking box slip first and drag the
// rest along. mu = sqrt(mu1 mu2) per pair.

#include <Eigen/Geometry>

#include "physics_node/physics/body.hpp"
#include "physics_node/physics/contact.hpp"
#include "physics_node/physics/normal_force.hpp"

namespace vcockpit::physics {

// Where a contact point's stick spring is anchored: state carried from step to step for each
// point of each touching pair, sorted by pair.
struct StickAnchor {
  int body_a = -1;
  int body_b = -1;
  Eigen::Vector3d p_A = Eigen::Vector3d::Zero();  // contact point in A's frame (to match)
  Eigen::Vector3d r_A = Eigen::Vector3d::Zero();  // anchor fixed on A, A's frame
  Eigen::Vector3d r_B = Eigen::Vector3d::Zero();  // anchor fixed on B, B's frame
  bool sticking = true;
  // the soft-constraint solver's impulses at this point over the last step (contact_solver.hpp),
  // its next step's warm start: normal (N s) and tangential (N s, A's frame)
  double lambda_n = 0.0;
  Eigen::Vector3d lambda_t_A = Eigen::Vector3d::Zero();
};

struct PairFriction {
  double mu_s = 0.0;
  double mu_d = 0.0;       // at most mu_s
  double mu_roll_m = 0.0;  // rolling resistance (the solver's rolling rows)
  double mu_spin_m = 0.0;  // spinning resistance (the solver's rolling rows)
};

// The pair's coefficients: geometric means (Box2D, Jolt), mu_d capped at mu_s; the rolling and
// spinning resistance's too (0 when either material has none).
PairFriction pair_friction(const ContactBody& A, const ContactBody& B);

}  // namespace vcockpit::physics
