#include "hand/tracking/xr_hand_joints.hpp"

namespace vcockpit::hand::tracking {
namespace {

constexpr std::array<std::string_view, kXrJointCount> kNames = {
    "palm", "wrist",
    "thumb_metacarpal", "thumb_proximal", "thumb_distal", "thumb_tip",
    "index_metacarpal", "index_proximal", "index_intermediate", "index_distal", "index_tip",
    "middle_metacarpal", "middle_proximal", "middle_intermediate", "middle_distal", "middle_tip",
    "ring_metacarpal", "ring_proximal", "ring_intermediate", "ring_distal", "ring_tip",
    "little_metacarpal", "little_proximal", "little_intermediate", "little_distal", "little_tip"};

}  // namespace

std::string_view xr_joint_name(XrJoint joint) { return kNames[static_cast<std::size_t>(joint)]; }

int xr_joint_index(std::string_view name) {
  for (int j = 0; j < kXrJointCount; ++j)
    if (kNames[static_cast<std::size_t>(j)] == name) return j;
  return -1;
}

XrFingerChain xr_finger_chain(int finger) {
  XrFingerChain chain;
  if (finger == 0) {
    chain.joints = {XrJoint::kThumbMetacarpal, XrJoint::kThumbProximal, XrJoint::kThumbDistal,
                    XrJoint::kThumbTip, XrJoint::kThumbTip};
    chain.count = 4;
    return chain;
  }
  const int first = static_cast<int>(XrJoint::kIndexMetacarpal) + 5 * (finger - 1);
  for (int k = 0; k < 5; ++k) chain.joints[static_cast<std::size_t>(k)] = static_cast<XrJoint>(first + k);
  chain.count = 5;
  return chain;
}

}  // namespace vcockpit::hand::tracking
