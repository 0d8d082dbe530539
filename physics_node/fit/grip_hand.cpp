#include "physics_node/fit/grip_hand.hpp"

#include <algorithm>
#include <limits>

#include "hand/tracker.hpp"

namespace vcockpit::fit {

GripHand grip_hand_at(const hand::HandModel& model, const hand::GloveSample& sample) {
  hand::GloveSample clamped = sample;
  hand::clamp_to_limits(model, clamped.joints_rad);
  GripHand out;
  out.X_GH = hand::X_GH_from_sample(model, clamped);
  hand::HandLinkPoses poses;
  hand::forward_kinematics(model, clamped.joints_rad, poses);
  for (int l = 1; l < hand::kLinkCount; ++l) {
    const Eigen::Isometry3d X_GL = out.X_GH * poses.X_HL[static_cast<std::size_t>(l)];
    const hand::Capsule& capsule = model.capsules[static_cast<std::size_t>(l)];
    out.a_G[static_cast<std::size_t>(l)] = X_GL.translation();
    out.b_G[static_cast<std::size_t>(l)] = X_GL * Eigen::Vector3d(capsule.length_m, 0.0, 0.0);
    out.radius_m[static_cast<std::size_t>(l)] = capsule.radius_m;
  }
  out.X_GP = out.X_GH * model.X_HP;
  out.palm_size_m = model.palm_size_m;
  return out;
}

double hand_lowest_z_m(const GripHand& hand) {
  double z = std::numeric_limits<double>::infinity();
  for (int l = 1; l < hand::kLinkCount; ++l) {
    const auto k = static_cast<std::size_t>(l);
    z = std::min({z, hand.a_G[k].z() - hand.radius_m[k], hand.b_G[k].z() - hand.radius_m[k]});
  }
  for (int corner = 0; corner < 8; ++corner) {
    const Eigen::Vector3d sign((corner & 1) ? 1.0 : -1.0, (corner & 2) ? 1.0 : -1.0,
                               (corner & 4) ? 1.0 : -1.0);
    z = std::min(z, (hand.X_GP * (0.5 * sign.cwiseProduct(hand.palm_size_m))).z());
  }
  return z;
}

}  // namespace vcockpit::fit
