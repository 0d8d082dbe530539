// grip_fit's placement (physics_node/fit/grip_fit.hpp) on made-up hands: a fist holds a bar, a
// ball, a capsule and a box (the thumb and two more fingers within 1 mm, one opposing the thumb,
// no link over 2 mm in: checked again here by brute force), a flat hand and a fist round a
// too-big ball hold nothing, and the same input gives the same placement.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "physics_node/fit/grip_fit.hpp"
#include "physics_node/fit/shape_distance.hpp"
#include "tests/unit/grip_fit_samples.hpp"

namespace vcockpit::fit {
namespace {

using physics::Shape;

// The deepest any point of a link gets into the object, by sampling: points along each phalanx
// segment (less the radius) and a grid through the palm box. > 0: inside.
double sampled_deepest_m(const GripHand& hand, const Shape& shape, const Eigen::Isometry3d& X_GO) {
  const Eigen::Isometry3d X_OG = X_GO.inverse();
  double least = INFINITY;
  for (int l = 1; l < hand::kLinkCount; ++l) {
    const auto k = static_cast<std::size_t>(l);
    for (int i = 0; i <= 400; ++i) {
      const Eigen::Vector3d p = hand.a_G[k] + (hand.b_G[k] - hand.a_G[k]) * (i / 400.0);
      least = std::min(least, point_signed_distance(shape, X_OG * p) - hand.radius_m[k]);
    }
  }
  for (int i = 0; i <= 30; ++i)
    for (int j = 0; j <= 30; ++j)
      for (int m = 0; m <= 10; ++m) {
        const Eigen::Vector3d u(i / 30.0 - 0.5, j / 30.0 - 0.5, m / 10.0 - 0.5);
        const Eigen::Vector3d p = hand.X_GP * Eigen::Vector3d(u.cwiseProduct(hand.palm_size_m));
        least = std::min(least, point_signed_distance(shape, X_OG * p));
      }
  return -least;
}

void print(const char* what, const Placement& p) {
  std::printf("%s: accepted %d, touching %d, opposing %d, deepest %s %.2f mm; thumb..little", what,
              p.accepted, p.touching_fingers, p.gripping_fingers,
              std::string(hand::link_name(p.deepest_link)).c_str(), p.deepest_m * 1e3);
  for (int f = 0; f < hand::kFingerCount; ++f)
    std::printf(" %.2f mm (%.0f deg)", p.finger_distance_m[static_cast<std::size_t>(f)] * 1e3,
                p.finger_opposition_deg[static_cast<std::size_t>(f)]);
  std::printf("\n");
}

// What an accepted placement promises, checked without the search's own figures where possible.
void expect_grip(const GripHand& hand, const Shape& shape, const Placement& p) {
  const FitLimits limits;
  ASSERT_TRUE(p.accepted);
  EXPECT_LE(p.finger_distance_m[0], limits.contact_m);
  int others = 0, opposing = 0;
  for (int f = 1; f < hand::kFingerCount; ++f) {
    const auto k = static_cast<std::size_t>(f);
    if (p.finger_distance_m[k] > limits.contact_m) continue;
    ++others;
    if (p.finger_normal_G[0].dot(p.finger_normal_G[k]) <
        std::cos(deg_to_rad(limits.opposition_deg)))
      ++opposing;
  }
  EXPECT_GE(others, 2);
  EXPECT_GE(opposing, 1);
  EXPECT_LE(p.deepest_m, limits.max_depth_m);
  // the brute force agrees with the search's distances to a few um (the grids' spacing)
  const double sampled_m = sampled_deepest_m(hand, shape, p.X_GO);
  EXPECT_LE(sampled_m, limits.max_depth_m + 1e-5);
  EXPECT_NEAR(sampled_m, p.deepest_m, 1e-4);
  // the placement's figures are its pose's
  const Placement again = evaluate_placement(hand, shape, p.X_GO);
  EXPECT_EQ(again.deepest_m, p.deepest_m);
  EXPECT_EQ(again.finger_distance_m, p.finger_distance_m);
}

// The object holds still on a flat top: a bar lies (axis horizontal), a box has an axis vertical.
void expect_resting(const Shape& shape, const Eigen::Matrix3d& R_GO) {
  if (shape.kind == physics::ShapeKind::kCapsule) {
    EXPECT_NEAR(R_GO(2, 2), 0.0, 1e-12);
  } else if (shape.kind == physics::ShapeKind::kBox) {
    EXPECT_NEAR(R_GO.row(2).cwiseAbs().maxCoeff(), 1.0, 1e-12);
  } else if (shape.kind == physics::ShapeKind::kCylinder) {
    EXPECT_TRUE(std::abs(R_GO(2, 2)) < 1e-12 || std::abs(std::abs(R_GO(2, 2)) - 1.0) < 1e-12);
  }
}

TEST(GripFitPlacement, AFistHoldsABar) {
  const GripHand hand = grip_hand_at(test::grip_fit_hand(), test::fist_sample());
  const Shape bar = Shape::cylinder(0.015, 0.10);
  const FitResult r = fit_object_in_grip(hand, bar);
  print("fist, 3 cm bar", r.best);
  expect_grip(hand, bar, r.best);
  expect_resting(bar, r.best.X_GO.linear());
  EXPECT_EQ(r.starts, 7 * 13);  // 7 positions x (6 lying yaws + standing at 7 positions)
}

TEST(GripFitPlacement, AFistHoldsABallACapsuleAndABox) {
  const GripHand hand = grip_hand_at(test::grip_fit_hand(), test::fist_sample());
  for (const Shape& shape :
       {Shape::sphere(0.025), Shape::capsule(0.012, 0.08), Shape::box({0.03, 0.03, 0.08})}) {
    const FitResult r = fit_object_in_grip(hand, shape);
    print("fist", r.best);
    expect_grip(hand, shape, r.best);
    expect_resting(shape, r.best.X_GO.linear());
  }
}

TEST(GripFitPlacement, AFlatHandHoldsNothing) {
  // a bar or a ball under a flat hand touches fingers and thumb, but all from one side
  const GripHand hand = grip_hand_at(test::grip_fit_hand(), test::flat_sample());
  for (const Shape& shape : {Shape::cylinder(0.015, 0.10), Shape::sphere(0.025)}) {
    const FitResult r = fit_object_in_grip(hand, shape);
    print("flat hand", r.best);
    EXPECT_FALSE(r.best.accepted);
    EXPECT_EQ(r.best.gripping_fingers, 0);
  }
}

TEST(GripFitPlacement, ABallTooBigForTheFistDoesNotFit) {
  const GripHand hand = grip_hand_at(test::grip_fit_hand(), test::fist_sample());
  const FitResult r = fit_object_in_grip(hand, Shape::sphere(0.09));
  print("fist, 18 cm ball", r.best);
  EXPECT_FALSE(r.best.accepted);
}

TEST(GripFitPlacement, TheSameInputGivesTheSamePlacement) {
  const GripHand hand = grip_hand_at(test::grip_fit_hand(), test::fist_sample());
  const Shape capsule = Shape::capsule(0.012, 0.08);
  const FitResult a = fit_object_in_grip(hand, capsule);
  const FitResult b = fit_object_in_grip(hand, capsule);
  EXPECT_TRUE(a.best.X_GO.matrix() == b.best.X_GO.matrix());
  EXPECT_EQ(a.best.cost, b.best.cost);
  EXPECT_EQ(a.evaluations, b.evaluations);
}

TEST(GripFitPlacement, ALeftHandHoldsABallToo) {
  const hand::HandModel left = hand::mirrored(test::grip_fit_hand());
  const GripHand hand = grip_hand_at(left, test::fist_sample());
  const Shape ball = Shape::sphere(0.025);
  const FitResult r = fit_object_in_grip(hand, ball);
  print("left fist, 5 cm ball", r.best);
  expect_grip(hand, ball, r.best);
  // on the palm side (-z of H, for a left hand as for a right)
  const Eigen::Vector3d p_H = hand.X_GH.inverse() * r.best.X_GO.translation();
  EXPECT_LT(p_H.z(), 0.0);
}

}  // namespace
}  // namespace vcockpit::fit
