#pragma once
// The tracked hand of one glove sample as collision geometry in the world: what an object placed
// in the recorded grip has to fit (grip_fit.hpp). Joints clamped to the hand's ranges, then
// forward kinematics at the sample's wrist pose X_GH (hand::X_GH_from_sample, eqs. 26-27), as the
// simulator's tracked hand.

#include <Eigen/Geometry>

#include <array>

#include "hand/glove_sample.hpp"
#include "hand/hand_model.hpp"

namespace vcockpit::fit {

struct GripHand {
  Eigen::Isometry3d X_GH = Eigen::Isometry3d::Identity();
  // per link (hand::Link order); the palm's entries are unused
  std::array<Eigen::Vector3d, hand::kLinkCount> a_G{};  // a phalanx's segment: proximal end
  std::array<Eigen::Vector3d, hand::kLinkCount> b_G{};  // ... distal end
  std::array<double, hand::kLinkCount> radius_m{};
  Eigen::Isometry3d X_GP = Eigen::Isometry3d::Identity();  // palm box centre
  Eigen::Vector3d palm_size_m = Eigen::Vector3d::Zero();   // palm box full extents
};

GripHand grip_hand_at(const hand::HandModel& model, const hand::GloveSample& sample);

// The lowest point of the hand's surfaces (m, world z): capsule ends less their radius, palm
// box corners.
double hand_lowest_z_m(const GripHand& hand);

}  // namespace vcockpit::fit
