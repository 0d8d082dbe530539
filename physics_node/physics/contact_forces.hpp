#pragma once
// Virtual forces at contacts (paper §4.2, eqs. 11-19, with DESIGN.md's corrections):
//   normal   N = k_pt d + c_pt d_dot, never pulling (N >= 0). k_pt is the pair's series
//            stiffness k1 k2 / (k1 + k2) (eqs. 11-14) shared among the points the narrowphase
//            reported for the pair, so a resting depth is m g / k_eff however many points;
//            c_pt from the damping ratio, the pair's stiffness and effective mass.
//   friction a pair of bodies is sticking or sliding, as one patch over its points.
//            Sticking: each point pulls with a tangential spring from where sticking began,
//            and the pair's total is capped at mu_s sum(N) (eq. 16); when the springs alone
//            pull harder than that it slides. (The damper is not counted in that test: it is
//            what keeps a freshly loaded spring from overshooting the cap, and its transient
//            would otherwise break every loaded contact loose; it is clipped at twice the cap.)
//            Sliding: mu_d N against each point's relative motion (eq. 17) until the pair's
//            |v_t| < epsilon (eq. 15's test), when it sticks again. A new pair sticks if it is
//            slower than epsilon. Deciding by speed alone would let the stick spring's own small
//            oscillation (mm/s) throw a loaded contact into sliding; capping per point would let
//            the lightly loaded points of a rocking box slip first and drag the rest along.
//            mu = sqrt(mu1 mu2) per pair.
// Forces act on body b along +n and on body a opposite; torques about each body's frame origin
// (its centroid) are (p - c) x F (the paper's F x r with r from the contact to the centroid).
//
// Stick anchors persist between substeps: a new contact takes the anchor of the previous
// substep's contact of the same pair within kAnchorMatch_m of it.

#include <Eigen/Core>

#include <cstdint>
#include <vector>

#include "physics_node/physics/body.hpp"
#include "physics_node/physics/contact.hpp"

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

  // Computes every contact's force for bodies `bodies` (indexed like the contacts) and adds them
  // to F_G / M_G (force and torque about each body's origin). `contacts` must be sorted by pair.
  // Updates the stick anchors (those of `kept` pairs absent from `contacts` carry over). No
  // allocation once the vectors have grown to the scene's size.
  void apply(const std::vector<ContactPoint>& contacts, const std::vector<ContactBody>& bodies,
             std::vector<Eigen::Vector3d>& F_G, std::vector<Eigen::Vector3d>& M_G,
             std::vector<AppliedContact>& applied, const KeptPairs& kept = {});

  void reset() { anchors_.clear(); }

 private:
  struct Anchor {
    int body_a = -1;
    int body_b = -1;
    Eigen::Vector3d p_A = Eigen::Vector3d::Zero();  // contact point in A's frame (to match)
    Eigen::Vector3d r_A = Eigen::Vector3d::Zero();  // anchor fixed on A, A's frame
    Eigen::Vector3d r_B = Eigen::Vector3d::Zero();  // anchor fixed on B, B's frame
    bool sticking = true;
    bool used = false;
  };

  const Anchor* match_anchor(const ContactPoint& c, const Eigen::Vector3d& p_A);

  // one point of the pair being solved
  struct PointWork {
    double N = 0.0;
    Eigen::Vector3d v_t = Eigen::Vector3d::Zero();
    Eigen::Vector3d f_spring = Eigen::Vector3d::Zero();
    Eigen::Vector3d f_t = Eigen::Vector3d::Zero();  // spring + damper
  };
  std::vector<PointWork> work_;

  double slip_speed_mps_;
  std::vector<Anchor> anchors_;       // previous substep's, sorted by pair
  std::vector<Anchor> next_anchors_;  // being built this substep
};

}  // namespace vcockpit::physics
