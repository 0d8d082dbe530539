#pragma once
// Carrying a contact point's stick anchor from one step to the next: the previous anchor of the
// same pair nearest the point, within max_m (kStickAnchorMatch_m), not yet taken by another point.

#include <algorithm>
#include <cstdint>
#include <vector>

#include "physics_node/physics/contact.hpp"
#include "physics_node/physics/friction_force.hpp"

namespace vcockpit::physics {

// How far a contact point may be from its anchor's point of the last step and still take it.
constexpr double kStickAnchorMatch_m = 0.005;

// Contacts and anchors are sorted by pair: (body_a, body_b) in this order.
inline bool pair_before(int a0, int b0, int a1, int b1) { return a0 != a1 ? a0 < a1 : b0 < b1; }

// `previous` is sorted by pair; `used` (one flag per previous anchor) marks the one returned.
inline const StickAnchor* match_stick_anchor(const std::vector<StickAnchor>& previous,
                                             std::vector<uint8_t>& used, const ContactPoint& c,
                                             const Eigen::Vector3d& p_A, double max_m) {
  auto first = std::lower_bound(previous.begin(), previous.end(), c,
                                [](const StickAnchor& a, const ContactPoint& k) {
                                  return pair_before(a.body_a, a.body_b, k.body_a, k.body_b);
                                });
  const StickAnchor* best = nullptr;
  std::size_t best_index = 0;
  double best_d2 = max_m * max_m;
  for (auto it = first; it != previous.end() && it->body_a == c.body_a && it->body_b == c.body_b; ++it) {
    const auto index = static_cast<std::size_t>(it - previous.begin());
    if (used[index] != 0) continue;
    const double d2 = (it->p_A - p_A).squaredNorm();
    if (d2 < best_d2) {
      best_d2 = d2;
      best = &*it;
      best_index = index;
    }
  }
  if (best) used[best_index] = 1;
  return best;
}

}  // namespace vcockpit::physics
