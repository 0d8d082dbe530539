#include "glove_driver/openxr/xr_joint_locations.hpp"

#include <cmath>

namespace vcockpit::glove::xr {

static_assert(XR_HAND_JOINT_COUNT_EXT == hand::tracking::kXrJointCount);
static_assert(XR_HAND_JOINT_WRIST_EXT == static_cast<int>(hand::tracking::XrJoint::kWrist));
static_assert(XR_HAND_JOINT_INDEX_PROXIMAL_EXT == static_cast<int>(hand::tracking::XrJoint::kIndexProximal));
static_assert(XR_HAND_JOINT_LITTLE_TIP_EXT == static_cast<int>(hand::tracking::XrJoint::kLittleTip));

hand::tracking::JointsFrame joints_frame(const XrHandJointLocationEXT* locations, bool left_hand,
                                         int64_t t_ns) {
  constexpr XrSpaceLocationFlags kPosition =
      XR_SPACE_LOCATION_POSITION_VALID_BIT | XR_SPACE_LOCATION_POSITION_TRACKED_BIT;
  constexpr XrSpaceLocationFlags kOrientation =
      XR_SPACE_LOCATION_ORIENTATION_VALID_BIT | XR_SPACE_LOCATION_ORIENTATION_TRACKED_BIT;
  hand::tracking::JointsFrame frame;
  frame.t_ns = t_ns;
  frame.left_hand = left_hand;
  for (int j = 0; j < XR_HAND_JOINT_COUNT_EXT; ++j) {
    const XrHandJointLocationEXT& in = locations[j];
    hand::tracking::TrackedJoint& out = frame.joints[static_cast<std::size_t>(j)];
    const Eigen::Vector3d p(in.pose.position.x, in.pose.position.y, in.pose.position.z);
    out.valid = (in.locationFlags & kPosition) == kPosition && p.allFinite();
    if (!out.valid) continue;
    out.p_m = p;
    const Eigen::Quaterniond q(in.pose.orientation.w, in.pose.orientation.x, in.pose.orientation.y,
                               in.pose.orientation.z);
    out.has_orientation = (in.locationFlags & kOrientation) == kOrientation && q.coeffs().allFinite() &&
                          std::abs(q.norm() - 1.0) < 1e-2;
    if (out.has_orientation) out.q = q.normalized();
    out.has_radius = std::isfinite(in.radius) && in.radius > 0.0f;
    if (out.has_radius) out.radius_m = in.radius;
  }
  return frame;
}

}  // namespace vcockpit::glove::xr
