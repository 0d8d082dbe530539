#pragma once
// Conversions between the IDL's plain pose types and Eigen.

#include <Eigen/Geometry>

#include "cockpit.h"

namespace vcockpit {

inline Eigen::Vector3d to_eigen(const cockpit::Vec3& v) { return {v.x(), v.y(), v.z()}; }

inline Eigen::Quaterniond to_eigen(const cockpit::Quat& q) {
  return Eigen::Quaterniond(q.w(), q.x(), q.y(), q.z());
}

inline Eigen::Isometry3d to_eigen(const cockpit::Pose& pose) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = to_eigen(pose.orientation()).normalized().toRotationMatrix();
  X.translation() = to_eigen(pose.position_m());
  return X;
}

inline cockpit::Vec3 to_idl(const Eigen::Vector3d& v) {
  cockpit::Vec3 out;
  out.x(v.x());
  out.y(v.y());
  out.z(v.z());
  return out;
}

inline cockpit::Quat to_idl(const Eigen::Quaterniond& q) {
  cockpit::Quat out;
  out.w(q.w());
  out.x(q.x());
  out.y(q.y());
  out.z(q.z());
  return out;
}

inline cockpit::Pose to_idl(const Eigen::Isometry3d& X) {
  cockpit::Pose out;
  out.position_m(to_idl(Eigen::Vector3d(X.translation())));
  out.orientation(to_idl(Eigen::Quaterniond(X.rotation())));
  return out;
}

}  // namespace vcockpit
