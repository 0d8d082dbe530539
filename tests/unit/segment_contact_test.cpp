// The capsule-against-round-body contact from closest points (segment_contact.hpp), against
// closed forms: a capsule beside a cylinder's side, over its cap, by its rim, lying along it; two
// capsules crossing; and a segment inside the body, which is left to MPR.

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "physics_node/physics/segment_contact.hpp"

namespace vcockpit::physics {
namespace {

// A cylinder of radius 18 mm and length 160 mm lying along x at the origin (a flashlight).
RoundBody flashlight() {
  RoundBody b;
  b.kind = RoundBody::Kind::kCylinder;
  b.X_GB.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY()).toRotationMatrix();
  b.radius_m = 0.018;
  b.half_length_m = 0.08;
  return b;
}

TEST(SegmentContact, AFingertipOnTheSideOfALongBarrelPushesStraightIntoIt) {
  // a fingertip capsule (radius 8 mm) near one end of the barrel, on its side at 30 degrees below
  // the horizontal, 1 mm into it, its axis along the barrel's tangent
  const double angle = -M_PI / 6;
  const Eigen::Vector3d radial(0.0, std::cos(angle), std::sin(angle));
  const Eigen::Vector3d tangent(0.0, -std::sin(angle), std::cos(angle));
  const Eigen::Vector3d centre = Eigen::Vector3d(0.06, 0.0, 0.0) + (0.018 + 0.008 - 0.001) * radial;
  const SegmentContact c = segment_contact(centre - 0.01 * tangent, centre + 0.01 * tangent, 0.008,
                                           flashlight());
  ASSERT_TRUE(c.resolved);
  EXPECT_NEAR(c.depth_m, 0.001, 1e-8);
  EXPECT_NEAR(c.n_G.dot(radial), 1.0, 1e-8) << c.n_G.transpose();
  // midway between the surfaces: the barrel's surface backed out by half the depth
  const Eigen::Vector3d expected = Eigen::Vector3d(0.06, 0.0, 0.0) + (0.018 - 0.0005) * radial;
  EXPECT_LT((c.p_G - expected).norm(), 1e-7) << c.p_G.transpose();
}

TEST(SegmentContact, OverTheCapTheNormalIsTheAxis) {
  // a capsule across the cap's face (x = 0.08), 0.5 mm into it
  const Eigen::Vector3d centre(0.08 + 0.006 - 0.0005, 0.003, 0.0);
  const SegmentContact c = segment_contact(centre + Eigen::Vector3d(0, 0.005, 0.002),
                                           centre - Eigen::Vector3d(0, 0.005, 0.002), 0.006,
                                           flashlight());
  ASSERT_TRUE(c.resolved);
  EXPECT_NEAR(c.depth_m, 0.0005, 1e-8);
  EXPECT_NEAR(c.n_G.x(), 1.0, 1e-8);
}

TEST(SegmentContact, ByTheRimTheNormalPointsFromTheRim) {
  // a capsule end beyond the rim at 45 degrees between the cap and the side
  const Eigen::Vector3d rim(0.08, 0.018, 0.0);
  const Eigen::Vector3d out = Eigen::Vector3d(1.0, 1.0, 0.0).normalized();
  const Eigen::Vector3d end = rim + (0.005 - 0.0008) * out;
  const SegmentContact c = segment_contact(end, end + 0.02 * out, 0.005, flashlight());
  ASSERT_TRUE(c.resolved);
  EXPECT_NEAR(c.depth_m, 0.0008, 1e-8);
  EXPECT_NEAR(c.n_G.dot(out), 1.0, 1e-8);
}

TEST(SegmentContact, ACapsuleLyingAlongTheBarrelTouchesAlongItsLength) {
  // parallel to the axis on top: every point of the segment is equally near; the depth is exact
  // and the normal straight up
  const double z = 0.018 + 0.007 - 0.0003;
  const SegmentContact c = segment_contact({-0.02, 0.0, z}, {0.02, 0.0, z}, 0.007, flashlight());
  ASSERT_TRUE(c.resolved);
  EXPECT_NEAR(c.depth_m, 0.0003, 1e-9);
  EXPECT_NEAR(c.n_G.z(), 1.0, 1e-9);
  EXPECT_LE(std::abs(c.p_G.x()), 0.02 + 1e-9);
}

TEST(SegmentContact, ApartGivesNoDepth) {
  const SegmentContact c = segment_contact({0.0, 0.0, 0.03}, {0.01, 0.0, 0.03}, 0.008, flashlight());
  ASSERT_TRUE(c.resolved);
  EXPECT_LT(c.depth_m, 0.0);
}

TEST(SegmentContact, TwoCrossingCapsulesMeetAtTheirCommonNormal) {
  RoundBody bar;
  bar.kind = RoundBody::Kind::kCapsule;
  bar.radius_m = 0.01;
  bar.half_length_m = 0.05;  // along z
  // a capsule along x beside the bar on +y, 2 mm into it, crossing it at z = 0.02
  const double y = 0.01 + 0.004 - 0.002;
  const SegmentContact c = segment_contact({-0.03, y, 0.02}, {0.03, y, 0.02}, 0.004, bar);
  ASSERT_TRUE(c.resolved);
  EXPECT_NEAR(c.depth_m, 0.002, 1e-8);
  EXPECT_NEAR(c.n_G.y(), 1.0, 1e-8);
  EXPECT_NEAR(c.p_G.z(), 0.02, 1e-7);
}

TEST(SegmentContact, ASegmentInsideTheBodyIsLeftToMpr) {
  const SegmentContact c = segment_contact({0.0, 0.0, 0.01}, {0.0, 0.0, 0.05}, 0.008, flashlight());
  EXPECT_FALSE(c.resolved);
}

TEST(SegmentContact, SignedDistanceOfACylinder) {
  const RoundBody b = flashlight();
  Eigen::Vector3d grad;
  EXPECT_NEAR(signed_distance(b, {0.0, 0.0, 0.03}, grad), 0.012, 1e-12);
  EXPECT_NEAR(grad.z(), 1.0, 1e-12);
  EXPECT_NEAR(signed_distance(b, {0.09, 0.0, 0.0}, grad), 0.01, 1e-12);
  EXPECT_NEAR(grad.x(), 1.0, 1e-12);
  EXPECT_NEAR(signed_distance(b, {0.083, 0.0, 0.022}, grad), 0.005, 1e-12);  // 3-4-5 from the rim
  EXPECT_NEAR(signed_distance(b, {0.0, 0.0, 0.01}, grad), -0.008, 1e-12);     // inside: the side
  EXPECT_NEAR(grad.z(), 1.0, 1e-12);
}

// The least distance along a segment is found wherever it lies -- at either end (a finger
// pointing at the body, found from the slope at the ends) or inside (one lying across it) --
// against the least of 20001 samples: never more than the search's tolerance above it, never
// below the true least value (the samples' error, first order where the segment passes a rim).
// Seeded segments of 1-6 cm around a cylinder and a capsule, each kept where it stays outside.
TEST(SegmentContact, TheLeastDistanceIsFoundAtAnEndOrInsideAsSamplingFindsIt) {
  std::mt19937 rng(20051207);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  RoundBody capsule = flashlight();
  capsule.kind = RoundBody::Kind::kCapsule;
  int at_end = 0, inside = 0;
  for (const RoundBody& body : {flashlight(), capsule}) {
    for (int trial = 0; trial < 400; ++trial) {
      const Eigen::Vector3d a(0.12 * unit(rng), 0.05 * unit(rng), 0.05 * unit(rng));
      const Eigen::Vector3d direction = Eigen::Vector3d(unit(rng), unit(rng), unit(rng)).normalized();
      const Eigen::Vector3d b = a + (0.035 + 0.025 * unit(rng)) * direction;
      double sampled = 1e9;
      int sampled_at = 0;
      constexpr int kSamples = 20000;
      for (int i = 0; i <= kSamples; ++i) {
        Eigen::Vector3d grad;
        const double d = signed_distance(body, a + (static_cast<double>(i) / kSamples) * (b - a), grad);
        if (d < sampled) {
          sampled = d;
          sampled_at = i;
        }
      }
      if (sampled <= 1e-4) continue;  // reaching into the body (or nearly): left to MPR
      constexpr double kRadius_m = 0.03;  // overlapping the body, so there is a depth to read
      const SegmentContact c = segment_contact(a, b, kRadius_m, body);
      ASSERT_TRUE(c.resolved) << trial;
      const double found = kRadius_m - c.depth_m;
      EXPECT_LE(found, sampled + 1e-9) << trial;
      EXPECT_GE(found, sampled - 1e-5) << trial;
      (sampled_at == 0 || sampled_at == kSamples ? at_end : inside) += 1;
    }
  }
  // both cases were tried
  EXPECT_GT(at_end, 50);
  EXPECT_GT(inside, 50);
}

}  // namespace
}  // namespace vcockpit::physics
