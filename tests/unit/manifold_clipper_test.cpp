// The manifold clipper on plain Eigen data (no FCL): a cylinder lying or standing on a box face,
// an overhang clipped to the face, a normal off every face left to the narrowphase, and the
// reduction keeping the deepest point and the spread ones.

#include "physics_node/physics/manifold_clipper.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace vcockpit::physics {
namespace {

constexpr double kDepth_m = 1e-3;
constexpr double kRadius_m = 0.03;
constexpr double kHalfLength_m = 0.1;

// A 1 m x 1 m x 0.2 m box, its top face at z = 0.1 m.
ClipBody table() {
  ClipBody b;
  b.shape = ShapeKind::kBox;
  b.half_size_m = {0.5, 0.5, 0.1};
  return b;
}

ClipBody cylinder(const Eigen::Vector3d& p_G, const Eigen::Matrix3d& R_GB) {
  ClipBody c;
  c.shape = ShapeKind::kCylinder;
  c.X_GB.translation() = p_G;
  c.X_GB.linear() = R_GB;
  c.radius_m = kRadius_m;
  c.half_length_m = kHalfLength_m;
  return c;
}

// The cylinder's axis along x, lying kDepth_m deep in the table's top.
ClipBody lying_cylinder(double x_m) {
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY()).toRotationMatrix();
  return cylinder({x_m, 0.0, 0.1 + kRadius_m - kDepth_m}, R);
}

TEST(ManifoldClipper, CylinderLyingOnABoxFaceGivesBothEndsOfItsSideLine) {
  ManifoldClipper clipper(4);
  std::array<ManifoldPoint, kMaxManifold> out;
  const int n = clipper.clip(table(), lying_cylinder(0.0), Eigen::Vector3d::UnitZ(), out);
  ASSERT_EQ(n, 2);
  for (int i = 0; i < n; ++i) {
    EXPECT_NEAR(out[i].depth_m, kDepth_m, 1e-12);
    // midway between the surfaces: the side line is kDepth_m below the face
    EXPECT_NEAR(out[i].p_G.z(), 0.1 - 0.5 * kDepth_m, 1e-12);
    EXPECT_NEAR(out[i].p_G.y(), 0.0, 1e-12);
    EXPECT_NEAR(std::abs(out[i].p_G.x()), kHalfLength_m, 1e-12);
  }
  EXPECT_NEAR(out[0].p_G.x(), -out[1].p_G.x(), 1e-12) << "one point at each end";
}

TEST(ManifoldClipper, EitherBodyOrderGivesTheSamePoints) {
  ManifoldClipper clipper(4);
  std::array<ManifoldPoint, kMaxManifold> ab, ba;
  const int n_ab = clipper.clip(table(), lying_cylinder(0.0), Eigen::Vector3d::UnitZ(), ab);
  const int n_ba = clipper.clip(lying_cylinder(0.0), table(), -Eigen::Vector3d::UnitZ(), ba);
  ASSERT_EQ(n_ab, n_ba);
  for (int i = 0; i < n_ab; ++i) {
    EXPECT_TRUE(ab[i].p_G.isApprox(ba[i].p_G, 1e-12));
    EXPECT_DOUBLE_EQ(ab[i].depth_m, ba[i].depth_m);
  }
}

TEST(ManifoldClipper, OverhangIsClippedToTheFaceEdge) {
  // the cylinder's middle over the table's edge at x = 0.5 m: the end beyond it is cut off there
  ManifoldClipper clipper(4);
  std::array<ManifoldPoint, kMaxManifold> out;
  const int n = clipper.clip(table(), lying_cylinder(0.5), Eigen::Vector3d::UnitZ(), out);
  ASSERT_EQ(n, 2);
  const double x_lo = std::min(out[0].p_G.x(), out[1].p_G.x());
  const double x_hi = std::max(out[0].p_G.x(), out[1].p_G.x());
  EXPECT_NEAR(x_lo, 0.5 - kHalfLength_m, 1e-12);
  EXPECT_NEAR(x_hi, 0.5, 1e-12) << "the crossing point on the face's edge";
}

TEST(ManifoldClipper, UprightCylinderKeepsFourSpreadRimPoints) {
  // a level cap: 8 rim points all equally deep; ties go to the lowest index, then the farthest
  // from it, the largest triangle, the most area outside it: a square on the rim
  ManifoldClipper clipper(4);
  std::array<ManifoldPoint, kMaxManifold> out;
  const ClipBody cup =
      cylinder({0.0, 0.0, 0.1 + kHalfLength_m - kDepth_m}, Eigen::Matrix3d::Identity());
  const int n = clipper.clip(table(), cup, Eigen::Vector3d::UnitZ(), out);
  ASSERT_EQ(n, 4);
  const Eigen::Vector2d expected[4] = {
      {kRadius_m, 0}, {-kRadius_m, 0}, {0, kRadius_m}, {0, -kRadius_m}};
  for (int i = 0; i < n; ++i) {
    EXPECT_NEAR(out[i].depth_m, kDepth_m, 1e-12);
    EXPECT_NEAR(out[i].p_G.x(), expected[i].x(), 1e-12) << "point " << i;
    EXPECT_NEAR(out[i].p_G.y(), expected[i].y(), 1e-12) << "point " << i;
  }
}

TEST(ManifoldClipper, MaxPointsCapsTheManifold) {
  ManifoldClipper clipper(2);
  std::array<ManifoldPoint, kMaxManifold> out;
  const ClipBody cup =
      cylinder({0.0, 0.0, 0.1 + kHalfLength_m - kDepth_m}, Eigen::Matrix3d::Identity());
  EXPECT_EQ(clipper.clip(table(), cup, Eigen::Vector3d::UnitZ(), out), 2);
}

TEST(ManifoldClipper, TiltedCylinderWithOneRimPointInGivesItsDeepestPoint) {
  // tilted 5 deg about y, 0.1 mm deep: only the rim's lowest point reaches into the face (the
  // next rim points are 0.77 mm higher)
  constexpr double kShallow_m = 1e-4;
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(5.0 * M_PI / 180, Eigen::Vector3d::UnitY()).toRotationMatrix();
  const double lowest_above_centre_m =
      kHalfLength_m * std::cos(5.0 * M_PI / 180) + kRadius_m * std::sin(5.0 * M_PI / 180);
  const ClipBody cup = cylinder({0.0, 0.0, 0.1 + lowest_above_centre_m - kShallow_m}, R);
  ManifoldClipper clipper(4);
  std::array<ManifoldPoint, kMaxManifold> out;
  ASSERT_EQ(clipper.clip(table(), cup, Eigen::Vector3d::UnitZ(), out), 1);
  EXPECT_NEAR(out[0].depth_m, kShallow_m, 1e-12);
  EXPECT_NEAR(out[0].p_G.z(), 0.1 - 0.5 * kShallow_m, 1e-12);
}

TEST(ManifoldClipper, NormalOffEveryFaceIsLeftToTheNarrowphase) {
  // an edge or rim contact: no face is perpendicular to the normal, so no manifold
  ManifoldClipper clipper(4);
  std::array<ManifoldPoint, kMaxManifold> out;
  const Eigen::Vector3d n = Eigen::Vector3d(0.0, 0.3, 1.0).normalized();
  EXPECT_EQ(clipper.clip(table(), lying_cylinder(0.0), n, out), 0);
}

TEST(ManifoldClipper, SeparatedBodiesGiveNothing) {
  ManifoldClipper clipper(4);
  std::array<ManifoldPoint, kMaxManifold> out;
  ClipBody above = lying_cylinder(0.0);
  above.X_GB.translation().z() += 0.01;
  EXPECT_EQ(clipper.clip(table(), above, Eigen::Vector3d::UnitZ(), out), 0);
}

TEST(ManifoldClipper, WantsAManifoldOnlyForFlatRoundContacts) {
  EXPECT_TRUE(wants_manifold(ShapeKind::kBox, ShapeKind::kCylinder));
  EXPECT_TRUE(wants_manifold(ShapeKind::kCapsule, ShapeKind::kBox));
  EXPECT_TRUE(wants_manifold(ShapeKind::kCylinder, ShapeKind::kCapsule));
  EXPECT_TRUE(wants_manifold(ShapeKind::kCylinder, ShapeKind::kCylinder));
  EXPECT_FALSE(wants_manifold(ShapeKind::kBox, ShapeKind::kBox));     // FCL's own 4 points
  EXPECT_FALSE(wants_manifold(ShapeKind::kBox, ShapeKind::kSphere));  // one point is right
  EXPECT_FALSE(wants_manifold(ShapeKind::kCapsule, ShapeKind::kCapsule));
}

TEST(ManifoldReduction, KeepsTheDeepestThenTheSpreadPoints) {
  // a 2 cm square's corners, its centre (deepest) and a near-duplicate of one corner
  std::array<Candidate, kMaxCandidates> cand;
  const Eigen::Vector3d q[] = {{0.01, 0.01, 0},   {-0.01, 0.01, 0}, {0.0, 0.0, 0},
                               {-0.01, -0.01, 0}, {0.01, -0.01, 0}, {0.01, -0.01 + 1e-8, 0}};
  const double depth_m[] = {1e-3, 1e-3, 2e-3, 1e-3, 1e-3, 1.5e-3};
  for (int i = 0; i < 6; ++i)
    cand[i] = {q[i], depth_m[i]};
  std::array<int, kMaxManifold> pick{};
  const int n = reduce_manifold(cand, 6, Eigen::Vector3d::UnitZ(), 4, pick);
  ASSERT_EQ(n, 4);
  EXPECT_EQ(pick[0], 2) << "the deepest first";
  EXPECT_EQ(pick[1], 0) << "then the farthest from it (ties to the lower index)";
  // then the largest triangle with those two (corner 1), then the most area outside it (corners
  // 3 and 4 add as much: the first), never the near-duplicate (5) of corner 4
  EXPECT_EQ(pick[2], 1);
  EXPECT_EQ(pick[3], 3);
}

TEST(ManifoldReduction, NearDuplicatesStayOnePoint) {
  std::array<Candidate, kMaxCandidates> cand;
  cand[0] = {Eigen::Vector3d(0.0, 0.0, 0.0), 1e-3};
  cand[1] = {Eigen::Vector3d(1e-7, 0.0, 0.0), 1e-3};
  std::array<int, kMaxManifold> pick{};
  EXPECT_EQ(reduce_manifold(cand, 2, Eigen::Vector3d::UnitZ(), 4, pick), 1);
  EXPECT_EQ(pick[0], 0);
}

}  // namespace
}  // namespace vcockpit::physics
