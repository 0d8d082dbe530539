#pragma once
// What holds a placed object up until the hand takes it (grip_fit's scene): a small static
// pedestal directly below it and a table under the pedestal, laid out from the object's pose and
// the hand at the chosen moment. Pure geometry; the YAML is written by
// physics_node/config/grip_scene_yaml.
//
// - Pedestal: its top at the object's lowest point (touching it), turned (yaw) along the object's
//   longest horizontal axis (a lying bar's axis), its footprint footprint_share (60 %) of the
//   object's extent along that axis and across it, so the hand closing round the object does not
//   hit it: while the hand at the moment comes closer to it than pedestal_clearance_m (1 mm) the
//   share narrows by 10 % down to 20 %. Then (once it clears the hand) each of its four sides is
//   pushed out in turn, 2 mm at a time, up to extend_m (6 cm) beyond the object's footprint, while
//   the hand at the moment still clears it by 1 mm: a pedestal as wide as the grip leaves room
//   for. A recorded wrist drifts and turns while the fist is closed (the Leap grab's carries what
//   it holds 3-4 cm sideways and 2-5 cm down); on a wide top the held object is carried along it,
//   not off it and down, and the hand lets it go onto it (grip_choice.hpp replays that).
// - Table (0.6 x 0.6 x 0.03 m): under the pedestal, its top hand_clearance_m (1 cm) below the
//   hand's lowest point at the moment and at least min_pedestal_m (2 cm) below the object's lowest
//   point. If that leaves no room above the floor (top z = 0) there is no table and the pedestal
//   stands on the floor.

#include <Eigen/Geometry>

#include <optional>

#include "physics_node/fit/grip_hand.hpp"
#include "physics_node/physics/scene.hpp"

namespace vcockpit::fit {

struct SupportBox {
  Eigen::Vector3d size_m = Eigen::Vector3d::Zero();  // full extents
  Eigen::Vector3d p_G = Eigen::Vector3d::Zero();     // centre
  double yaw_rad = 0.0;                              // about world z
};

struct LayoutRule {
  double footprint_share = 0.6;
  double footprint_step = 0.1;
  double min_footprint_share = 0.2;
  // then each of its four sides pushed out, extend_step_m at a time, up to extend_m beyond the
  // object's footprint, while the hand at the moment still clears it (0: not extended)
  double extend_m = 0.06;
  double extend_step_m = 0.002;
  double pedestal_clearance_m = 1e-3;
  double min_pedestal_m = 0.02;
  double hand_clearance_m = 0.01;
  Eigen::Vector3d table_size_m{0.6, 0.6, 0.03};
};

struct GripSceneLayout {
  SupportBox pedestal;
  std::optional<SupportBox> table;
  double object_lowest_z_m = 0.0;
  double footprint_share = 0.0;  // the share used (before the sides were pushed out)
  // the least signed distance of the hand's links from the pedestal at the moment (< 0: a link
  // is in it) and that link
  double pedestal_clearance_m = 0.0;
  hand::Link pedestal_nearest_link = hand::Link::kPalm;
};

// Throws std::invalid_argument when the object's lowest point is not above the floor (z = 0).
GripSceneLayout lay_out_supports(const GripHand& hand, const physics::Shape& shape,
                                 const Eigen::Isometry3d& X_GO, const LayoutRule& rule = {});

Eigen::Isometry3d support_pose(const SupportBox& box);

}  // namespace vcockpit::fit
