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

Eigen::Vector3d tangential_velocity(const Eigen::Vector3d& v_rel, double v_n,
                                    const Eigen::Vector3d& n_G) {
  return v_rel - v_n * n_G;
}

void stick_spring(const StickAnchor& anchor, const ContactBody& A, const ContactBody& B,
                  const Eigen::Vector3d& n_G, const NormalPair& k, FrictionPoint& w) {
  const Eigen::Vector3d& n = n_G;
  const Eigen::Vector3d delta = B.X_GB * anchor.r_B - A.X_GB * anchor.r_A;
  w.f_spring = -k.k_pt * (delta - delta.dot(n) * n);
  w.f_t = w.f_spring - k.c_pt * w.v_t;
}

void PatchSums::add(const FrictionPoint& w) {
  N_sum += w.N;
  speed_weighted += w.N * w.v_t.norm();
  if (w.N > 0.0) {
    spring_sum += w.f_spring;
    f_trial_sum += w.f_t;
  }
}

PatchDecision decide_patch(const PatchSums& sums, const PairFriction& mu, double slip_speed_mps) {
  const double N_sum = sums.N_sum;
  const bool slow = N_sum > 0.0 ? sums.speed_weighted / N_sum < slip_speed_mps : true;
  PatchDecision d;
  if (sums.was_sliding && !slow) {
    d.restart = true;  // still sliding: kinetic friction, anchors follow the contact
  } else if (sums.was_sliding) {
    d.sticking = true;  // slowed below epsilon: sticks from here
    d.restart = true;
  } else {
    d.sticking = sums.spring_sum.norm() <= mu.mu_s * N_sum;  // eq. 16 over the patch
  }
  // sticking: spring + damper; the damper may exceed the cap for a moment (it is what keeps
  // a freshly loaded spring from overshooting the cap), but never more than the cap again
  const double trial_norm = sums.f_trial_sum.norm();
  d.stick_scale = trial_norm > 2.0 * mu.mu_s * N_sum && trial_norm > 0.0
                      ? 2.0 * mu.mu_s * N_sum / trial_norm
                      : 1.0;
  return d;
}

Eigen::Vector3d friction_force_G(const PatchDecision& d, const FrictionPoint& w,
                                 const PairFriction& mu, const NormalPair& k, const ContactBody& A,
                                 const Eigen::Isometry3d& X_BG, const ContactPoint& c,
                                 StickAnchor& anchor) {
  const bool sticking = d.sticking;
  const bool restart = d.restart;
  anchor.sticking = sticking;
  Eigen::Vector3d f_t = Eigen::Vector3d::Zero();
  if (w.N > 0.0) {
    if (sticking && !restart) {
      f_t = w.f_t * d.stick_scale;
    } else if (!sticking && !restart) {
      // just broke loose: mu_d N along the spring's pull; the anchor follows so the spring
      // holds that force
      const double f_norm = w.f_spring.norm();
      if (f_norm > 0.0) f_t = w.f_spring * (mu.mu_d * w.N / f_norm);
      anchor.r_B = X_BG * (A.X_GB * anchor.r_A - f_t / k.k_pt);
    } else if (!sticking) {
      const double speed = w.v_t.norm();
      if (speed > 0.0) f_t = -mu.mu_d * w.N / speed * w.v_t;  // eq. 17
    }
  }
  if (restart || w.N <= 0.0) {
    anchor.r_A = anchor.p_A;
    anchor.r_B = X_BG * c.p_G;
  }
  return f_t;
}

}  // namespace vcockpit::physics
