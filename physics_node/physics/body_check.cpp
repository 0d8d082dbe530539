#include "physics_node/physics/body_check.hpp"

#include <algorithm>

#include "common/assert.hpp"

namespace vcockpit::physics {

const char* body_fault_name(BodyFaultKind what) {
  switch (what) {
    case BodyFaultKind::kNone:
      return "sound";
    case BodyFaultKind::kNonFinite:
      return "non-finite pose or velocity";
    case BodyFaultKind::kTooFast:
      return "speed beyond the limit";
    case BodyFaultKind::kSpinning:
      return "spin beyond the limit";
    case BodyFaultKind::kTooFar:
      return "beyond the distance limit from the origin";
  }
  return "unknown";
}

BodyFaultKind check_body(const BodyState& body, const SanityLimits& limits) {
  if (!body.X_GO.matrix().allFinite() || !body.v_G.allFinite() || !body.w_G.allFinite())
    return BodyFaultKind::kNonFinite;
  // norms of huge finite vectors overflow to infinity, which is over the limit too
  if (body.v_G.norm() > limits.max_speed_mps) return BodyFaultKind::kTooFast;
  if (body.w_G.norm() > limits.max_spin_radps) return BodyFaultKind::kSpinning;
  if (body.X_GO.translation().norm() > limits.max_distance_m) return BodyFaultKind::kTooFar;
  return BodyFaultKind::kNone;
}

BodyCheck::BodyCheck(const Scene& scene)
    : scene_(scene), recovered_(scene.objects.size(), 0), fault_of_(scene.objects.size(), -1) {
  faults_.reserve(scene.objects.size());
  new_faults_.reserve(scene.objects.size());
}

void BodyCheck::check(std::vector<BodyState>& bodies, const std::vector<BodyState>& start,
                      int64_t t_ns) {
  VCOCKPIT_ASSERT(bodies.size() == scene_.objects.size() && start.size() == bodies.size(),
                  "one body state per object");
  if (any_recovered_) std::fill(recovered_.begin(), recovered_.end(), uint8_t{0});
  any_recovered_ = false;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    if (!scene_.objects[i].dynamic) continue;
    const BodyFaultKind what = check_body(bodies[i], scene_.limits);
    if (what == BodyFaultKind::kNone) continue;
    recover(static_cast<int>(i), bodies[i], start[i]);
    recovered_[i] = 1;
    any_recovered_ = true;
    int& index = fault_of_[i];
    if (index < 0) {
      index = static_cast<int>(faults_.size());
      faults_.push_back({static_cast<int>(i), what, t_ns, 0});
      new_faults_.push_back({static_cast<int>(i), what, t_ns, 1});
    }
    ++faults_[static_cast<std::size_t>(index)].count;
  }
}

void BodyCheck::recover(int object, BodyState& body, const BodyState& start) const {
  body = start;
  body.v_G.setZero();
  body.w_G.setZero();
  // awake: it broke in a step it moved in, and what it rested on may have moved since
  body.wake();
  // a start already broken (a restored state, a broken initial pose): the scene's initial pose
  if (check_body(body, scene_.limits) != BodyFaultKind::kNone)
    body.X_GO = scene_.objects[static_cast<std::size_t>(object)].X_GO;
}

}  // namespace vcockpit::physics
