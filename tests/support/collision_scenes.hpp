#pragma once
// Scenes for the collision tests (collision_test, mesh_collision_test): objects at poses, the 1 m
// box floor whose top face is z = 0, one narrowphase pass, and a vector comparison.

#include <gtest/gtest.h>

#include <array>
#include <string>
#include <vector>

#include "physics_node/physics/collision.hpp"
#include "physics_node/physics/scene.hpp"

namespace vcockpit::test {

inline Eigen::Isometry3d pose(double x_m, double y_m, double z_m,
                              const Eigen::Matrix3d& R = Eigen::Matrix3d::Identity()) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = R;
  X.translation() = Eigen::Vector3d(x_m, y_m, z_m);
  return X;
}

inline physics::ObjectSpec object(const std::string& name, bool dynamic,
                                  const physics::Shape& shape, const Eigen::Isometry3d& X_GO) {
  physics::ObjectSpec spec;
  spec.name = name;
  spec.dynamic = dynamic;
  spec.shape = shape;
  spec.X_GO = X_GO;
  spec.mass_kg = dynamic ? 0.1 : 0.0;
  return spec;
}

// 1 m x 1 m, 0.1 m thick, top face at z = 0.
inline physics::ObjectSpec floor_box(bool dynamic = false) {
  return object("floor", dynamic, physics::Shape::box({1.0, 1.0, 0.1}), pose(0, 0, -0.05));
}

inline std::vector<Eigen::Isometry3d> initial_poses(const physics::Scene& scene) {
  std::vector<Eigen::Isometry3d> X_GO;
  for (const physics::ObjectSpec& spec : scene.objects)
    X_GO.push_back(spec.X_GO);
  return X_GO;
}

inline std::vector<physics::ContactPoint> step(
    physics::CollisionWorld& world, const std::vector<Eigen::Isometry3d>& X_GO,
    const std::array<Eigen::Isometry3d, physics::kLinkCount>* X_GL = nullptr) {
  std::vector<physics::ContactPoint> contacts;
  world.set_poses(X_GO, X_GL);
  world.find_candidate_pairs();
  world.compute_contacts(contacts);
  return contacts;
}

inline void expect_vec_near(const Eigen::Vector3d& actual, const Eigen::Vector3d& expected,
                            double tol, const std::string& what) {
  EXPECT_LE((actual - expected).norm(), tol)
      << what << ": got " << actual.transpose() << ", expected " << expected.transpose();
}

}  // namespace vcockpit::test
