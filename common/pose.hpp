#pragma once
// Eigen pose helpers. Poses are Eigen::Isometry3d named in monogram style: X_AB is the pose of
// frame B in frame A, so X_AC = X_AB * X_BC and p_A = X_AB * p_B.

#include <Eigen/Geometry>

#include <array>
#include <string>

namespace vcockpit {

// R = Rz(yaw) * Ry(pitch) * Rx(roll): extrinsic roll-pitch-yaw about fixed x, y, z (radians).
Eigen::Matrix3d rotation_from_rpy(double roll, double pitch, double yaw);

// Intrinsic Euler angles about the axes named by `axes` (three of 'x','y','z', e.g. "zyx"):
// R = R_axes[0](a) * R_axes[1](b) * R_axes[2](c). Throws std::invalid_argument on a bad string.
Eigen::Matrix3d rotation_from_euler(const std::string& axes, double a, double b, double c);

// True if `axes` is a valid Euler convention for rotation_from_euler (adjacent axes differ).
bool is_valid_euler_axes(const std::string& axes);

Eigen::Isometry3d make_pose(const Eigen::Vector3d& p, const Eigen::Matrix3d& R);
Eigen::Isometry3d make_pose(const Eigen::Vector3d& p, const Eigen::Quaterniond& q);

// Pose from a position and extrinsic roll-pitch-yaw in degrees (the scene YAML convention).
Eigen::Isometry3d pose_from_position_rpy_deg(const std::array<double, 3>& p_m,
                                             const std::array<double, 3>& rpy_deg);

constexpr double deg_to_rad(double deg) { return deg * 0.017453292519943295; }
constexpr double rad_to_deg(double rad) { return rad * 57.29577951308232; }

}  // namespace vcockpit
