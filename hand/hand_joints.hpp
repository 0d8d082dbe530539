#pragma once
// The 22 glove channels (CyberGlove order) and the 16 hand links, with stable ids and names.
// Ids match the IDL enums cockpit::JointIndex and cockpit::LinkIndex.

#include <array>
#include <cstdint>
#include <string_view>

namespace vcockpit::hand {

constexpr int kJointCount = 22;
constexpr int kLinkCount = 16;
constexpr int kFingerCount = 5;

enum class Joint : uint8_t {
  kThumbRotation, kThumbMcp, kThumbIp, kThumbAbduction,
  kIndexMcp, kIndexPip, kIndexDip,
  kMiddleMcp, kMiddlePip, kMiddleDip, kMiddleIndexAbduction,
  kRingMcp, kRingPip, kRingDip, kRingMiddleAbduction,
  kLittleMcp, kLittlePip, kLittleDip, kLittleRingAbduction,
  kPalmArch, kWristPitch, kWristYaw
};

enum class Finger : uint8_t { kThumb, kIndex, kMiddle, kRing, kLittle };

// Palm, then proximal/middle/distal phalanx of thumb, index, middle, ring, little.
enum class Link : uint8_t {
  kPalm,
  kThumbProximal, kThumbMiddle, kThumbDistal,
  kIndexProximal, kIndexMiddle, kIndexDistal,
  kMiddleProximal, kMiddleMiddle, kMiddleDistal,
  kRingProximal, kRingMiddle, kRingDistal,
  kLittleProximal, kLittleMiddle, kLittleDistal
};

// snake_case names as used in glove log headers and hand.yaml: "thumb_rotation", ..., "wrist_yaw".
std::string_view joint_name(Joint joint);
// -1 when the name is not a joint.
int joint_index(std::string_view name);

// "palm", "thumb_proximal", ..., "little_distal".
std::string_view link_name(Link link);
std::string_view finger_name(Finger finger);

// The finger a link belongs to; palm has none (returns false).
bool finger_of(Link link, Finger& finger);
// Phalanx links of a finger, proximal to distal.
std::array<Link, 3> finger_links(Finger finger);

using JointAngles = std::array<double, kJointCount>;  // rad, Joint order

}  // namespace vcockpit::hand
