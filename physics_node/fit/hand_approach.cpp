#include "physics_node/fit/hand_approach.hpp"

#include <algorithm>

#include "physics_node/fit/grip_fit.hpp"

namespace vcockpit::fit {

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
  for (std::size_t i = 0; i < hands.size(); ++i) {
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
