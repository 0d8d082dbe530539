#pragma once
// The hand joints of OpenXR's XR_EXT_hand_tracking: 26 per hand, palm and wrist, then the thumb's
// 4 and each finger's 5, base to tip. A joint is at the proximal end of the bone it names (the
// index's "proximal" joint is its knuckle, the MCP), and "tip" is the fingertip. Positions are in
// metres; a joint pose's -Z points toward the fingertips and +Y out of the back of the hand.

#include <array>
#include <cstdint>
#include <string_view>

namespace vcockpit::hand::tracking {

enum class XrJoint : uint8_t {
  kPalm, kWrist,
  kThumbMetacarpal, kThumbProximal, kThumbDistal, kThumbTip,
  kIndexMetacarpal, kIndexProximal, kIndexIntermediate, kIndexDistal, kIndexTip,
  kMiddleMetacarpal, kMiddleProximal, kMiddleIntermediate, kMiddleDistal, kMiddleTip,
  kRingMetacarpal, kRingProximal, kRingIntermediate, kRingDistal, kRingTip,
  kLittleMetacarpal, kLittleProximal, kLittleIntermediate, kLittleDistal, kLittleTip,
};
inline constexpr int kXrJointCount = 26;

// snake_case names, as in the joints log's columns: "palm", "wrist", "thumb_metacarpal", ...,
// "little_tip".
std::string_view xr_joint_name(XrJoint joint);
// -1 when the name is not a joint.
int xr_joint_index(std::string_view name);

// A finger's joints from base to tip (hand::Finger order: thumb, index, middle, ring, little):
// the thumb's metacarpal, proximal, distal and tip (its `count` 4), a finger's metacarpal,
// proximal, intermediate, distal and tip (5).
struct XrFingerChain {
  std::array<XrJoint, 5> joints{};
  int count = 0;
};
XrFingerChain xr_finger_chain(int finger);

}  // namespace vcockpit::hand::tracking
