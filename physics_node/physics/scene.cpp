#include "physics_node/physics/scene.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace vcockpit::physics {
namespace {

constexpr double kPi = std::numbers::pi;

// Solid cylinder of unit density about its centroid, axis along z.
Eigen::Matrix3d cylinder_inertia(double r_m, double h_m) {
  const double m = kPi * r_m * r_m * h_m;
  const double transverse = m * (3.0 * r_m * r_m + h_m * h_m) / 12.0;
  return Eigen::Vector3d(transverse, transverse, 0.5 * m * r_m * r_m).asDiagonal();
}

Eigen::Matrix3d box_inertia(const Eigen::Vector3d& size_m) {
  const double m = size_m.prod();
  const Eigen::Vector3d s2 = size_m.cwiseProduct(size_m);
  return (m / 12.0 * Eigen::Vector3d(s2.y() + s2.z(), s2.x() + s2.z(), s2.x() + s2.y()))
      .asDiagonal();
}

Eigen::Matrix3d sphere_inertia(double r_m) {
  const double m = 4.0 / 3.0 * kPi * r_m * r_m * r_m;
  return Eigen::Matrix3d::Identity() * (0.4 * m * r_m * r_m);
}

// Cylinder of length h plus two hemispherical caps. A cap's centroid sits 3r/8 from its flat
// face, so about the capsule centre (parallel axis) each cap of mass m_c contributes
// m_c (2/5 r^2 - 9/64 r^2 + (h/2 + 3r/8)^2) = m_c (2/5 r^2 + h^2/4 + 3hr/8) transversally.
Eigen::Matrix3d capsule_inertia(double r_m, double h_m) {
  const double r2 = r_m * r_m;
  const double m_cyl = kPi * r2 * h_m;
  const double m_caps = 4.0 / 3.0 * kPi * r2 * r_m;  // both caps together: one sphere
  const double transverse = m_cyl * (r2 / 4.0 + h_m * h_m / 12.0) +
                            m_caps * (0.4 * r2 + h_m * h_m / 4.0 + 3.0 * h_m * r_m / 8.0);
  const double axial = 0.5 * m_cyl * r2 + 0.4 * m_caps * r2;
  return Eigen::Vector3d(transverse, transverse, axial).asDiagonal();
}

}  // namespace

Shape Shape::box(const Eigen::Vector3d& size_m) {
  Shape s;
  s.kind = ShapeKind::kBox;
  s.box_size_m = size_m;
  return s;
}

Shape Shape::sphere(double radius_m) {
  Shape s;
  s.kind = ShapeKind::kSphere;
  s.radius_m = radius_m;
  return s;
}

Shape Shape::capsule(double radius_m, double length_m) {
  Shape s;
  s.kind = ShapeKind::kCapsule;
  s.radius_m = radius_m;
  s.length_m = length_m;
  return s;
}

Shape Shape::cylinder(double radius_m, double length_m) {
  Shape s;
  s.kind = ShapeKind::kCylinder;
  s.radius_m = radius_m;
  s.length_m = length_m;
  return s;
}

Shape Shape::triangle_mesh(std::shared_ptr<const model::TriangleMesh> mesh,
                           std::shared_ptr<const model::TriangleMesh> hull) {
  Shape s;
  s.kind = ShapeKind::kMesh;
  s.mesh_bounds = model::bounds(*mesh);
  s.mesh = std::move(mesh);
  s.hull = std::move(hull);
  return s;
}

double Shape::volume_m3() const {
  const double r2 = radius_m * radius_m;
  switch (kind) {
    case ShapeKind::kBox:
      return box_size_m.prod();
    case ShapeKind::kSphere:
      return 4.0 / 3.0 * kPi * r2 * radius_m;
    case ShapeKind::kCapsule:
      return kPi * r2 * length_m + 4.0 / 3.0 * kPi * r2 * radius_m;
    case ShapeKind::kCylinder:
      return kPi * r2 * length_m;
    case ShapeKind::kMesh:
      return hull ? model::mass_properties(*hull).volume_m3 : 0.0;
  }
  return 0.0;
}

Eigen::Matrix3d Shape::unit_density_inertia() const {
  switch (kind) {
    case ShapeKind::kBox:
      return box_inertia(box_size_m);
    case ShapeKind::kSphere:
      return sphere_inertia(radius_m);
    case ShapeKind::kCapsule:
      return capsule_inertia(radius_m, length_m);
    case ShapeKind::kCylinder:
      return cylinder_inertia(radius_m, length_m);
    case ShapeKind::kMesh: {
      if (!hull) return Eigen::Matrix3d::Zero();
      // about the hull's centroid, moved to the frame's origin (parallel axes) if it is not there
      const model::MassProperties m = model::mass_properties(*hull);
      const Eigen::Vector3d& c = m.centroid_m;
      return m.unit_density_inertia +
             m.volume_m3 * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
    }
  }
  return Eigen::Matrix3d::Zero();
}

double Shape::bounding_radius_m() const {
  switch (kind) {
    case ShapeKind::kBox:
      return 0.5 * box_size_m.norm();
    case ShapeKind::kSphere:
      return radius_m;
    case ShapeKind::kCapsule:
      return 0.5 * length_m + radius_m;
    case ShapeKind::kCylinder:
      return std::hypot(radius_m, 0.5 * length_m);  // rim corner
    case ShapeKind::kMesh: {
      double r2_m2 = 0.0;
      for (const Eigen::Vector3d& v : (hull ? hull : mesh)->vertices_m) r2_m2 = std::max(r2_m2, v.squaredNorm());
      return std::sqrt(r2_m2);
    }
  }
  return 0.0;
}

Eigen::Vector3d Shape::axis_reach_m() const {
  switch (kind) {
    case ShapeKind::kBox: {
      const Eigen::Vector3d h = 0.5 * box_size_m;
      return {std::hypot(h.y(), h.z()), std::hypot(h.x(), h.z()), std::hypot(h.x(), h.y())};
    }
    case ShapeKind::kSphere:
      return Eigen::Vector3d::Constant(radius_m);
    case ShapeKind::kCapsule: {
      const double across = 0.5 * length_m + radius_m;
      return {across, across, radius_m};
    }
    case ShapeKind::kCylinder: {
      const double across = std::hypot(radius_m, 0.5 * length_m);
      return {across, across, radius_m};
    }
    case ShapeKind::kMesh: {
      Eigen::Vector3d reach_m = Eigen::Vector3d::Zero();
      for (const Eigen::Vector3d& v : (hull ? hull : mesh)->vertices_m)
        reach_m = reach_m.cwiseMax(Eigen::Vector3d(std::hypot(v.y(), v.z()), std::hypot(v.x(), v.z()),
                                                   std::hypot(v.x(), v.y())));
      return reach_m;
    }
  }
  return Eigen::Vector3d::Zero();
}

int Scene::find_control(const std::string& name) const {
  for (std::size_t i = 0; i < controls.size(); ++i)
    if (controls[i].name == name) return static_cast<int>(i);
  return -1;
}

int Scene::find_object(const std::string& name) const {
  for (std::size_t i = 0; i < objects.size(); ++i) {
    if (objects[i].name == name) return static_cast<int>(i);
  }
  return -1;
}

void mass_properties_from_density(const Shape& shape, double density_kgpm3, double& mass_kg,
                                  Eigen::Matrix3d& I_O) {
  mass_kg = density_kgpm3 * shape.volume_m3();
  I_O = density_kgpm3 * shape.unit_density_inertia();
}

}  // namespace vcockpit::physics
