#pragma once
// Virtual forces at contacts (paper §4.2, eqs. 11-19, with DESIGN.md's corrections), in three
// stages named after the equations:
//   normal_force.hpp    eqs. 11-14 and the normal dashpot: N = k_pt d + c_pt d_dot, N >= 0
//   friction_force.hpp  eqs. 15-17: a pair sticks (a tangential spring capped at mu_s sum(N))
//                       or slides (mu_d N against the relative motion) as one patch
//   contact_sums.hpp    eqs. 18-19: each body's force sum and torque sum about its centroid
//   rolling_resistance.hpp  beyond the paper: a couple against the pair's relative rolling
//                       and spinning
// This model runs them over a substep's contacts, pair by pair, and keeps the stick anchors
// from substep to substep: a new contact takes the anchor of the previous substep's contact of
// the same pair within kAnchorMatch_m of it.

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "physics_node/physics/body.hpp"
#include "physics_node/physics/contact.hpp"
#include "physics_node/physics/friction_force.hpp"

namespace vcockpit::physics {

struct AppliedContact {
  ContactPoint contact;
  Eigen::Vector3d F_on_b_G = Eigen::Vector3d::Zero();  // total contact force on body b (N)
  double normal_N = 0.0;
  bool sliding = false;
};

// Pairs left out of a substep's contacts whose anchors are kept as they are: a hand link
// (body >= first_hand_body) with an object flagged in `objects` (null: none).
struct KeptPairs {
  const std::vector<uint8_t>* objects = nullptr;
  int first_hand_body = 0;
  bool keeps(int body_a, int body_b) const {
    return objects != nullptr && body_b >= first_hand_body && body_a < first_hand_body &&
           (*objects)[static_cast<std::size_t>(body_a)] != 0;
  }
};

class ContactForceModel {
 public:
  static constexpr double kAnchorMatch_m = 0.005;

  explicit ContactForceModel(double slip_speed_mps) : slip_speed_mps_(slip_speed_mps) {}

  // Computes every contact's force for bodies `bodies` (indexed like the contacts) over a
  // substep of dt_s and adds them to F_G / M_G (force and torque about each body's origin), with
  // each pair's rolling-resistance couple. `contacts` must be sorted by pair.
  // Updates the stick anchors `anchors` (the previous substep's in, this one's out; those of
  // `kept` pairs absent from `contacts` carry over). No allocation once the vectors have grown
  // to the scene's size.
  void apply(const std::vector<ContactPoint>& contacts, const std::vector<ContactBody>& bodies,
             double dt_s, std::vector<Eigen::Vector3d>& F_G, std::vector<Eigen::Vector3d>& M_G,
             std::vector<AppliedContact>& applied, std::vector<StickAnchor>& anchors,
             const KeptPairs& kept = {});
  // The same with anchors the model keeps itself.
  void apply(const std::vector<ContactPoint>& contacts, const std::vector<ContactBody>& bodies,
             double dt_s, std::vector<Eigen::Vector3d>& F_G, std::vector<Eigen::Vector3d>& M_G,
             std::vector<AppliedContact>& applied, const KeptPairs& kept = {}) {
    apply(contacts, bodies, dt_s, F_G, M_G, applied, anchors_, kept);
  }

  void reset() { anchors_.clear(); }

 private:
  // One pair's points, contacts[first, end): normal forces, friction, rolling and spinning
  // resistance, and their sums.
  void solve_pair(const std::vector<ContactPoint>& contacts, std::size_t first, std::size_t end,
                  const std::vector<ContactBody>& bodies, double dt_s,
                  std::vector<Eigen::Vector3d>& F_G,
                  std::vector<Eigen::Vector3d>& M_G, std::vector<AppliedContact>& applied,
                  const std::vector<StickAnchor>& previous);
  // The previous substep's unused anchor of c's pair nearest p_A (within kAnchorMatch_m), if any.
  const StickAnchor* match_anchor(const std::vector<StickAnchor>& previous, const ContactPoint& c,
                                  const Eigen::Vector3d& p_A);

  double slip_speed_mps_;
  std::vector<StickAnchor> anchors_;  // the model's own (the overload without anchors)
  // scratch of one substep
  std::vector<StickAnchor> next_anchors_;  // being built
  std::vector<uint8_t> anchor_used_;       // previous anchors already matched
  std::vector<FrictionPoint> work_;        // the pair being solved
};

}  // namespace vcockpit::physics
