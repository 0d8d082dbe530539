#include "physics_node/physics/contact_forces.hpp"

#include <algorithm>
#include <cmath>

#include "common/assert.hpp"
#include "physics_node/physics/anchor_match.hpp"
#include "physics_node/physics/contact_sums.hpp"
#include "physics_node/physics/normal_force.hpp"
#include "physics_node/physics/rolling_resistance.hpp"

namespace vcockpit::physics {

const StickAnchor* ContactForceModel::match_anchor(const std::vector<StickAnchor>& previous,
                                                   const ContactPoint& c,
                                                   const Eigen::Vector3d& p_A) {
  return match_stick_anchor(previous, anchor_used_, c, p_A, ContactForceModel::kAnchorMatch_m);
}

void ContactForceModel::apply(const std::vector<ContactPoint>& contacts,
                              const std::vector<ContactBody>& bodies, double dt_s,
                              std::vector<Eigen::Vector3d>& F_G, std::vector<Eigen::Vector3d>& M_G,
                              std::vector<AppliedContact>& applied,
                              std::vector<StickAnchor>& anchors, const KeptPairs& kept) {
  applied.clear();
  next_anchors_.clear();
  anchor_used_.assign(anchors.size(), 0);
  // kept pairs' anchors go in among the new ones in pair order (both lists are sorted by pair)
  // (a pair present in the contacts has new anchors: its old ones are never carried)
  std::size_t kept_cursor = 0;
  int present_a = -1, present_b = -1;
  const auto carry_kept_before = [&](int a, int b) {
    for (; kept_cursor < anchors.size(); ++kept_cursor) {
      const StickAnchor& old = anchors[kept_cursor];
      if (old.body_a > a || (old.body_a == a && old.body_b >= b)) break;
      const bool present = old.body_a == present_a && old.body_b == present_b;
      if (!present && kept.keeps(old.body_a, old.body_b)) next_anchors_.push_back(old);
    }
  };
  std::size_t i = 0;
  while (i < contacts.size()) {
    // one pair's points are consecutive
    std::size_t end = i + 1;
    while (end < contacts.size() && contacts[end].body_a == contacts[i].body_a &&
           contacts[end].body_b == contacts[i].body_b) {
      ++end;
    }
    const int a = contacts[i].body_a;
    const int b = contacts[i].body_b;
    VCOCKPIT_ASSERT(pair_before(present_a, present_b, a, b), "contacts must be sorted by pair");
    VCOCKPIT_ASSERT(0 <= a && a < b && b < static_cast<int>(bodies.size()),
                    "contact bodies out of range");
    if (kept.objects != nullptr) carry_kept_before(a, b);
    present_a = a;
    present_b = b;
    solve_pair(contacts, i, end, bodies, dt_s, F_G, M_G, applied, anchors);
    i = end;
  }
  if (kept.objects != nullptr) carry_kept_before(INT32_MAX, INT32_MAX);
  std::swap(anchors, next_anchors_);
}

void ContactForceModel::solve_pair(const std::vector<ContactPoint>& contacts, std::size_t first,
                                   std::size_t end, const std::vector<ContactBody>& bodies,
                                   double dt_s, std::vector<Eigen::Vector3d>& F_G,
                                   std::vector<Eigen::Vector3d>& M_G,
                                   std::vector<AppliedContact>& applied,
                                   const std::vector<StickAnchor>& previous) {
  const int a = contacts[first].body_a;
  const int b = contacts[first].body_b;
  const ContactBody& A = bodies[a];
  const ContactBody& B = bodies[b];
  const NormalPair k = normal_pair(A, B, static_cast<int>(end - first));
  const PairFriction mu = pair_friction(A, B);
  const Eigen::Isometry3d X_AG = A.X_GB.inverse();
  const Eigen::Isometry3d X_BG = B.X_GB.inverse();

  // pass 1: normal forces (eqs. 11-14), relative motion (eq. 15), anchors and each point's
  // stick-spring trial force (eq. 16)
  const std::size_t pair_anchors = next_anchors_.size();
  work_.clear();
  PatchSums sums;
  for (std::size_t i = first; i < end; ++i) {
    const ContactPoint& c = contacts[i];
    const Eigen::Vector3d& n = c.n_G;
    const Eigen::Vector3d v_rel = B.point_velocity(c.p_G) - A.point_velocity(c.p_G);
    const double v_n = v_rel.dot(n);
    FrictionPoint w;
    w.v_t = tangential_velocity(v_rel, v_n, n);
    w.N = normal_force_N(k, c.depth_m, v_n);

    StickAnchor anchor;
    anchor.body_a = a;
    anchor.body_b = b;
    anchor.p_A = X_AG * c.p_G;
    if (const StickAnchor* before = match_anchor(previous, c, anchor.p_A)) {
      anchor.r_A = before->r_A;
      anchor.r_B = before->r_B;
      sums.was_sliding = sums.was_sliding || !before->sticking;
    } else {
      anchor.r_A = anchor.p_A;
      anchor.r_B = X_BG * c.p_G;
    }
    stick_spring(anchor, A, B, n, k, w);
    sums.add(w);
    work_.push_back(w);
    next_anchors_.push_back(anchor);
  }

  // pass 2: the pair sticks or slides as a whole (eqs. 15-17); each point's force goes into
  // both bodies' sums (eqs. 18-19)
  const PatchDecision decision = decide_patch(sums, mu, slip_speed_mps_);
  Eigen::Vector3d n_weighted = Eigen::Vector3d::Zero();  // the patch's normal, by load
  for (std::size_t j = 0; j < work_.size(); ++j) {
    const ContactPoint& c = contacts[first + j];
    const FrictionPoint& w = work_[j];
    StickAnchor& anchor = next_anchors_[pair_anchors + j];
    const Eigen::Vector3d f_t = friction_force_G(decision, w, mu, k, A, X_BG, c, anchor);
    const Eigen::Vector3d F = contact_force_G(w.N, c.n_G, f_t);
    add_contact_to_sums(a, b, A, B, c.p_G, F, F_G, M_G);
    applied.push_back({c, F, w.N, !decision.sticking});
    n_weighted += w.N * c.n_G;
  }
  // the pair's rolling and spinning resistance: one couple for the patch, from its total load
  if (sums.N_sum > 0.0 && (mu.mu_roll_m > 0.0 || mu.mu_spin_m > 0.0)) {
    const Eigen::Vector3d M_couple = resistance_couple_on_b_G(
        A, B, n_weighted.normalized(), sums.N_sum, mu.mu_roll_m, mu.mu_spin_m, dt_s);
    M_G[b] += M_couple;
    M_G[a] -= M_couple;
  }
}

}  // namespace vcockpit::physics
