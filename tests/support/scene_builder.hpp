#pragma once
// Small scenes in code for scenario tests: boxes and spheres with given materials.

#include <string>

#include "common/pose.hpp"
#include "physics_node/physics/scene.hpp"

namespace vcockpit::test {

inline physics::Material material(double k_Npm, double mu_s = 0.6, double mu_d = 0.4,
                                  double zeta = 0.7) {
  physics::Material m;
  m.stiffness_Npm = k_Npm;
  m.mu_s = mu_s;
  m.mu_d = mu_d;
  m.damping_ratio = zeta;
  return m;
}

inline physics::ObjectSpec static_box(const std::string& name, const Eigen::Vector3d& size_m,
                                      const Eigen::Isometry3d& X_GO, const physics::Material& m) {
  physics::ObjectSpec o;
  o.name = name;
  o.dynamic = false;
  o.shape = physics::Shape::box(size_m);
  o.X_GO = X_GO;
  o.material = m;
  return o;
}

inline physics::ObjectSpec dynamic_object(const std::string& name, const physics::Shape& shape,
                                          double mass_kg, const Eigen::Isometry3d& X_GO,
                                          const physics::Material& m) {
  physics::ObjectSpec o;
  o.name = name;
  o.dynamic = true;
  o.shape = shape;
  o.mass_kg = mass_kg;
  o.I_O = shape.unit_density_inertia() * (mass_kg / shape.volume_m3());
  o.X_GO = X_GO;
  o.material = m;
  return o;
}

inline Eigen::Isometry3d at(double x, double y, double z, double roll_deg = 0, double pitch_deg = 0,
                            double yaw_deg = 0) {
  return pose_from_position_rpy_deg({x, y, z}, {roll_deg, pitch_deg, yaw_deg});
}

// A 4 m x 4 m floor box whose top is at z = 0.
inline physics::ObjectSpec floor_box(const physics::Material& m) {
  return static_box("floor", {4.0, 4.0, 0.2}, at(0, 0, -0.1), m);
}

}  // namespace vcockpit::test
