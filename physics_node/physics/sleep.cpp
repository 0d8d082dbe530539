#include "physics_node/physics/sleep.hpp"

#include <algorithm>
#include <numeric>

#include "common/assert.hpp"

namespace vcockpit::physics {

SleepTracker::SleepTracker(const Scene& scene)
    : scene_(scene),
      object_count_(static_cast<int>(scene.objects.size())),
      parent_(scene.objects.size()),
      kept_awake_(scene.objects.size()),
      island_still_s_(scene.objects.size()) {
  // (once: a mesh's takes a pass over its vertices)
  for (const ObjectSpec& o : scene.objects) reach_m_.push_back(o.shape.bounding_radius_m());
}

int SleepTracker::root(int i) {
  while (parent_[static_cast<std::size_t>(i)] != i) {
    int& p = parent_[static_cast<std::size_t>(i)];
    p = parent_[static_cast<std::size_t>(p)];  // path halving
    i = p;
  }
  return i;
}

void SleepTracker::join(int a, int b) {
  const int ra = root(a);
  const int rb = root(b);
  if (ra == rb) return;
  // the lower index is the root: an island's id does not depend on the contacts' order
  parent_[static_cast<std::size_t>(std::max(ra, rb))] = std::min(ra, rb);
}

bool SleepTracker::free_object(int i, const std::vector<BodyState>& bodies) const {
  const ObjectSpec& o = scene_.objects[static_cast<std::size_t>(i)];
  return o.dynamic && o.control < 0 && !bodies[static_cast<std::size_t>(i)].held();
}

void SleepTracker::update(const std::vector<ContactPoint>& contacts, const std::vector<uint8_t>& may_sleep,
                         std::vector<BodyState>& bodies) {
  VCOCKPIT_ASSERT(static_cast<int>(bodies.size()) == object_count_ &&
                      static_cast<int>(may_sleep.size()) == object_count_,
                  "a body state and a flag per object");
  const SleepParams& p = scene_.sleep;
  std::iota(parent_.begin(), parent_.end(), 0);
  std::fill(kept_awake_.begin(), kept_awake_.end(), 0);
  const auto is_static = [&](int i) { return !scene_.objects[static_cast<std::size_t>(i)].dynamic; };
  for (const ContactPoint& c : contacts) {
    const int a = c.body_a;
    const int b = c.body_b;
    const bool a_object = a < object_count_;
    const bool b_object = b < object_count_;
    const bool a_free = a_object && free_object(a, bodies);
    const bool b_free = b_object && free_object(b, bodies);
    if (a_free && b_free) {
      join(a, b);
      continue;
    }
    // a hand link, a control or a held object moves on its own: what it touches stays awake
    if (a_free && !(b_object && is_static(b))) kept_awake_[static_cast<std::size_t>(a)] = 1;
    if (b_free && !(a_object && is_static(a))) kept_awake_[static_cast<std::size_t>(b)] = 1;
  }
  std::fill(island_still_s_.begin(), island_still_s_.end(), p.time_s);
  for (int i = 0; i < object_count_; ++i) {
    BodyState& body = bodies[static_cast<std::size_t>(i)];
    if (body.asleep) continue;
    if (!free_object(i, bodies)) {
      body.still_s = 0.0;
      continue;
    }
    const bool still = may_sleep[static_cast<std::size_t>(i)] != 0 &&
                       kept_awake_[static_cast<std::size_t>(i)] == 0 &&
                       body.v_G.norm() + body.w_G.norm() * reach_m_[static_cast<std::size_t>(i)] <
                           p.speed_mps;
    body.still_s = still ? body.still_s + scene_.step_s : 0.0;
    double& least = island_still_s_[static_cast<std::size_t>(root(i))];
    least = std::min(least, body.still_s);
  }
  for (int i = 0; i < object_count_; ++i) {
    BodyState& body = bodies[static_cast<std::size_t>(i)];
    if (body.asleep || !free_object(i, bodies)) continue;
    const int island = root(i);
    // (a small tolerance: time_s is a whole number of steps summed in floating point)
    if (island_still_s_[static_cast<std::size_t>(island)] < p.time_s - 0.5 * scene_.step_s) continue;
    body.asleep = true;
    body.island = island;
    body.v_G.setZero();
    body.w_G.setZero();
  }
}

int SleepTracker::wake_island(int object, std::vector<BodyState>& bodies) {
  const BodyState& body = bodies[static_cast<std::size_t>(object)];
  if (!body.asleep) return 0;
  const int island = body.island;
  int woken = 0;
  for (BodyState& b : bodies) {
    if (!b.asleep || b.island != island) continue;
    b.wake();
    ++woken;
  }
  return woken;
}

void SleepTracker::wake_all(std::vector<BodyState>& bodies) {
  for (BodyState& b : bodies) b.wake();
}

}  // namespace vcockpit::physics
