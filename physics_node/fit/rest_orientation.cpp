#include "physics_node/fit/rest_orientation.hpp"

#include <cmath>

namespace vcockpit::fit {
namespace {

Eigen::Matrix3d about_x(double angle_rad) {
  return Eigen::AngleAxisd(angle_rad, Eigen::Vector3d::UnitX()).toRotationMatrix();
}
Eigen::Matrix3d about_y(double angle_rad) {
  return Eigen::AngleAxisd(angle_rad, Eigen::Vector3d::UnitY()).toRotationMatrix();
}

}  // namespace

std::vector<RestOrientation> rest_orientations(const physics::Shape& shape) {
  const Eigen::Matrix3d lying = about_y(0.5 * M_PI);  // the object's z (its axis) along world x
  switch (shape.kind) {
    case physics::ShapeKind::kSphere:
      return {{Eigen::Matrix3d::Identity(), false, "any"}};
    case physics::ShapeKind::kCylinder:
      return {{lying, true, "lying"}, {Eigen::Matrix3d::Identity(), false, "standing"}};
    case physics::ShapeKind::kCapsule:
      return {{lying, true, "lying"}};
    case physics::ShapeKind::kBox:
      // z up, y up (Rx(90) y = z), x up (Ry(-90) x = z)
      return {{Eigen::Matrix3d::Identity(), true, "on its z faces"},
              {about_x(0.5 * M_PI), true, "on its y faces"},
              {about_y(-0.5 * M_PI), true, "on its x faces"}};
    case physics::ShapeKind::kMesh:  // grip_fit places the primitives its command line names
      break;
  }
  return {};
}

Eigen::Matrix3d rest_rotation(const RestOrientation& rest, double yaw_rad) {
  return Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix() * rest.R_rest;
}

std::vector<double> start_yaws_rad(const Eigen::Matrix3d& R_GH, const RestOrientation& rest,
                                   int count) {
  // the direction across the fingers, on the floor
  Eigen::Vector2d across(R_GH(0, 1), R_GH(1, 1));
  if (across.norm() < 0.3) across = Eigen::Vector2d(-R_GH(1, 0), R_GH(0, 0));
  const double across_yaw = across.norm() > 1e-9 ? std::atan2(across.y(), across.x()) : 0.0;
  // the yaw that turns the object's first horizontal axis at yaw 0 (z, x, y in that order: a
  // lying bar's axis) onto it
  Eigen::Vector3d first = Eigen::Vector3d::Zero();
  for (int c : {2, 0, 1}) {
    if (rest.R_rest.col(c).head<2>().norm() > 0.5) {
      first = rest.R_rest.col(c);
      break;
    }
  }
  const double yaw0 = across_yaw - std::atan2(first.y(), first.x());
  if (!rest.yaw_free) return {yaw0};
  std::vector<double> out;
  for (int k = 0; k < count; ++k)
    out.push_back(yaw0 + k * M_PI / count);
  return out;
}

}  // namespace vcockpit::fit
