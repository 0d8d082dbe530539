#pragma once
// Substeps short enough for the stiffest contact that can happen within a step (paper §4.3's
// semi-implicit Euler is stable on a spring below 2 sqrt(m/k); keep a margin):
//   dt_sub <= safety sqrt(m_eff / k)
// with k a pair's series stiffness and m_eff the least effective mass it can show: against a
// static, held or hand body the free body's own, between two free bodies the two in series.
// Only the pairs that can touch within the step count (sweep and prune over boxes grown by how far
// each body can move in the step): a cup resting alone does not pay for a pen lying across the
// cockpit.

#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <vector>

#include "physics_node/physics/body.hpp"
#include "physics_node/physics/broadphase.hpp"
#include "physics_node/physics/collision.hpp"
#include "physics_node/physics/scene.hpp"

namespace vcockpit::physics {

// A lower bound of the effective mass a contact on this dynamic object can see,
// 1 / (1/m + (r x n)^T I^-1 (r x n)) over every point and normal of its shape (kg).
double worst_contact_mass(const ObjectSpec& o);

class SubstepChoice {
 public:
  // `collision` gives the hand links' boxes; both must outlive this.
  SubstepChoice(const Scene& scene, const CollisionWorld& collision);

  // The substep count, in [1, contact.max_substeps], for the step that starts with the bodies in
  // `bodies` and each hand (`hands`, in the scene's hand order; fewer or an inactive one: not
  // in the step) sweeping from its links now to the wrist pose and joint angles at its end.
  struct HandSweep {
    const std::array<Eigen::Isometry3d, kLinkCount>* X_GL_now = nullptr;  // null: not active
    Eigen::Isometry3d X_GH_end = Eigen::Isometry3d::Identity();
    JointAngles q_end{};
  };
  int choose(const std::vector<BodyState>& bodies, const std::vector<HandSweep>& hands);

  // The pairs that could touch within the last chosen step: objects, then the hands' links.
  const std::vector<BodyPair>& reachable_pairs() const { return reach_pairs_; }

 private:
  void find_reachable_pairs(const std::vector<BodyState>& bodies, const std::vector<HandSweep>& hands);

  static constexpr double kReachMargin_m = 0.002;

  const Scene& scene_;
  const CollisionWorld& collision_;
  int object_count_;
  std::vector<double> contact_mass_;  // worst_contact_mass of the dynamic objects
  SweepAndPrune reach_;
  std::vector<BodyPair> reach_pairs_;
  std::vector<uint8_t> may_wake_;  // per object: asleep, in an island a moving body can reach
};

}  // namespace vcockpit::physics
