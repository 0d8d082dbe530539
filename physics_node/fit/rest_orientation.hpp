#pragma once
// The orientations a placed object may take: those in which it holds still on its pedestal
// until the hand takes it (grip_fit's scene stands it on a flat top touching its lowest point).
// A bar tilted in the grip would rest on one rim and topple before the fingers close.
//   sphere    any (one orientation, no yaw)
//   cylinder  lying (axis horizontal, any yaw) or standing on a cap
//   capsule   lying (standing on a round cap it rolls off)
//   box       on any of its three pairs of faces, any yaw
// Yaw turns about the world's vertical z; a lying bar's axis is then (cos yaw, sin yaw, 0), so the
// scene writes it as rpy_deg (0, 90, yaw).

#include <Eigen/Geometry>

#include <vector>

#include "physics_node/physics/scene.hpp"

namespace vcockpit::fit {

struct RestOrientation {
  Eigen::Matrix3d R_rest = Eigen::Matrix3d::Identity();  // at yaw 0, in the world
  bool yaw_free =
      false;  // false: turning about the vertical changes nothing (a sphere, a standing cylinder)
  // for the report: "any" (a sphere), "lying", "standing" (a cylinder on a cap), "on its z faces"
  // (a box; x, y alike)
  const char* name = "any";
};

std::vector<RestOrientation> rest_orientations(const physics::Shape& shape);

// R_GO = Rz(yaw) R_rest
Eigen::Matrix3d rest_rotation(const RestOrientation& rest, double yaw_rad);

// Yaws to start a search from: first the one that lays the object's first horizontal axis (of z,
// x, y: a lying bar's axis) across the fingers, along the hand's y axis projected on the
// floor (when the hand is on its edge, y_H near vertical: across the fingers' direction x_H
// projected instead), then every 180/count deg from it. One yaw (that) when the yaw is not free.
std::vector<double> start_yaws_rad(const Eigen::Matrix3d& R_GH, const RestOrientation& rest,
                                   int count);

}  // namespace vcockpit::fit
