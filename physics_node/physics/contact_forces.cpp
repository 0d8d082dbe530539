#include "physics_node/physics/contact_forces.hpp"

#include <algorithm>
#include <cmath>

namespace vcockpit::physics {
namespace {

// Constants of one contact pair, shared by its points.
struct PairConstants {
  double k_pt = 0.0;  // N/m per point
  double c_pt = 0.0;  // N s/m per point
  double mu_s = 0.0;
  double mu_d = 0.0;
};

PairConstants pair_constants(const ContactBody& A, const ContactBody& B, int point_count) {
  const Material& ma = *A.material;
  const Material& mb = *B.material;
  const double k_pair = ma.stiffness_Npm * mb.stiffness_Npm / (ma.stiffness_Npm + mb.stiffness_Npm);
  // effective mass of the relative motion: a body that does not move counts as infinitely heavy
  double m_eff = 0.0;
  if (A.mass_for_damping > 0 && B.mass_for_damping > 0) {
    m_eff = A.mass_for_damping * B.mass_for_damping / (A.mass_for_damping + B.mass_for_damping);
  } else {
    m_eff = std::max(A.mass_for_damping, B.mass_for_damping);
  }
  const double zeta = 0.5 * (ma.damping_ratio + mb.damping_ratio);
  const double c_pair = 2.0 * zeta * std::sqrt(k_pair * m_eff);
  PairConstants out;
  out.k_pt = k_pair / point_count;
  out.c_pt = c_pair / point_count;
  out.mu_s = std::sqrt(ma.mu_s * mb.mu_s);
  out.mu_d = std::min(std::sqrt(ma.mu_d * mb.mu_d), out.mu_s);
  return out;
}

}  // namespace

const ContactForceModel::Anchor* ContactForceModel::match_anchor(const ContactPoint& c,
                                                                 const Eigen::Vector3d& p_A) {
  auto first = std::lower_bound(anchors_.begin(), anchors_.end(), c, [](const Anchor& a, const ContactPoint& k) {
    return a.body_a != k.body_a ? a.body_a < k.body_a : a.body_b < k.body_b;
  });
  Anchor* best = nullptr;
  double best_d2 = kAnchorMatch_m * kAnchorMatch_m;
  for (auto it = first; it != anchors_.end() && it->body_a == c.body_a && it->body_b == c.body_b; ++it) {
    if (it->used) continue;
    const double d2 = (it->p_A - p_A).squaredNorm();
    if (d2 < best_d2) {
      best_d2 = d2;
      best = &*it;
    }
  }
  if (best) best->used = true;
  return best;
}

void ContactForceModel::apply(const std::vector<ContactPoint>& contacts,
                              const std::vector<ContactBody>& bodies,
                              std::vector<Eigen::Vector3d>& F_G, std::vector<Eigen::Vector3d>& M_G,
                              std::vector<AppliedContact>& applied, const KeptPairs& kept) {
  applied.clear();
  next_anchors_.clear();
  // kept pairs' anchors go in among the new ones in pair order (both lists are sorted by pair)
  // (a pair present in the contacts has new anchors: its old ones are never carried)
  std::size_t kept_cursor = 0;
  int present_a = -1, present_b = -1;
  const auto carry_kept_before = [&](int a, int b) {
    for (; kept_cursor < anchors_.size(); ++kept_cursor) {
      const Anchor& old = anchors_[kept_cursor];
      if (old.body_a > a || (old.body_a == a && old.body_b >= b)) break;
      const bool present = old.body_a == present_a && old.body_b == present_b;
      if (!present && kept.keeps(old.body_a, old.body_b)) {
        next_anchors_.push_back(old);
        next_anchors_.back().used = false;
      }
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
    if (kept.objects != nullptr) carry_kept_before(a, b);
    present_a = a;
    present_b = b;
    const ContactBody& A = bodies[a];
    const ContactBody& B = bodies[b];
    const PairConstants k = pair_constants(A, B, static_cast<int>(end - i));
    const Eigen::Isometry3d X_AG = A.X_GB.inverse();
    const Eigen::Isometry3d X_BG = B.X_GB.inverse();

    // pass 1: normal forces, relative motion, anchors and each point's stick-spring trial force
    const std::size_t first = i;
    const std::size_t pair_anchors = next_anchors_.size();
    work_.clear();
    bool was_sliding = false;
    double N_sum = 0.0, speed_weighted = 0.0;
    Eigen::Vector3d f_trial_sum = Eigen::Vector3d::Zero();
    Eigen::Vector3d spring_sum = Eigen::Vector3d::Zero();
    for (; i < end; ++i) {
      const ContactPoint& c = contacts[i];
      const Eigen::Vector3d& n = c.n_G;
      const Eigen::Vector3d v_rel = B.point_velocity(c.p_G) - A.point_velocity(c.p_G);
      const double v_n = v_rel.dot(n);
      PointWork w;
      w.v_t = v_rel - v_n * n;
      // penetration grows when b moves toward a, i.e. against +n
      w.N = std::max(0.0, k.k_pt * c.depth_m - k.c_pt * v_n);

      Anchor anchor;
      anchor.body_a = a;
      anchor.body_b = b;
      anchor.p_A = X_AG * c.p_G;
      if (const Anchor* previous = match_anchor(c, anchor.p_A)) {
        anchor.r_A = previous->r_A;
        anchor.r_B = previous->r_B;
        was_sliding = was_sliding || !previous->sticking;
      } else {
        anchor.r_A = anchor.p_A;
        anchor.r_B = X_BG * c.p_G;
      }
      const Eigen::Vector3d delta = B.X_GB * anchor.r_B - A.X_GB * anchor.r_A;
      w.f_spring = -k.k_pt * (delta - delta.dot(n) * n);
      w.f_t = w.f_spring - k.c_pt * w.v_t;
      N_sum += w.N;
      speed_weighted += w.N * w.v_t.norm();
      if (w.N > 0.0) {
        spring_sum += w.f_spring;
        f_trial_sum += w.f_t;
      }
      work_.push_back(w);
      next_anchors_.push_back(anchor);
    }
    const bool slow = N_sum > 0.0 ? speed_weighted / N_sum < slip_speed_mps_ : true;

    // pass 2: the pair sticks or slides as a whole
    bool sticking = false;
    bool restart = false;
    if (was_sliding && !slow) {
      restart = true;  // still sliding: kinetic friction, anchors follow the contact
    } else if (was_sliding) {
      sticking = true;  // slowed below epsilon: sticks from here
      restart = true;
    } else {
      sticking = spring_sum.norm() <= k.mu_s * N_sum;  // eq. 16 over the patch
    }
    // sticking: spring + damper; the damper may exceed the cap for a moment (it is what keeps
    // a freshly loaded spring from overshooting the cap), but never more than the cap again
    const double trial_norm = f_trial_sum.norm();
    const double stick_scale = trial_norm > 2.0 * k.mu_s * N_sum && trial_norm > 0.0
                                   ? 2.0 * k.mu_s * N_sum / trial_norm
                                   : 1.0;
    for (std::size_t j = 0; j < work_.size(); ++j) {
      const ContactPoint& c = contacts[first + j];
      PointWork& w = work_[j];
      Anchor& anchor = next_anchors_[pair_anchors + j];
      anchor.sticking = sticking;
      Eigen::Vector3d f_t = Eigen::Vector3d::Zero();
      if (w.N > 0.0) {
        if (sticking && !restart) {
          f_t = w.f_t * stick_scale;
        } else if (!sticking && !restart) {
          // just broke loose: mu_d N along the spring's pull; the anchor follows so the spring
          // holds that force
          const double f_norm = w.f_spring.norm();
          if (f_norm > 0.0) f_t = w.f_spring * (k.mu_d * w.N / f_norm);
          anchor.r_B = X_BG * (A.X_GB * anchor.r_A - f_t / k.k_pt);
        } else if (!sticking) {
          const double speed = w.v_t.norm();
          if (speed > 0.0) f_t = -k.mu_d * w.N / speed * w.v_t;  // eq. 17
        }
      }
      if (restart || w.N <= 0.0) {
        anchor.r_A = anchor.p_A;
        anchor.r_B = X_BG * c.p_G;
      }
      const Eigen::Vector3d F = w.N * c.n_G + f_t;
      F_G[b] += F;
      M_G[b] += (c.p_G - B.X_GB.translation()).cross(F);
      F_G[a] -= F;
      M_G[a] -= (c.p_G - A.X_GB.translation()).cross(F);
      applied.push_back({c, F, w.N, !sticking});
    }
  }
  if (kept.objects != nullptr) carry_kept_before(INT32_MAX, INT32_MAX);
  std::swap(anchors_, next_anchors_);
}

}  // namespace vcockpit::physics
