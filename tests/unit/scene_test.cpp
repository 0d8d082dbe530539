// Shape volumes, inertias and bounding radii against closed forms, and the capsule against an
// independent numerical integration over z slices.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <numbers>

#include "physics_node/physics/scene.hpp"

namespace vcockpit::physics {
namespace {

constexpr double kPi = std::numbers::pi;

void expect_diagonal(const Eigen::Matrix3d& I, const Eigen::Vector3d& expected, double rel_tol) {
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(I(i, i), expected[i], rel_tol * expected.maxCoeff())
        << "I(" << i << "," << i << ")";
    for (int j = 0; j < 3; ++j) {
      if (i == j) continue;
      EXPECT_EQ(I(i, j), 0.0) << "I(" << i << "," << j << ")";
    }
  }
}

// Principal moments of any rigid body: positive and each at most the sum of the other two.
void expect_physical(const Eigen::Matrix3d& I) {
  const Eigen::Vector3d d = I.diagonal();
  for (int i = 0; i < 3; ++i) {
    EXPECT_GT(d[i], 0.0);
    EXPECT_LE(d[i], d[(i + 1) % 3] + d[(i + 2) % 3] + 1e-18);
  }
}

TEST(SceneShapes, FactoriesSetKindAndDimensions) {
  const Shape box = Shape::box({0.1, 0.2, 0.3});
  EXPECT_EQ(box.kind, ShapeKind::kBox);
  EXPECT_EQ(box.box_size_m, Eigen::Vector3d(0.1, 0.2, 0.3));
  const Shape sphere = Shape::sphere(0.05);
  EXPECT_EQ(sphere.kind, ShapeKind::kSphere);
  EXPECT_EQ(sphere.radius_m, 0.05);
  const Shape capsule = Shape::capsule(0.01, 0.08);
  EXPECT_EQ(capsule.kind, ShapeKind::kCapsule);
  EXPECT_EQ(capsule.radius_m, 0.01);
  EXPECT_EQ(capsule.length_m, 0.08);
  const Shape cylinder = Shape::cylinder(0.02, 0.18);
  EXPECT_EQ(cylinder.kind, ShapeKind::kCylinder);
  EXPECT_EQ(cylinder.radius_m, 0.02);
  EXPECT_EQ(cylinder.length_m, 0.18);
}

TEST(SceneShapes, BoxVolumeAndInertia) {
  const double a_m = 0.2, b_m = 0.3, c_m = 0.5;
  const Shape box = Shape::box({a_m, b_m, c_m});
  const double m = a_m * b_m * c_m;  // unit density
  EXPECT_DOUBLE_EQ(box.volume_m3(), m);
  expect_diagonal(
      box.unit_density_inertia(),
      m / 12.0 *
          Eigen::Vector3d(b_m * b_m + c_m * c_m, a_m * a_m + c_m * c_m, a_m * a_m + b_m * b_m),
      1e-14);
  expect_physical(box.unit_density_inertia());
}

TEST(SceneShapes, SphereVolumeAndInertia) {
  const double r_m = 0.03;
  const Shape sphere = Shape::sphere(r_m);
  const double m = 4.0 / 3.0 * kPi * r_m * r_m * r_m;
  EXPECT_DOUBLE_EQ(sphere.volume_m3(), m);
  const double I = 2.0 / 5.0 * m * r_m * r_m;
  expect_diagonal(sphere.unit_density_inertia(), Eigen::Vector3d(I, I, I), 1e-14);
}

TEST(SceneShapes, SolidCylinderVolumeAndInertia) {
  const double r_m = 0.035, h_m = 0.10;
  const Shape cylinder = Shape::cylinder(r_m, h_m);
  const double m = kPi * r_m * r_m * h_m;
  EXPECT_DOUBLE_EQ(cylinder.volume_m3(), m);
  const double transverse = m * (3.0 * r_m * r_m + h_m * h_m) / 12.0;
  expect_diagonal(cylinder.unit_density_inertia(),
                  Eigen::Vector3d(transverse, transverse, 0.5 * m * r_m * r_m), 1e-14);
  expect_physical(cylinder.unit_density_inertia());
}

// Composite Simpson rule on [a, b] with n (even) panels.
double simpson(const std::function<double(double)>& f, double a, double b, int n) {
  const double h = (b - a) / n;
  double sum = f(a) + f(b);
  for (int i = 1; i < n; ++i)
    sum += f(a + i * h) * (i % 2 == 1 ? 4.0 : 2.0);
  return sum * h / 3.0;
}

// Volume and inertia of a body of revolution about z, slice by slice: a disk of radius rho at
// height z has area pi rho^2, axial moment pi rho^4 / 2 and transverse moment
// pi rho^4 / 4 + pi rho^2 z^2 (per unit thickness). No parallel-axis algebra involved.
struct Integrals {
  double volume = 0.0;
  double axial = 0.0;
  double transverse = 0.0;
};

Integrals integrate_revolution(const std::function<double(double)>& rho, double z0, double z1) {
  constexpr int kPanels = 2000;
  Integrals out;
  out.volume = simpson([&](double z) { return kPi * std::pow(rho(z), 2); }, z0, z1, kPanels);
  out.axial = simpson([&](double z) { return kPi * std::pow(rho(z), 4) / 2.0; }, z0, z1, kPanels);
  out.transverse = simpson(
      [&](double z) { return kPi * std::pow(rho(z), 4) / 4.0 + kPi * std::pow(rho(z), 2) * z * z; },
      z0, z1, kPanels);
  return out;
}

TEST(SceneShapes, CapsuleMatchesSliceIntegration) {
  const std::array<std::array<double, 2>, 4> radius_length_m{
      {{0.01, 0.05}, {0.02, 0.0}, {0.03, 0.3}, {0.05, 0.02}}};
  for (const auto& rl : radius_length_m) {
    const double r_m = rl[0], h_m = rl[1];
    SCOPED_TRACE("r " + std::to_string(r_m) + " h " + std::to_string(h_m));
    const double half = 0.5 * h_m;
    // integrate cap, cylinder and cap separately so each integrand is a smooth polynomial
    auto cap_rho = [&](double z) {
      const double s = std::abs(z) - half;
      return std::sqrt(std::max(0.0, r_m * r_m - s * s));
    };
    const Integrals lower = integrate_revolution(cap_rho, -half - r_m, -half);
    const Integrals body = integrate_revolution([&](double) { return r_m; }, -half, half);
    const Integrals upper = integrate_revolution(cap_rho, half, half + r_m);
    const double volume = lower.volume + body.volume + upper.volume;
    const double axial = lower.axial + body.axial + upper.axial;
    const double transverse = lower.transverse + body.transverse + upper.transverse;

    const Shape capsule = Shape::capsule(r_m, h_m);
    EXPECT_NEAR(capsule.volume_m3(), volume, 1e-9 * volume);
    expect_diagonal(capsule.unit_density_inertia(), Eigen::Vector3d(transverse, transverse, axial),
                    1e-8);
    expect_physical(capsule.unit_density_inertia());
  }
}

TEST(SceneShapes, CapsuleLimitsAreSphereAndLongCylinder) {
  const double r_m = 0.02;
  // no cylinder part: exactly a sphere
  const Shape ball = Shape::capsule(r_m, 0.0);
  EXPECT_DOUBLE_EQ(ball.volume_m3(), Shape::sphere(r_m).volume_m3());
  EXPECT_TRUE(
      ball.unit_density_inertia().isApprox(Shape::sphere(r_m).unit_density_inertia(), 1e-14));
  // very long: the caps stop mattering
  const double h_m = 200.0;
  const Eigen::Matrix3d I_cap = Shape::capsule(r_m, h_m).unit_density_inertia();
  const Eigen::Matrix3d I_cyl = Shape::cylinder(r_m, h_m).unit_density_inertia();
  EXPECT_NEAR(I_cap(0, 0) / I_cyl(0, 0), 1.0, 1e-3);
}

TEST(SceneShapes, DensityGivesMassAndScaledInertia) {
  const double density_kgpm3 = 2700.0;  // aluminium
  for (const Shape& shape : {Shape::box({0.1, 0.2, 0.05}), Shape::sphere(0.03),
                             Shape::capsule(0.01, 0.1), Shape::cylinder(0.018, 0.16)}) {
    double mass_kg = 0.0;
    Eigen::Matrix3d I_O = Eigen::Matrix3d::Zero();
    mass_properties_from_density(shape, density_kgpm3, mass_kg, I_O);
    EXPECT_DOUBLE_EQ(mass_kg, density_kgpm3 * shape.volume_m3());
    EXPECT_TRUE(I_O.isApprox(density_kgpm3 * shape.unit_density_inertia(), 1e-15));
  }
  // a 10 cm cube of water weighs a kilogram, I = m a^2 / 6
  double mass_kg = 0.0;
  Eigen::Matrix3d I_O;
  mass_properties_from_density(Shape::box({0.1, 0.1, 0.1}), 1000.0, mass_kg, I_O);
  EXPECT_NEAR(mass_kg, 1.0, 1e-12);
  EXPECT_NEAR(I_O(2, 2), 1.0 * 0.01 / 6.0, 1e-15);
}

TEST(SceneShapes, BoundingRadiusIsTheFarthestPoint) {
  EXPECT_DOUBLE_EQ(Shape::box({0.2, 0.3, 0.6}).bounding_radius_m(), 0.35);  // half of 0.7
  EXPECT_DOUBLE_EQ(Shape::sphere(0.03).bounding_radius_m(), 0.03);
  EXPECT_DOUBLE_EQ(Shape::capsule(0.01, 0.08).bounding_radius_m(), 0.05);   // cap tip
  EXPECT_DOUBLE_EQ(Shape::cylinder(0.03, 0.08).bounding_radius_m(), 0.05);  // rim: 3-4-5
}

TEST(SceneShapes, FindObjectByName) {
  Scene scene;
  scene.objects.resize(3);
  scene.objects[0].name = "floor";
  scene.objects[1].name = "cup";
  scene.objects[2].name = "ball";
  EXPECT_EQ(scene.find_object("floor"), 0);
  EXPECT_EQ(scene.find_object("ball"), 2);
  EXPECT_EQ(scene.find_object("Cup"), -1);
  EXPECT_EQ(scene.find_object(""), -1);
}

}  // namespace
}  // namespace vcockpit::physics
