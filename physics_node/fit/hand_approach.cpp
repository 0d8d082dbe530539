#include "physics_node/fit/hand_approach.hpp"

#include <algorithm>

#include "physics_node/fit/grip_fit.hpp"
#include "physics_node/fit/shape_distance.hpp"

namespace vcockpit::fit {
namespace {
// a bound must clear the nearest by this much (far above FCL's 1e-9 m tolerance)
constexpr double kSkipMargin_m = 1e-6;
}  // namespace

std::vector<RecordedHand> hands_before(const hand::HandModel& model,
                                       const std::vector<hand::GloveSample>& samples,
                                       std::size_t moment_index) {
  std::vector<RecordedHand> out;
  const std::size_t end = std::min(std::max<std::size_t>(moment_index, 1), samples.size());
  out.reserve(end);
  for (std::size_t i = 0; i < end; ++i)
    out.push_back({samples[i].t_ns, grip_hand_at(model, samples[i])});
  return out;
}

HandApproach hand_approach(const std::vector<RecordedHand>& hands, const physics::Shape& shape,
                           const Eigen::Isometry3d& X_GO) {
  HandApproach out;
  const ShapeCore core = shape_core(shape, X_GO);
  for (std::size_t i = 0; i < hands.size(); ++i) {
    // a hand that cannot come nearer than the nearest so far is left out (a cheap bound: its
    // capsules against the shape's core, the palm box as its enclosing ball)
    if (i > 0) {
      const GripHand& h = hands[i].hand;
      double bound_m =
          segment_segment_distance(h.X_GP.translation(), h.X_GP.translation(), core.a_G, core.b_G) -
          core.radius_m - 0.5 * h.palm_size_m.norm();
      for (int l = 1; l < hand::kLinkCount && bound_m > out.nearest_m + kSkipMargin_m; ++l) {
        const auto k = static_cast<std::size_t>(l);
        bound_m = std::min(bound_m,
                           capsule_distance_lower_bound(core, h.a_G[k], h.b_G[k], h.radius_m[k]));
      }
      if (bound_m > out.nearest_m + kSkipMargin_m) continue;
    }
    const Placement p = evaluate_placement(hands[i].hand, shape, X_GO);
    if (i == 0) out.first_m = -p.deepest_m;
    if (i == 0 || -p.deepest_m < out.nearest_m) {
      out.nearest_m = -p.deepest_m;
      out.nearest_t_ns = hands[i].t_ns;
      out.nearest_link = p.deepest_link;
    }
  }
  return out;
}

}  // namespace vcockpit::fit
