#include "image_generator/render/camera.hpp"

#include <cmath>

namespace vcockpit::render {
namespace {

// Rows: OpenGL eye axes (x right, y up, z back) expressed in the eye frame (x fwd, y left, z up).
Eigen::Matrix3d R_glE() {
  Eigen::Matrix3d R;
  R << 0, -1, 0,  //
      0, 0, 1,    //
      -1, 0, 0;
  return R;
}

}  // namespace

Eigen::Isometry3d eye_pose(const HmdConfig& config, Eye eye, const Eigen::Isometry3d& X_GHead) {
  const double y_m = (eye == Eye::kLeft ? 0.5 : -0.5) * config.ipd_m;
  return X_GHead * Eigen::Translation3d(0.0, y_m, 0.0);
}

Eigen::Matrix4f off_axis_projection(const EyeFov& fov, double near_m, double far_m) {
  const double n = near_m, f = far_m;
  const double l = n * std::tan(fov.left_rad), r = n * std::tan(fov.right_rad);
  const double b = n * std::tan(fov.down_rad), t = n * std::tan(fov.up_rad);
  Eigen::Matrix4d P = Eigen::Matrix4d::Zero();
  P(0, 0) = 2.0 * n / (r - l);
  P(0, 2) = (r + l) / (r - l);
  P(1, 1) = 2.0 * n / (t - b);
  P(1, 2) = (t + b) / (t - b);
  P(2, 2) = -(f + n) / (f - n);
  P(2, 3) = -2.0 * f * n / (f - n);
  P(3, 2) = -1.0;
  return P.cast<float>();
}

Eigen::Matrix4f view_matrix(const Eigen::Isometry3d& X_GE) {
  const Eigen::Isometry3d X_EG = X_GE.inverse();
  Eigen::Matrix4d V = Eigen::Matrix4d::Identity();
  V.topLeftCorner<3, 3>() = R_glE() * X_EG.linear();
  V.topRightCorner<3, 1>() = R_glE() * X_EG.translation();
  return V.cast<float>();
}

bool project_to_pixel(const HmdConfig& config, Eye eye, const Eigen::Isometry3d& X_GHead,
                      const Eigen::Vector3d& p_G, Eigen::Vector2d& pixel) {
  const Eigen::Vector3d p_E = eye_pose(config, eye, X_GHead).inverse() * p_G;
  if (!(p_E.x() >= config.near_m)) return false;
  // tangents of the angles right of and above the optical axis
  const double tan_right = -p_E.y() / p_E.x(), tan_up = p_E.z() / p_E.x();
  const EyeFov& fov = config.eye_fov(eye);
  const double tl = std::tan(fov.left_rad), tr = std::tan(fov.right_rad);
  const double tu = std::tan(fov.up_rad), td = std::tan(fov.down_rad);
  const double column = (tan_right - tl) / (tr - tl) * config.width_px;
  const double row = (tu - tan_up) / (tu - td) * config.height_px;
  if (column < 0.0 || column >= config.width_px || row < 0.0 || row >= config.height_px) {
    return false;
  }
  pixel = {column, row};
  return true;
}

}  // namespace vcockpit::render
