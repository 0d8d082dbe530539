#include "hand/hand_joints.hpp"

namespace vcockpit::hand {
namespace {

constexpr std::array<std::string_view, kJointCount> kJointNames = {
    "thumb_rotation", "thumb_mcp", "thumb_ip", "thumb_abduction",
    "index_mcp", "index_pip", "index_dip",
    "middle_mcp", "middle_pip", "middle_dip", "middle_index_abduction",
    "ring_mcp", "ring_pip", "ring_dip", "ring_middle_abduction",
    "little_mcp", "little_pip", "little_dip", "little_ring_abduction",
    "palm_arch", "wrist_pitch", "wrist_yaw"};

constexpr std::array<std::string_view, kLinkCount> kLinkNames = {
    "palm",
    "thumb_proximal", "thumb_middle", "thumb_distal",
    "index_proximal", "index_middle", "index_distal",
    "middle_proximal", "middle_middle", "middle_distal",
    "ring_proximal", "ring_middle", "ring_distal",
    "little_proximal", "little_middle", "little_distal"};

constexpr std::array<std::string_view, kFingerCount> kFingerNames = {"thumb", "index", "middle",
                                                                     "ring", "little"};

}  // namespace

std::string_view joint_name(Joint joint) { return kJointNames[static_cast<int>(joint)]; }

int joint_index(std::string_view name) {
  for (int i = 0; i < kJointCount; ++i) {
    if (kJointNames[i] == name) return i;
  }
  return -1;
}

std::string_view link_name(Link link) { return kLinkNames[static_cast<int>(link)]; }

std::string_view finger_name(Finger finger) { return kFingerNames[static_cast<int>(finger)]; }

bool finger_of(Link link, Finger& finger) {
  if (link == Link::kPalm) return false;
  finger = static_cast<Finger>((static_cast<int>(link) - 1) / 3);
  return true;
}

std::array<Link, 3> finger_links(Finger finger) {
  const int first = 1 + 3 * static_cast<int>(finger);
  return {static_cast<Link>(first), static_cast<Link>(first + 1), static_cast<Link>(first + 2)};
}

}  // namespace vcockpit::hand
