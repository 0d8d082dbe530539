#include "common/pose.hpp"

#include <stdexcept>

namespace vcockpit {
namespace {

Eigen::Vector3d axis_of(char c) {
  switch (c) {
    case 'x': return Eigen::Vector3d::UnitX();
    case 'y': return Eigen::Vector3d::UnitY();
    case 'z': return Eigen::Vector3d::UnitZ();
    default: throw std::invalid_argument(std::string("bad Euler axis '") + c + "'");
  }
}

}  // namespace

Eigen::Matrix3d rotation_from_rpy(double roll, double pitch, double yaw) {
  return (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

bool is_valid_euler_axes(const std::string& axes) {
  if (axes.size() != 3) return false;
  for (char c : axes) {
    if (c != 'x' && c != 'y' && c != 'z') return false;
  }
  return axes[0] != axes[1] && axes[1] != axes[2];
}

Eigen::Matrix3d rotation_from_euler(const std::string& axes, double a, double b, double c) {
  if (!is_valid_euler_axes(axes)) {
    throw std::invalid_argument("bad Euler convention '" + axes +
                                "' (three of x, y, z with no axis repeated next to itself)");
  }
  return (Eigen::AngleAxisd(a, axis_of(axes[0])) * Eigen::AngleAxisd(b, axis_of(axes[1])) *
          Eigen::AngleAxisd(c, axis_of(axes[2])))
      .toRotationMatrix();
}

Eigen::Isometry3d make_pose(const Eigen::Vector3d& p, const Eigen::Matrix3d& R) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = R;
  X.translation() = p;
  return X;
}

Eigen::Isometry3d make_pose(const Eigen::Vector3d& p, const Eigen::Quaterniond& q) {
  return make_pose(p, q.normalized().toRotationMatrix());
}

Eigen::Isometry3d pose_from_position_rpy_deg(const std::array<double, 3>& p_m,
                                             const std::array<double, 3>& rpy_deg) {
  return make_pose(Eigen::Vector3d(p_m[0], p_m[1], p_m[2]),
                   rotation_from_rpy(deg_to_rad(rpy_deg[0]), deg_to_rad(rpy_deg[1]),
                                     deg_to_rad(rpy_deg[2])));
}

}  // namespace vcockpit
