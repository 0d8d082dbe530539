#pragma once
// How deep the drawn hand is inside the cockpit's static objects, computed here independently of
// the physics (which computes no hand-static contacts at all): every hand link as the hand model
// describes it — the palm box, 15 phalanx capsules on [0, length] of the link's x axis — against
// every static object of the scene, by FCL's own narrowphase (libccd GJK/EPA penetration depth).

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <memory>
#include <vector>

#include "hand/hand_joints.hpp"
#include "hand/hand_model.hpp"
#include "physics_node/physics/scene.hpp"

namespace vcockpit::test {

struct Penetration {
  double depth_m = 0.0;  // 0 when nothing overlaps
  int link = -1;         // hand::Link
  int object = -1;       // scene object index
};

// The lowest z of phalanx `link`'s capsule (on [0, length] of its x axis) with the link frame at
// X (in whatever frame X is given: z of that frame).
inline double capsule_lowest_z(const hand::HandModel& hand, int link, const Eigen::Isometry3d& X) {
  const hand::Capsule& capsule = hand.capsules[static_cast<std::size_t>(link)];
  return std::min(X.translation().z(), (X * Eigen::Vector3d(capsule.length_m, 0, 0)).z()) -
         capsule.radius_m;
}

class HandStaticClearance {
 public:
  HandStaticClearance(const physics::Scene& scene, const hand::HandModel& hand);
  ~HandStaticClearance();

  // The deepest overlap of any link (poses in the world) with any static object.
  Penetration deepest(const std::array<Eigen::Isometry3d, hand::kLinkCount>& X_GL);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace vcockpit::test
