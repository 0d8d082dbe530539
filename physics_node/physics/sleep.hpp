#pragma once
// Sleeping (Box2D's islands, Jolt's sleeping bodies): a free object that rests costs nothing until
// something that moves touches it.
//
// After each step, every free object (dynamic, not a control, not held) none of whose points
// moved faster than SleepParams::speed_mps (|v| + |w| r, r its farthest reach from the
// centroid) has been still for that much longer; any faster motion starts its count again. The free objects touching each other (the last step's
// contacts) form islands; an island whose every member has been still for time_s falls asleep:
// its bodies stop (velocity zero) and are left out of the broadphase's pairs with static bodies
// and with each other, so they cost no narrowphase, force or integration. A hand link, a control
// or a held object touching an object keeps it awake (each moves on its own), and so does the
// world (World::update_sleep) while a hand still owns it (held, or clearing it after a release).
//
// A sleeping body wakes with its island when a contact with a moving body is found (the
// world's step, which then runs its collision again: the woken bodies' contacts with the
// floor are there from the first step they are awake). Its friction anchors go when it falls
// asleep (carrying them every step would cost what sleeping saves): it wakes with new ones
// at zero stretch, which on a slope gives way by the stretch that holds it (mg sin(theta) / k,
// micrometres) before they hold again.
//
// Deterministic: islands by union-find with the lowest index as root, in object order.

#include <cstdint>
#include <vector>

#include "physics_node/physics/body.hpp"
#include "physics_node/physics/contact.hpp"
#include "physics_node/physics/scene.hpp"

namespace vcockpit::physics {

class SleepTracker {
 public:
  explicit SleepTracker(const Scene& scene);

  // After a step, over the last step's contacts (objects then hand links, as the collision
  // world numbers bodies). may_sleep[i] == 0: object i stays awake this step whatever its motion.
  void update(const std::vector<ContactPoint>& contacts, const std::vector<uint8_t>& may_sleep,
             std::vector<BodyState>& bodies);

  // Wakes `object`'s island if it sleeps; returns how many bodies woke.
  static int wake_island(int object, std::vector<BodyState>& bodies);
  // Wakes every body (an instructor's reset puts objects where nothing rests them yet).
  static void wake_all(std::vector<BodyState>& bodies);

 private:
  int root(int i);
  void join(int a, int b);
  bool free_object(int i, const std::vector<BodyState>& bodies) const;

  const Scene& scene_;
  int object_count_;
  std::vector<int> parent_;          // union-find over the objects
  std::vector<uint8_t> kept_awake_;  // touched by something that moves on its own
  std::vector<double> island_still_s_;  // per root: the least still time of its members
  std::vector<double> reach_m_;         // per object: its farthest point from the centroid
};

}  // namespace vcockpit::physics
