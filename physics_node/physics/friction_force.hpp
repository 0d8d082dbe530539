#pragma once
// Friction at a pair's contacts, paper eqs. 15-17 with DESIGN.md's reading: a pair of bodies is
// sticking or sliding, as one patch over its points.
//   Sticking: each point pulls with a tangential spring from where sticking began, and the
//   pair's total is capped at mu_s sum(N) (eq. 16); when the springs alone pull harder than that
//   it slides. (The damper is not counted in that test: it is what keeps a freshly loaded spring
//   from overshooting the cap, and its transient would otherwise break every loaded contact
//   loose; it is clipped at twice the cap.)
//   Sliding: mu_d N against each point's relative motion (eq. 17) until the pair's |v_t| <
//   epsilon (eq. 15's test), when it sticks again. A new pair sticks if it is slower than epsilon.
// Deciding by speed alone would let the stick spring's own small oscillation (mm/s) throw a loaded
// contact into sliding; capping per point would let the lightly loaded points of a rocking box
// slip first and drag the rest along. mu = sqrt(mu1 mu2) per pair.

#include <Eigen/Geometry>

#include "physics_node/physics/body.hpp"
#include "physics_node/physics/contact.hpp"
#include "physics_node/physics/normal_force.hpp"

namespace vcockpit::physics {

// Where a contact point's stick spring is anchored: state carried from substep to substep (and
// step to step) for each point of each touching pair, sorted by pair.
struct StickAnchor {
  int body_a = -1;
  int body_b = -1;
  Eigen::Vector3d p_A = Eigen::Vector3d::Zero();  // contact point in A's frame (to match)
  Eigen::Vector3d r_A = Eigen::Vector3d::Zero();  // anchor fixed on A, A's frame
  Eigen::Vector3d r_B = Eigen::Vector3d::Zero();  // anchor fixed on B, B's frame
  bool sticking = true;
  // the soft-constraint solver's impulses at this point over the last step (contact_solver.hpp),
  // its next step's warm start: normal (N s) and tangential (N s, A's frame); 0 for the penalty
  double lambda_n = 0.0;
  Eigen::Vector3d lambda_t_A = Eigen::Vector3d::Zero();
};

struct PairFriction {
  double mu_s = 0.0;
  double mu_d = 0.0;       // at most mu_s
  double mu_roll_m = 0.0;  // rolling resistance (rolling_resistance.hpp)
  double mu_spin_m = 0.0;  // spinning resistance (rolling_resistance.hpp)
};

// The pair's coefficients: geometric means (Box2D, Jolt), mu_d capped at mu_s; the rolling and
// spinning resistance's too (0 when either material has none).
PairFriction pair_friction(const ContactBody& A, const ContactBody& B);

// One point of the pair being solved: its normal force and its friction figures.
struct FrictionPoint {
  double N = 0.0;
  Eigen::Vector3d v_t = Eigen::Vector3d::Zero();       // eq. 15: tangential relative velocity
  Eigen::Vector3d f_spring = Eigen::Vector3d::Zero();  // the stick spring's pull
  Eigen::Vector3d f_t = Eigen::Vector3d::Zero();       // spring + damper
};

// Eq. 15: the tangential part of b's velocity relative to a at the contact (v_n along n removed).
Eigen::Vector3d tangential_velocity(const Eigen::Vector3d& v_rel, double v_n,
                                    const Eigen::Vector3d& n_G);

// Eq. 16's trial: the stick spring (stiffness k_pt) pulling the point back to its anchor, and
// its damper (c_pt) against the tangential motion.
void stick_spring(const StickAnchor& anchor, const ContactBody& A, const ContactBody& B,
                  const Eigen::Vector3d& n_G, const NormalPair& k, FrictionPoint& w);

// Eqs. 15-16 over the patch: what the pair's points add up to.
struct PatchSums {
  double N_sum = 0.0;
  double speed_weighted = 0.0;                            // sum of N |v_t|
  Eigen::Vector3d spring_sum = Eigen::Vector3d::Zero();   // loaded points' springs
  Eigen::Vector3d f_trial_sum = Eigen::Vector3d::Zero();  // loaded points' spring + damper
  bool was_sliding = false;  // a matched anchor was sliding on the previous substep

  void add(const FrictionPoint& w);
};

// Eqs. 15-17: the pair sticks or slides as a whole.
struct PatchDecision {
  bool sticking = false;
  bool restart = false;      // anchors start over where the points are
  double stick_scale = 1.0;  // sticking: the spring + damper scaled to at most twice the cap
};
PatchDecision decide_patch(const PatchSums& sums, const PairFriction& mu, double slip_speed_mps);

// Eqs. 16-17: one point's friction force on b (a gets its opposite), and its anchor for the next
// substep (it follows a sliding point; it starts over on a restart or when the point unloads).
Eigen::Vector3d friction_force_G(const PatchDecision& d, const FrictionPoint& w,
                                 const PairFriction& mu, const NormalPair& k, const ContactBody& A,
                                 const Eigen::Isometry3d& X_BG, const ContactPoint& c,
                                 StickAnchor& anchor);

}  // namespace vcockpit::physics
