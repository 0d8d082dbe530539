// grip_fit's signed distances (physics_node/fit/shape_distance.hpp) against closed forms: a point
// against each shape, a capsule link against each shape (apart and shallowly overlapping), the
// palm box against each shape, two segments, and each shape's reach along a direction.

#include <gtest/gtest.h>

#include <cmath>

#include "physics_node/fit/shape_distance.hpp"

namespace vcockpit::fit {
namespace {

using physics::Shape;

Eigen::Isometry3d pose(const Eigen::Vector3d& p,
                       const Eigen::Matrix3d& R = Eigen::Matrix3d::Identity()) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = R;
  X.translation() = p;
  return X;
}

Eigen::Matrix3d about(const Eigen::Vector3d& axis, double angle_rad) {
  return Eigen::AngleAxisd(angle_rad, axis.normalized()).toRotationMatrix();
}

// The least point distance along the segment, sampled finely: the brute force the search's
// closed forms and golden sections must agree with.
double sampled_capsule_distance(const Shape& shape, const Eigen::Isometry3d& X_GO,
                                const Eigen::Vector3d& a, const Eigen::Vector3d& b, double r) {
  double least = INFINITY;
  for (int i = 0; i <= 20000; ++i) {
    const Eigen::Vector3d p = a + (b - a) * (i / 20000.0);
    least = std::min(least, point_signed_distance(shape, X_GO.inverse() * p));
  }
  return least - r;
}

TEST(GripFitDistance, PointAgainstEachShape) {
  const Shape box = Shape::box({0.04, 0.02, 0.06});                    // half 0.02, 0.01, 0.03
  EXPECT_NEAR(point_signed_distance(box, {0.05, 0, 0}), 0.03, 1e-15);  // beyond a face
  EXPECT_NEAR(point_signed_distance(box, {0.03, 0.02, 0}), std::hypot(0.01, 0.01),
              1e-15);                                                     // an edge
  EXPECT_NEAR(point_signed_distance(box, {0.015, 0, 0}), -0.005, 1e-15);  // inside: nearest face
  EXPECT_NEAR(point_signed_distance(box, {0, 0.008, 0.01}), -0.002, 1e-15);

  const Shape sphere = Shape::sphere(0.025);
  EXPECT_NEAR(point_signed_distance(sphere, {0.03, 0.04, 0}), 0.025, 1e-15);
  EXPECT_NEAR(point_signed_distance(sphere, {0, 0, 0.005}), -0.02, 1e-15);

  const Shape cylinder = Shape::cylinder(0.015, 0.12);  // axis z, caps at +-0.06
  EXPECT_NEAR(point_signed_distance(cylinder, {0.02, 0, 0.01}), 0.005, 1e-15);      // the side
  EXPECT_NEAR(point_signed_distance(cylinder, {0.003, 0.004, 0.07}), 0.01, 1e-15);  // a cap
  EXPECT_NEAR(point_signed_distance(cylinder, {0.018, 0, -0.064}), 0.005, 1e-15);  // the rim: 3-4-5
  EXPECT_NEAR(point_signed_distance(cylinder, {0.012, 0, 0}), -0.003,
              1e-15);  // inside, near the side
  EXPECT_NEAR(point_signed_distance(cylinder, {0, 0, 0.058}), -0.002, 1e-15);  // inside, near a cap

  const Shape capsule = Shape::capsule(0.01, 0.05);  // segment z in +-0.025
  EXPECT_NEAR(point_signed_distance(capsule, {0.02, 0, 0.01}), 0.01, 1e-15);
  EXPECT_NEAR(point_signed_distance(capsule, {0, 0.03, 0.065}), 0.04,
              1e-15);  // beyond a cap: 3-4-5
  EXPECT_NEAR(point_signed_distance(capsule, {0.004, 0, 0.02}), -0.006, 1e-15);
}

TEST(GripFitDistance, SegmentsClosestPoints) {
  const Eigen::Vector3d o = Eigen::Vector3d::Zero();
  // skew, perpendicular, 7 mm apart where they cross
  EXPECT_NEAR(segment_segment_distance({-1, 0, 0}, {1, 0, 0}, {0, -1, 0.007}, {0, 1, 0.007}), 0.007,
              1e-15);
  // parallel and overlapping: the gap between the lines
  EXPECT_NEAR(segment_segment_distance(o, {1, 0, 0}, {0.5, 0.003, 0}, {2, 0.003, 0}), 0.003, 1e-15);
  // parallel, end to end along the same line
  EXPECT_NEAR(segment_segment_distance(o, {1, 0, 0}, {1.2, 0, 0}, {2, 0, 0}), 0.2, 1e-15);
  // crossing: 0
  EXPECT_NEAR(segment_segment_distance({-1, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 1, 0}), 0.0, 1e-15);
  // a point (degenerate segment) against a segment: the end nearest it
  EXPECT_NEAR(segment_segment_distance({2, 1, 0}, {2, 1, 0}, o, {1, 0, 0}), std::sqrt(2.0), 1e-15);
}

TEST(GripFitDistance, CapsuleLinkAgainstEachShapeMatchesClosedForms) {
  const double r = 0.008;  // a phalanx
  // a box: the link parallel to its top face (z = +0.03) at a 1.5 mm surface gap, then 1 mm into it
  const Shape box = Shape::box({0.04, 0.02, 0.06});
  const Eigen::Isometry3d X_GB = pose({0.3, -0.2, 0.9}, about({1, 2, 3}, 0.7));
  for (double gap : {0.0015, -0.001}) {
    const Eigen::Vector3d a = X_GB * Eigen::Vector3d(-0.01, 0, 0.03 + r + gap);
    const Eigen::Vector3d b = X_GB * Eigen::Vector3d(0.01, 0.005, 0.03 + r + gap);
    EXPECT_NEAR(capsule_signed_distance(box, X_GB, a, b, r), gap, 1e-9) << gap;
  }
  // across an edge of the box at 45 deg: the edge is 2 mm from the segment
  {
    const Eigen::Vector3d edge(0.02, 0.0, 0.03);  // the edge along y at x = 0.02, z = 0.03
    const Eigen::Vector3d out = Eigen::Vector3d(1, 0, 1).normalized() * (0.002);
    const Eigen::Vector3d a = X_GB * (edge + out + Eigen::Vector3d(-0.01, 0, 0.01));
    const Eigen::Vector3d b = X_GB * (edge + out + Eigen::Vector3d(0.01, 0, -0.01));
    EXPECT_NEAR(capsule_signed_distance(box, X_GB, a, b, r), 0.002 - r, 1e-9);
    EXPECT_NEAR(capsule_signed_distance(box, X_GB, a, b, r),
                sampled_capsule_distance(box, X_GB, a, b, r), 2e-6);
  }
  // a sphere: the segment passes 30 mm from its centre
  const Shape sphere = Shape::sphere(0.02);
  const Eigen::Isometry3d X_GS = pose({0.1, 0.2, 0.3});
  EXPECT_NEAR(capsule_signed_distance(sphere, X_GS, {0.05, 0.23, 0.3}, {0.15, 0.23, 0.3}, r),
              0.03 - 0.02 - r, 1e-15);
  // a cylinder lying along world y: the link across it above, 0.7 mm off the side; then along it
  // beyond a cap, 3 mm off
  const Shape cylinder = Shape::cylinder(0.015, 0.12);
  const Eigen::Isometry3d X_GC = pose({0.4, -0.3, 0.8}, about({1, 0, 0}, M_PI / 2));  // z_O = -y_G
  EXPECT_NEAR(capsule_signed_distance(cylinder, X_GC, {0.37, -0.31, 0.8 + 0.015 + r + 0.0007},
                                      {0.43, -0.29, 0.8 + 0.015 + r + 0.0007}, r),
              0.0007, 1e-9);
  EXPECT_NEAR(capsule_signed_distance(cylinder, X_GC, {0.4, -0.3 + 0.06 + r + 0.003, 0.8},
                                      {0.4, -0.3 + 0.1, 0.8}, r),
              0.003, 1e-9);
  // ... and in general poses, the brute force
  for (int k = 0; k < 20; ++k) {
    const Eigen::Vector3d a(0.4 + 0.01 * std::sin(k), -0.3 + 0.03 * std::cos(3.0 * k),
                            0.8 + 0.025 * std::sin(2.0 * k));
    const Eigen::Vector3d b = a + Eigen::Vector3d(0.03 * std::cos(k), 0.02, -0.01 * k / 20.0);
    EXPECT_NEAR(capsule_signed_distance(cylinder, X_GC, a, b, r),
                sampled_capsule_distance(cylinder, X_GC, a, b, r), 2e-6)
        << k;
    EXPECT_NEAR(capsule_signed_distance(box, X_GB, a, b, r),
                sampled_capsule_distance(box, X_GB, a, b, r), 2e-6)
        << k;
  }
  // a capsule: skew at right angles, 25 mm between the segments
  const Shape capsule = Shape::capsule(0.01, 0.05);
  const Eigen::Isometry3d X_GK = pose({0, 0, 1});
  EXPECT_NEAR(capsule_signed_distance(capsule, X_GK, {-0.02, 0.025, 1.0}, {0.02, 0.025, 1.0}, r),
              0.025 - 0.01 - r, 1e-15);
}

TEST(GripFitDistance, PalmBoxAgainstEachShape) {
  const Eigen::Vector3d palm(0.09, 0.085, 0.03);  // half 0.045, 0.0425, 0.015
  const Eigen::Isometry3d X_GP = pose({0.2, 0.1, 0.9}, about({0, 1, 0}, 0.3));
  const Eigen::Vector3d down = X_GP.linear() * Eigen::Vector3d(0, 0, -1);  // out of the palm face
  const Eigen::Vector3d face = X_GP * Eigen::Vector3d(0.01, 0.0, -0.015);
  // a sphere 2 mm below the face, 1 mm into it, and beyond a corner
  const Shape sphere = Shape::sphere(0.02);
  EXPECT_NEAR(box_signed_distance(sphere, pose(face + (0.022) * down), palm, X_GP), 0.002, 1e-12);
  EXPECT_NEAR(box_signed_distance(sphere, pose(face + (0.019) * down), palm, X_GP), -0.001, 1e-12);
  const Eigen::Vector3d corner = X_GP * Eigen::Vector3d(0.045, 0.0425, 0.015);
  const Eigen::Vector3d diagonal = X_GP.linear() * Eigen::Vector3d(1, 1, 1).normalized();
  EXPECT_NEAR(box_signed_distance(sphere, pose(corner + 0.03 * diagonal), palm, X_GP), 0.01, 1e-12);
  // a capsule lying under the face, across it, 1.5 mm off
  const Shape capsule = Shape::capsule(0.01, 0.05);
  const Eigen::Matrix3d across =
      X_GP.linear() * about({1, 0, 0}, M_PI / 2);  // its z along the palm's y
  EXPECT_NEAR(box_signed_distance(capsule, pose(face + 0.0115 * down, across), palm, X_GP), 0.0015,
              1e-9);
  // FCL for a box and a cylinder: a bar under the face (1.5 mm off, then 1 mm in) and a box under
  // it
  const Shape cylinder = Shape::cylinder(0.015, 0.12);
  EXPECT_NEAR(box_signed_distance(cylinder, pose(face + 0.0165 * down, across), palm, X_GP), 0.0015,
              1e-6);
  EXPECT_NEAR(box_signed_distance(cylinder, pose(face + 0.014 * down, across), palm, X_GP), -0.001,
              1e-6);
  const Shape box = Shape::box({0.03, 0.03, 0.02});
  EXPECT_NEAR(box_signed_distance(box, pose(face + 0.013 * down, X_GP.linear()), palm, X_GP), 0.003,
              1e-6);
  EXPECT_NEAR(box_signed_distance(box, pose(face + 0.009 * down, X_GP.linear()), palm, X_GP),
              -0.001, 1e-6);
}

TEST(GripFitDistance, ReachAlongADirection) {
  const Eigen::Vector3d u = Eigen::Vector3d(1, 2, 2) / 3.0;
  EXPECT_NEAR(support_half_extent(Shape::box({0.04, 0.02, 0.06}), u), (0.02 + 0.02 + 0.06) / 3.0,
              1e-15);
  EXPECT_NEAR(support_half_extent(Shape::sphere(0.025), u), 0.025, 1e-15);
  // cylinder: r sin + L/2 cos of the angle to its axis (cos = 2/3)
  EXPECT_NEAR(support_half_extent(Shape::cylinder(0.015, 0.12), u),
              0.015 * std::sqrt(5.0) / 3.0 + 0.06 * 2.0 / 3.0, 1e-15);
  EXPECT_NEAR(support_half_extent(Shape::capsule(0.01, 0.05), u), 0.01 + 0.025 * 2.0 / 3.0, 1e-15);
}

}  // namespace
}  // namespace vcockpit::fit
