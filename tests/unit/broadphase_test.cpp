// Sweep and prune against brute force: the same pairs, sorted, through random motion (the
// insertion sort's temporal coherence must never lose a pair), with the can-act filter; and each
// shape's box holds the shape tightly.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>

#include "common/pose.hpp"
#include "physics_node/physics/broadphase.hpp"

namespace vcockpit::physics {
namespace {

using Kind = BroadphaseBody;

bool can_act(Kind a, Kind b, bool hand_enabled) {
  if (a != Kind::kDynamic && b != Kind::kDynamic) return false;
  const bool hand = a == Kind::kHand || b == Kind::kHand;
  return !hand || hand_enabled;
}

std::vector<BodyPair> brute_force(const std::vector<Kind>& kinds, const std::vector<Aabb>& boxes,
                                  bool hand_enabled) {
  std::vector<BodyPair> out;
  for (int a = 0; a < static_cast<int>(boxes.size()); ++a)
    for (int b = a + 1; b < static_cast<int>(boxes.size()); ++b)
      if (can_act(kinds[a], kinds[b], hand_enabled) && boxes[a].overlaps(boxes[b]))
        out.push_back({a, b});
  return out;
}

TEST(SweepAndPrune, SamePairsAsBruteForceThroughRandomMotion) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> pos(-1.0, 1.0), size(0.02, 0.3), step(-0.05, 0.05);
  std::vector<Kind> kinds;
  for (int i = 0; i < 120; ++i)
    kinds.push_back(i < 10 ? Kind::kStatic : i < 100 ? Kind::kDynamic : Kind::kHand);
  std::vector<Aabb> boxes(kinds.size());
  std::vector<Eigen::Vector3d> centre(kinds.size()), half(kinds.size());
  for (std::size_t i = 0; i < kinds.size(); ++i) {
    centre[i] = {pos(rng), pos(rng), 0.3 * pos(rng)};
    half[i] = {size(rng), size(rng), size(rng)};
  }
  SweepAndPrune sap(kinds);
  std::vector<BodyPair> pairs;
  std::size_t total = 0;
  for (int round = 0; round < 200; ++round) {
    const bool hand_enabled = round % 3 != 0;
    for (std::size_t i = 0; i < kinds.size(); ++i) {
      if (kinds[i] != Kind::kStatic) centre[i] += Eigen::Vector3d(step(rng), step(rng), step(rng));
      boxes[i] = {centre[i] - half[i], centre[i] + half[i]};
      sap.set_box(static_cast<int>(i), boxes[i]);
    }
    for (std::size_t i = 0; i < kinds.size(); ++i)
      if (kinds[i] == Kind::kHand) sap.set_enabled(static_cast<int>(i), hand_enabled);
    sap.find_pairs(pairs);
    const auto expected = brute_force(kinds, boxes, hand_enabled);
    ASSERT_EQ(pairs, expected) << "round " << round;
    total += pairs.size();
  }
  EXPECT_GT(total, 1000u);  // the scene is crowded enough for the comparison to mean something
}

// Sleeping bodies (sleep.hpp) pair only with awake non-static ones; the sweep takes them apart
// from the awake ones, so it must find exactly the pairs brute force finds, through sleepers
// falling asleep and waking, and through boxes that start at the same coordinate (the ties of
// the two lists' sweeps).
TEST(SweepAndPrune, WithSleepersSamePairsAsBruteForce) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> pos(-1.0, 1.0), size(0.02, 0.3), step(-0.05, 0.05),
      unit(0.0, 1.0);
  std::vector<Kind> kinds;
  for (int i = 0; i < 150; ++i)
    kinds.push_back(i < 10 ? Kind::kStatic : i < 130 ? Kind::kDynamic : Kind::kHand);
  std::vector<Aabb> boxes(kinds.size());
  std::vector<Eigen::Vector3d> centre(kinds.size()), half(kinds.size());
  std::vector<uint8_t> asleep(kinds.size(), 0);
  for (std::size_t i = 0; i < kinds.size(); ++i) {
    // a coarse grid of centres and sizes: many boxes start at exactly the same coordinate
    centre[i] = {0.1 * std::round(10 * pos(rng)), 0.1 * std::round(10 * pos(rng)), 0.0};
    half[i] = Eigen::Vector3d::Constant(0.05 * std::round(1 + 4 * unit(rng)));
  }
  SweepAndPrune sap(kinds);
  for (std::size_t i = 0; i < kinds.size(); ++i)
    if (kinds[i] == Kind::kHand) sap.set_enabled(static_cast<int>(i), true);
  std::vector<BodyPair> pairs;
  std::size_t total = 0, with_sleeper = 0;
  for (int round = 0; round < 200; ++round) {
    for (std::size_t i = 0; i < kinds.size(); ++i) {
      if (kinds[i] == Kind::kDynamic && unit(rng) < 0.1) asleep[i] = asleep[i] ? 0 : 1;
      // a sleeper keeps still; the rest move on the grid
      if (kinds[i] != Kind::kStatic && asleep[i] == 0 && unit(rng) < 0.3)
        centre[i] += Eigen::Vector3d(0.1 * std::round(step(rng) * 20), 0.0, 0.0);
      boxes[i] = {centre[i] - half[i], centre[i] + half[i]};
      sap.set_box(static_cast<int>(i), boxes[i]);
      sap.set_asleep(static_cast<int>(i), asleep[i] != 0);
    }
    sap.find_pairs(pairs);
    std::vector<BodyPair> expected;
    for (int a = 0; a < static_cast<int>(boxes.size()); ++a)
      for (int b = a + 1; b < static_cast<int>(boxes.size()); ++b) {
        const bool sa = asleep[a] != 0, sb = asleep[b] != 0;
        bool acts = can_act(kinds[a], kinds[b], true);
        if (sa || sb) acts = acts && !(sa && sb) && kinds[a] != Kind::kStatic && kinds[b] != Kind::kStatic;
        if (acts && boxes[a].overlaps(boxes[b])) {
          expected.push_back({a, b});
          with_sleeper += sa || sb ? 1 : 0;
        }
      }
    ASSERT_EQ(pairs, expected) << "round " << round;
    total += pairs.size();
  }
  EXPECT_GT(total, 1000u);
  EXPECT_GT(with_sleeper, 200u);  // awake-sleeping pairs were there to be found
}

TEST(SweepAndPrune, TouchingBoxesArePairsAndStaticOrHandPairsNever) {
  SweepAndPrune sap({Kind::kStatic, Kind::kStatic, Kind::kDynamic, Kind::kHand, Kind::kHand});
  const Aabb unit{Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones()};
  for (int i = 0; i < 5; ++i) sap.set_box(i, unit);  // all five overlap
  sap.set_box(2, {Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(2, 1, 1)});  // touches on x = 1
  std::vector<BodyPair> pairs;
  sap.find_pairs(pairs);
  EXPECT_EQ(pairs, (std::vector<BodyPair>{{0, 2}, {1, 2}}));  // the hand is disabled
  sap.set_enabled(3, true);
  sap.set_enabled(4, true);
  sap.find_pairs(pairs);
  EXPECT_EQ(pairs, (std::vector<BodyPair>{{0, 2}, {1, 2}, {2, 3}, {2, 4}}));
}

// Every point of the shape's surface lies in its box, and the box touches the shape on each face.
TEST(ShapeAabb, HoldsEachShapeTightly) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> angle(-180.0, 180.0), unit(0.0, 1.0);
  const std::vector<Shape> shapes = {Shape::box({0.3, 0.1, 0.05}), Shape::sphere(0.07),
                                     Shape::capsule(0.02, 0.15), Shape::cylinder(0.035, 0.1)};
  for (const Shape& shape : shapes) {
    for (int trial = 0; trial < 20; ++trial) {
      const Eigen::Isometry3d X = pose_from_position_rpy_deg(
          {unit(rng), unit(rng), unit(rng)}, {angle(rng), angle(rng), angle(rng)});
      const Aabb box = shape_aabb(shape, X);
      Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e9), hi = -lo;
      // dense samples of the surface in the shape's frame
      for (int i = 0; i <= 40; ++i) {
        for (int j = 0; j < 80; ++j) {
          const double u = static_cast<double>(i) / 40, phi = 2 * M_PI * j / 80;
          std::vector<Eigen::Vector3d> points;
          switch (shape.kind) {
            case ShapeKind::kBox: {
              const Eigen::Vector3d h = 0.5 * shape.box_size_m;
              for (int c = 0; c < 8; ++c)
                points.push_back({c & 1 ? h.x() : -h.x(), c & 2 ? h.y() : -h.y(), c & 4 ? h.z() : -h.z()});
              break;
            }
            case ShapeKind::kSphere: {
              const double th = M_PI * u;
              points.push_back(shape.radius_m * Eigen::Vector3d(std::sin(th) * std::cos(phi),
                                                                std::sin(th) * std::sin(phi), std::cos(th)));
              break;
            }
            case ShapeKind::kCapsule: {
              const double th = M_PI * u;
              const Eigen::Vector3d s(std::sin(th) * std::cos(phi), std::sin(th) * std::sin(phi), std::cos(th));
              for (double end : {-0.5, 0.5})
                points.push_back(Eigen::Vector3d(0, 0, end * shape.length_m) + shape.radius_m * s);
              break;
            }
            case ShapeKind::kCylinder:
              for (double end : {-0.5, 0.5})
                points.push_back({shape.radius_m * std::cos(phi), shape.radius_m * std::sin(phi),
                                  end * shape.length_m});
              break;
            case ShapeKind::kMesh:  // (meshes: model_mesh_test)
              break;
          }
          for (const auto& p : points) {
            const Eigen::Vector3d q = X * p;
            lo = lo.cwiseMin(q);
            hi = hi.cwiseMax(q);
          }
        }
      }
      EXPECT_TRUE((box.lo.array() <= lo.array() + 1e-12).all()) << "box misses part of the shape";
      EXPECT_TRUE((box.hi.array() >= hi.array() - 1e-12).all()) << "box misses part of the shape";
      // tight: within the sampling's resolution of the shape's extent
      EXPECT_LT((lo - box.lo).cwiseAbs().maxCoeff(), 0.003);
      EXPECT_LT((box.hi - hi).cwiseAbs().maxCoeff(), 0.003);
    }
  }
}

}  // namespace
}  // namespace vcockpit::physics
