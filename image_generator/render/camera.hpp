#pragma once
// Eye poses and the OpenGL matrices of an off-axis stereo camera, and the same projection on
// the CPU (project_to_pixel) so callers and tests know where a world point lands in an image.
//
// Frames: world G and head H are both x forward, y left, z up. Eye E = H shifted by +-ipd/2
// along y (left eye +y), same axes. OpenGL eye space is x right, y up, looking down -z.

#include <Eigen/Geometry>

#include "image_generator/render/hmd_config.hpp"

namespace vcockpit::render {

// X_GE = X_GHead * Translation(0, +-ipd/2, 0), + for the left eye.
Eigen::Isometry3d eye_pose(const HmdConfig& config, Eye eye, const Eigen::Isometry3d& X_GHead);

// glFrustum with l, r, b, t = near * tan(left, right, down, up): an asymmetric frustum whose
// image plane stays perpendicular to the eye's x axis (no toe-in).
Eigen::Matrix4f off_axis_projection(const EyeFov& fov, double near_m, double far_m);

// World -> OpenGL eye space for an eye at X_GE: eye +x (forward) -> -z, +y (left) -> -x,
// +z (up) -> +y.
Eigen::Matrix4f view_matrix(const Eigen::Isometry3d& X_GE);

// Where p_G lands in one eye's image: pixel = (column, row), continuous, row 0 at the top, the
// centre of pixel (c, r) at (c + 0.5, r + 0.5). False (pixel untouched) if the point is nearer
// than near_m along the eye's optical axis (behind the eye or clipped) or outside the image.
bool project_to_pixel(const HmdConfig& config, Eye eye, const Eigen::Isometry3d& X_GHead,
                      const Eigen::Vector3d& p_G, Eigen::Vector2d& pixel);

}  // namespace vcockpit::render
