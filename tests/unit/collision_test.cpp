// Collision (paper §4.2): FCL's contacts against closed forms (resting depths, normals, manifold
// sizes), the pair filter (static-static, hand-static, link-link, disabled hand), the normal
// convention for every shape pair in both body orders, determinism and allocation-free steps.
// The manifolds collision.cpp builds for flat contacts of round shapes (a cylinder standing or
// lying on a box, a capsule lying on one, a cup on a cup) against closed forms and against FCL's
// own single point.
//
// Every scene is built here; none reads config/cockpit.yaml. The floor is a static box whose
// top face is z = 0, so a body resting d into it has its lowest point at z = -d.

#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/collision_object.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <new>
#include <stdexcept>
#include <string>
#include <vector>

#include "hand/config/hand_yaml.hpp"
#include "physics_node/physics/collision.hpp"
#include "hand/hand_model.hpp"
#include "tests/support/allocation_counter.hpp"
#include "tests/support/collision_scenes.hpp"
#include "physics_node/physics/scene.hpp"

namespace vcockpit::physics {
namespace {

// to prove the broadphase step allocates nothing
using test::g_allocations;
using test::g_count_allocations;

// FCL's closed-form pairs (box-box, sphere-*) are exact to rounding; the MPR pairs (capsule or
// cylinder against box, cylinder, capsule) converge to collision.cpp's 1e-9 m tolerance.
constexpr double kDepthTol_m = 1e-8;
constexpr double kPointTol_m = 1e-8;
constexpr double kNormalTol = 1e-6;  // |n - n_expected|, unitless
constexpr double kDepth_m = 1e-3;    // how far bodies are pushed into each other

std::string source_dir() {
  if (const char* dir = std::getenv("VCOCKPIT_SOURCE_DIR")) return dir;
  const std::string file = __FILE__;  // <repo>/tests/unit/collision_test.cpp
  return file.substr(0, file.rfind("/tests/unit/"));
}

const HandModel& shipped_hand() {
  static const HandModel model = load_hand_model(source_dir() + "/config/hand.yaml");
  return model;
}

// Exact quarter turns, so closed-form expectations stay exact.
Eigen::Matrix3d ry90() {  // z -> x: an axis-along-z shape lying along x
  Eigen::Matrix3d R;
  R << 0, 0, 1, 0, 1, 0, -1, 0, 0;
  return R;
}
Eigen::Matrix3d rx90() {  // z -> -y: an axis-along-z shape lying along y
  Eigen::Matrix3d R;
  R << 1, 0, 0, 0, 0, -1, 0, 1, 0;
  return R;
}

using test::expect_vec_near;
using test::floor_box;
using test::initial_poses;
using test::object;
using test::pose;
using test::step;

bool same_bits(const ContactPoint& x, const ContactPoint& y) {
  return x.body_a == y.body_a && x.body_b == y.body_b &&
         std::memcmp(x.p_G.data(), y.p_G.data(), 3 * sizeof(double)) == 0 &&
         std::memcmp(x.n_G.data(), y.n_G.data(), 3 * sizeof(double)) == 0 &&
         std::memcmp(&x.depth_m, &y.depth_m, sizeof(double)) == 0;
}

// ---- closed-form resting contacts -----------------------------------------------------------

TEST(Collision, SphereOneMillimetreIntoStaticBox) {
  constexpr double r_m = 0.05;
  Scene scene;
  scene.objects = {floor_box(),
                   object("ball", true, Shape::sphere(r_m), pose(0.1, 0.05, r_m - kDepth_m))};
  CollisionWorld world(scene);
  const auto contacts = step(world, initial_poses(scene));

  EXPECT_EQ(world.candidate_pair_count(), 1u);
  ASSERT_EQ(contacts.size(), 1u);
  const ContactPoint& c = contacts[0];
  EXPECT_EQ(c.body_a, 0);  // the box
  EXPECT_EQ(c.body_b, 1);
  EXPECT_NEAR(c.depth_m, kDepth_m, 1e-6);
  expect_vec_near(c.n_G, Eigen::Vector3d::UnitZ(), kNormalTol, "normal, box -> sphere");
  // FCL puts the point midway between the sphere's bottom (z = -d) and the box top (z = 0)
  expect_vec_near(c.p_G, Eigen::Vector3d(0.1, 0.05, -0.5 * kDepth_m), kPointTol_m, "point");
  EXPECT_EQ(world.skipped_contacts(), 0u);
}

TEST(Collision, BoxOneMillimetreIntoBoxFloorGivesFourCorners) {
  constexpr double half_m = 0.05;  // 0.1 m cube
  const Eigen::Vector3d centre(0.1, -0.2, half_m - kDepth_m);
  Scene scene;
  scene.objects = {floor_box(), object("crate", true, Shape::box(Eigen::Vector3d::Constant(0.1)),
                                       pose(centre.x(), centre.y(), centre.z()))};
  CollisionWorld world(scene);
  const auto contacts = step(world, initial_poses(scene));

  ASSERT_EQ(contacts.size(), 4u);
  int corners_seen = 0;
  for (const ContactPoint& c : contacts) {
    EXPECT_EQ(c.body_a, 0);
    EXPECT_EQ(c.body_b, 1);
    EXPECT_NEAR(c.depth_m, kDepth_m, 1e-6);
    expect_vec_near(c.n_G, Eigen::Vector3d::UnitZ(), kNormalTol, "normal");
    // one point under each corner of the footprint, midway through the overlap
    const Eigen::Vector3d offset = c.p_G - Eigen::Vector3d(centre.x(), centre.y(), 0.0);
    EXPECT_NEAR(std::abs(offset.x()), half_m, kPointTol_m);
    EXPECT_NEAR(std::abs(offset.y()), half_m, kPointTol_m);
    EXPECT_NEAR(offset.z(), -0.5 * kDepth_m, kPointTol_m);
    corners_seen |= 1 << ((offset.x() > 0 ? 1 : 0) + (offset.y() > 0 ? 2 : 0));
  }
  EXPECT_EQ(corners_seen, 0b1111);
}

TEST(Collision, MaxPointsPerPairCapsTheManifold) {
  Scene scene;
  scene.contact.max_points_per_pair = 2;
  scene.objects = {floor_box(), object("crate", true, Shape::box(Eigen::Vector3d::Constant(0.1)),
                                       pose(0, 0, 0.05 - kDepth_m))};
  CollisionWorld world(scene);
  const auto contacts = step(world, initial_poses(scene));
  ASSERT_EQ(contacts.size(), 2u);
  for (const ContactPoint& c : contacts)
    EXPECT_NEAR(c.depth_m, kDepth_m, 1e-6);
}

TEST(Collision, CylinderLyingOnBox) {
  constexpr double r_m = 0.03, length_m = 0.2;
  const Eigen::Vector3d centre(-0.1, 0.15, r_m - kDepth_m);
  Scene scene;
  scene.objects = {floor_box(), object("can", true, Shape::cylinder(r_m, length_m),
                                       pose(centre.x(), centre.y(), centre.z(), ry90()))};
  CollisionWorld world(scene);
  const auto contacts = step(world, initial_poses(scene));

  // FCL 0.7 gives one MPR point for the line contact; collision.cpp reports its two ends
  ASSERT_EQ(contacts.size(), 2u);
  double x_sum = 0.0;
  for (const ContactPoint& c : contacts) {
    EXPECT_NEAR(c.depth_m, kDepth_m, 1e-6);
    expect_vec_near(c.n_G, Eigen::Vector3d::UnitZ(), kNormalTol, "normal");
    // an end of the contact line, midway through the overlap slab
    EXPECT_NEAR(std::abs(c.p_G.x() - centre.x()), 0.5 * length_m, kPointTol_m);
    EXPECT_NEAR(c.p_G.y(), centre.y(), 1e-6);
    EXPECT_NEAR(c.p_G.z(), -0.5 * kDepth_m, kPointTol_m);
    x_sum += c.p_G.x() - centre.x();
  }
  EXPECT_NEAR(x_sum, 0.0, 2 * kPointTol_m);  // one at each end
}

// ---- manifolds for flat contacts of round shapes ----------------------------------------------
// FCL 0.7's MPR gives one point for these; collision.cpp clips the round shape's facing feature
// (cap rim, side line, capsule segment) to the box face and reduces to at most 4 points.

Eigen::Matrix3d rot(double angle_deg, const Eigen::Vector3d& axis) {
  return Eigen::AngleAxisd(angle_deg * M_PI / 180.0, axis.normalized()).toRotationMatrix();
}

// FCL's own single contact for the floor_box() and a cylinder or capsule, at collision.cpp's
// MPR tolerance: what the manifold must agree with.
fcl::Contactd fcl_contact(const Shape& round, const Eigen::Isometry3d& X_G_round) {
  const ObjectSpec floor = floor_box();
  auto box = std::make_shared<fcl::Boxd>(floor.shape.box_size_m);
  std::shared_ptr<fcl::CollisionGeometryd> other;
  if (round.kind == ShapeKind::kCylinder)
    other = std::make_shared<fcl::Cylinderd>(round.radius_m, round.length_m);
  else
    other = std::make_shared<fcl::Capsuled>(round.radius_m, round.length_m);
  fcl::CollisionObjectd o1(box, floor.X_GO), o2(other, X_G_round);
  fcl::CollisionRequestd request(1, true);
  request.gjk_tolerance = 1e-9;
  fcl::CollisionResultd result;
  fcl::collide(&o1, &o2, request, result);
  EXPECT_EQ(result.numContacts(), 1u);
  return result.numContacts() > 0 ? result.getContact(0) : fcl::Contactd{};
}

std::vector<ContactPoint> round_on_floor(const Shape& round, const Eigen::Isometry3d& X_GO,
                                         int max_points = 4) {
  Scene scene;
  scene.contact.max_points_per_pair = max_points;
  scene.objects = {floor_box(), object("round", true, round, X_GO)};
  CollisionWorld world(scene);
  return step(world, initial_poses(scene));
}

double max_depth(const std::vector<ContactPoint>& contacts) {
  double d = 0.0;
  for (const ContactPoint& c : contacts) d = std::max(d, c.depth_m);
  return d;
}

void expect_spread(const std::vector<ContactPoint>& contacts, double min_distance_m) {
  for (std::size_t i = 0; i < contacts.size(); ++i)
    for (std::size_t j = i + 1; j < contacts.size(); ++j)
      EXPECT_GT((contacts[i].p_G - contacts[j].p_G).norm(), min_distance_m)
          << "points " << i << " and " << j;
}

// libccd's MPR, for a short cylinder exactly touching a large floor far from its centre, returns
// a direction along the floor with the overlap across the whole floor (1.7 m here): the box's
// face normals are checked too, so touching gives no contact and a slight overlap the top face.
Eigen::Matrix3d rotation_rpy_deg(const Eigen::Vector3d& rpy_deg) {
  const Eigen::Vector3d r = rpy_deg * M_PI / 180.0;
  return (Eigen::AngleAxisd(r.z(), Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(r.y(), Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(r.x(), Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

TEST(Collision, RoundBodiesTouchingALargeFloorGetItsTopFaceNeverASideFace) {
  const Shape floor = Shape::box({4.1, 2.0, 0.1});
  struct Case {
    Shape shape;
    double rest_z_m;
    Eigen::Vector3d rpy_deg;
  };
  const Case cases[] = {{Shape::cylinder(0.0221, 0.0353), 0.5 * 0.0353, {0, 0, 0}},
                        {Shape::cylinder(0.03, 0.08), 0.04, {0, 0, 25}},
                        {Shape::capsule(0.015, 0.03), 0.015, {0, 90, -20}}};
  for (const Case& c : cases) {
    for (const auto& xy : {Eigen::Vector2d(-0.33, 0.72), Eigen::Vector2d(1.8, -0.9),
                           Eigen::Vector2d(-1.9, 0.1)}) {
      for (const double overlap_m : {0.0, 0.0005}) {
        Scene scene;
        scene.objects = {object("floor", false, floor, pose(-0.05, 0, -0.05)),
                         object("round", true, c.shape,
                                pose(xy.x(), xy.y(), c.rest_z_m - overlap_m,
                                     rotation_rpy_deg(c.rpy_deg)))};
        CollisionWorld world(scene);
        const auto contacts = step(world, initial_poses(scene));
        if (overlap_m == 0.0) {
          EXPECT_TRUE(contacts.empty()) << "touching gave " << contacts.size() << " contacts, depth "
                                        << (contacts.empty() ? 0.0 : contacts[0].depth_m);
          continue;
        }
        ASSERT_FALSE(contacts.empty());
        for (const ContactPoint& p : contacts) {
          expect_vec_near(p.n_G, Eigen::Vector3d::UnitZ(), 1e-9, "normal");
          EXPECT_NEAR(p.depth_m, overlap_m, 1e-7);
        }
      }
    }
  }
}

TEST(CollisionManifold, UprightCylinderOnBoxGivesFourPointsOnTheRim) {
  constexpr double r_m = 0.035, length_m = 0.1;
  for (double yaw_deg : {0.0, 30.0, 67.0}) {
    SCOPED_TRACE("yaw " + std::to_string(yaw_deg));
    const Eigen::Vector3d axis(0.1, -0.05, 0.0);
    const auto X = pose(axis.x(), axis.y(), 0.5 * length_m - kDepth_m,
                        rot(yaw_deg, Eigen::Vector3d::UnitZ()));
    const auto contacts = round_on_floor(Shape::cylinder(r_m, length_m), X);
    ASSERT_EQ(contacts.size(), 4u);
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (const ContactPoint& c : contacts) {
      EXPECT_EQ(c.body_a, 0);
      EXPECT_EQ(c.body_b, 1);
      EXPECT_NEAR(c.depth_m, kDepth_m, 1e-6);
      expect_vec_near(c.n_G, Eigen::Vector3d::UnitZ(), kNormalTol, "normal");
      EXPECT_NEAR(c.p_G.z(), -0.5 * kDepth_m, kPointTol_m);  // midway through the overlap
      EXPECT_NEAR((c.p_G - axis).head<2>().norm(), r_m, kPointTol_m);  // on the rim
      centroid += c.p_G / 4.0;
    }
    expect_spread(contacts, r_m);
    // a square on the rim: its centre is on the axis, so the support has no lever arm
    expect_vec_near(Eigen::Vector3d(centroid.x(), centroid.y(), 0.0), axis, kPointTol_m,
                    "centre of the points");
  }
}

TEST(CollisionManifold, LyingCapsuleOnBoxGivesBothSegmentEnds) {
  constexpr double r_m = 0.01, length_m = 0.08;
  const Eigen::Vector3d centre(-0.2, 0.1, r_m - kDepth_m);
  const auto contacts = round_on_floor(Shape::capsule(r_m, length_m),
                                       pose(centre.x(), centre.y(), centre.z(), rx90()));
  ASSERT_EQ(contacts.size(), 2u);
  for (const ContactPoint& c : contacts) {
    EXPECT_NEAR(c.depth_m, kDepth_m, 1e-6);
    expect_vec_near(c.n_G, Eigen::Vector3d::UnitZ(), kNormalTol, "normal");
    EXPECT_NEAR(c.p_G.x(), centre.x(), kPointTol_m);
    EXPECT_NEAR(std::abs(c.p_G.y() - centre.y()), 0.5 * length_m, kPointTol_m);
    EXPECT_NEAR(c.p_G.z(), -0.5 * kDepth_m, kPointTol_m);
  }
  EXPECT_NEAR(contacts[0].p_G.y() + contacts[1].p_G.y(), 2 * centre.y(), 2 * kPointTol_m);
}

// Tilted 5 deg about y: the cap's lowest rim point is 1 mm in, the rest of the rim is out.
TEST(CollisionManifold, TiltedCylinderWithOneRimPointInGivesThatPoint) {
  constexpr double r_m = 0.05, length_m = 0.1, tilt_deg = 5.0;
  const double t = tilt_deg * M_PI / 180.0;
  const double z_m = 0.5 * length_m * std::cos(t) + r_m * std::sin(t) - kDepth_m;
  const Eigen::Vector3d lowest(0.5 * length_m * -std::sin(t) + r_m * std::cos(t), 0.0, -kDepth_m);
  const Shape shape = Shape::cylinder(r_m, length_m);

  // a body-fixed rim point is the lowest one: exactly one point
  {
    const auto X = pose(0, 0, z_m, rot(tilt_deg, Eigen::Vector3d::UnitY()));
    const auto contacts = round_on_floor(shape, X);
    ASSERT_EQ(contacts.size(), 1u);
    EXPECT_NEAR(contacts[0].depth_m, kDepth_m, 1e-6);
    EXPECT_NEAR(contacts[0].depth_m, fcl_contact(shape, X).penetration_depth, 1e-6);
    expect_vec_near(contacts[0].n_G, Eigen::Vector3d::UnitZ(), kNormalTol, "normal");
    expect_vec_near(contacts[0].p_G, lowest + Eigen::Vector3d(0, 0, 0.5 * kDepth_m), kPointTol_m,
                    "the lowest rim point, midway");
  }
  // the lowest point between two body-fixed rim points (turned 22.5 deg about its axis): the
  // exact lowest point, deepest, plus the two rim points beside it, 22.5 deg up the rim
  {
    const auto X = pose(0, 0, z_m, rot(tilt_deg, Eigen::Vector3d::UnitY()) *
                                       rot(22.5, Eigen::Vector3d::UnitZ()));
    const auto contacts = round_on_floor(shape, X);
    ASSERT_EQ(contacts.size(), 3u);
    EXPECT_NEAR(max_depth(contacts), kDepth_m, 1e-6);
    EXPECT_NEAR(max_depth(contacts), fcl_contact(shape, X).penetration_depth, 1e-6);
    EXPECT_NEAR(contacts[0].depth_m, kDepth_m, 1e-6);  // the deepest comes first
    expect_vec_near(contacts[0].p_G, lowest + Eigen::Vector3d(0, 0, 0.5 * kDepth_m), kPointTol_m,
                    "the lowest rim point, midway");
    const double up_m = r_m * std::sin(t) * (1.0 - std::cos(22.5 * M_PI / 180.0));
    for (std::size_t i = 1; i < 3; ++i) EXPECT_NEAR(contacts[i].depth_m, kDepth_m - up_m, 1e-9);
  }
}

TEST(CollisionManifold, CylinderCapOverhangingTheBoxEdgeKeepsOnlyPointsOverTheFace) {
  constexpr double r_m = 0.035, length_m = 0.1, edge_x_m = 0.5;  // the floor's face ends at x 0.5
  for (double overhang_m : {0.01, 0.025, 0.045}) {
    SCOPED_TRACE("axis " + std::to_string(overhang_m) + " m from the edge");
    const double x_m = edge_x_m + overhang_m - r_m;  // the rim overhangs by overhang_m
    const auto contacts =
        round_on_floor(Shape::cylinder(r_m, length_m), pose(x_m, 0.0, 0.5 * length_m - kDepth_m));
    ASSERT_GE(contacts.size(), 3u);
    ASSERT_LE(contacts.size(), 4u);
    double x_max = -1.0;
    for (const ContactPoint& c : contacts) {
      EXPECT_NEAR(c.depth_m, kDepth_m, 1e-6);
      EXPECT_LE(c.p_G.x(), edge_x_m + kPointTol_m);  // over the face
      EXPECT_LE((c.p_G - Eigen::Vector3d(x_m, 0, 0)).head<2>().norm(), r_m + kPointTol_m);
      x_max = std::max(x_max, c.p_G.x());
    }
    EXPECT_NEAR(x_max, edge_x_m, kPointTol_m);  // the support reaches the edge
    expect_spread(contacts, 1e-3);
  }
}

TEST(CollisionManifold, MaxPointsPerPairKeepsTheDeepestAndSpreadPoints) {
  constexpr double r_m = 0.035, length_m = 0.1;
  const Shape shape = Shape::cylinder(r_m, length_m);
  const auto X = pose(0, 0, 0.5 * length_m - kDepth_m);
  for (int max_points : {1, 2, 3, 4, 8}) {
    SCOPED_TRACE("max_points_per_pair " + std::to_string(max_points));
    const auto contacts = round_on_floor(shape, X, max_points);
    ASSERT_EQ(contacts.size(), static_cast<std::size_t>(std::min(max_points, 4)));
    for (const ContactPoint& c : contacts) EXPECT_NEAR(c.depth_m, kDepth_m, 1e-6);
    if (max_points >= 2) {
      EXPECT_NEAR((contacts[0].p_G - contacts[1].p_G).norm(), 2 * r_m, 1e-9);
    }
  }
  // tilted: a single point is the deepest, FCL's depth
  const double t = 3.0 * M_PI / 180.0;
  const auto X_tilted =
      pose(0, 0, 0.5 * length_m * std::cos(t) + r_m * std::sin(t) - 2 * kDepth_m,
           rot(3.0, Eigen::Vector3d(1, 2, 0)));
  const auto one = round_on_floor(shape, X_tilted, 1);
  ASSERT_EQ(one.size(), 1u);
  EXPECT_NEAR(one[0].depth_m, fcl_contact(shape, X_tilted).penetration_depth, 1e-6);
  EXPECT_NEAR(one[0].depth_m, max_depth(round_on_floor(shape, X_tilted)), 1e-12);
}

// Friction anchors follow the points: a level cup must report the same rim points whichever
// way it is tilted by rounding-sized amounts.
TEST(CollisionManifold, BarelyTiltedCupKeepsTheSameRimPoints) {
  constexpr double r_m = 0.035, length_m = 0.1;
  const Shape shape = Shape::cylinder(r_m, length_m);
  const auto level = round_on_floor(shape, pose(0, 0, 0.5 * length_m - kDepth_m));
  ASSERT_EQ(level.size(), 4u);
  for (int k = 0; k < 16; ++k) {
    const double phi = 2.0 * M_PI * k / 16;
    for (double tilt_rad : {1e-12, 1e-10, 1e-9}) {
      const Eigen::Vector3d tilt_axis(std::cos(phi), std::sin(phi), 0.0);
      const auto X = pose(0, 0, 0.5 * length_m - kDepth_m, rot(tilt_rad * 180.0 / M_PI, tilt_axis));
      const auto contacts = round_on_floor(shape, X);
      ASSERT_EQ(contacts.size(), 4u) << "direction " << k << ", tilt " << tilt_rad;
      for (std::size_t i = 0; i < 4; ++i)
        expect_vec_near(contacts[i].p_G, level[i].p_G, 1e-9, "point " + std::to_string(i));
    }
  }
}

TEST(CollisionManifold, SmallBoxOnACylinderCapRestsOnItsFourCorners) {
  // a 40 mm cube on a drum of radius 50 mm: the cap's rim is outside the box's face
  Scene scene;
  scene.objects = {object("drum", false, Shape::cylinder(0.05, 0.1), pose(0, 0, -0.05)),
                   object("cube", true, Shape::box(Eigen::Vector3d::Constant(0.04)),
                          pose(0.003, -0.002, 0.02 - kDepth_m))};
  CollisionWorld world(scene);
  const auto contacts = step(world, initial_poses(scene));
  ASSERT_EQ(contacts.size(), 4u);
  for (const ContactPoint& c : contacts) {
    EXPECT_NEAR(c.depth_m, kDepth_m, kDepthTol_m);
    expect_vec_near(c.n_G, Eigen::Vector3d::UnitZ(), kNormalTol, "normal");
    EXPECT_NEAR(std::abs(c.p_G.x() - 0.003), 0.02, kPointTol_m);
    EXPECT_NEAR(std::abs(c.p_G.y() + 0.002), 0.02, kPointTol_m);
    EXPECT_NEAR(c.p_G.z(), -0.5 * kDepth_m, kPointTol_m);
  }
}

// Over many poses with the deepest point over the face: the manifold's deepest point is FCL's
// depth, no point is deeper, the normal is FCL's.
TEST(CollisionManifold, DeepestPointAgreesWithFclOverManyPoses) {
  int checked = 0;
  for (const Shape& shape : {Shape::cylinder(0.035, 0.1), Shape::cylinder(0.02, 0.16),
                             Shape::capsule(0.01, 0.06)}) {
    for (double tilt_deg : {0.0, 0.5, 2.0, 5.0, 20.0, 44.0, 46.0, 70.0, 88.0, 89.9, 90.0}) {
      for (double dir_deg : {0.0, 10.0, 22.5, 100.0, 200.0}) {
        for (double depth_m : {1e-4, 1e-3, 4e-3}) {
          const double dir_rad = dir_deg * M_PI / 180.0;
          const Eigen::Vector3d tilt_axis(std::cos(dir_rad), std::sin(dir_rad), 0.0);
          const Eigen::Matrix3d R = rot(tilt_deg, tilt_axis) * rot(13.0, Eigen::Vector3d::UnitZ());
          // the shape's lowest point along -z, then lowered to depth_m into the floor
          Eigen::Isometry3d X = pose(0.05, -0.03, 0.0, R);
          const Eigen::Vector3d a = R.col(2);
          const double h = shape.kind == ShapeKind::kCylinder
                               ? 0.5 * shape.length_m * std::abs(a.z()) +
                                     shape.radius_m * std::sqrt(std::max(0.0, 1 - a.z() * a.z()))
                               : 0.5 * shape.length_m * std::abs(a.z()) + shape.radius_m;
          X.translation().z() = h - depth_m;
          SCOPED_TRACE("shape " + std::to_string(static_cast<int>(shape.kind)) + " tilt " +
                       std::to_string(tilt_deg) + " dir " + std::to_string(dir_deg) + " depth " +
                       std::to_string(depth_m));
          const fcl::Contactd f = fcl_contact(shape, X);
          const auto contacts = round_on_floor(shape, X);
          ASSERT_GE(contacts.size(), 1u);
          ASSERT_LE(contacts.size(), 4u);
          EXPECT_NEAR(max_depth(contacts), f.penetration_depth, 1e-6);
          EXPECT_NEAR(max_depth(contacts), depth_m, 1e-6);
          for (const ContactPoint& c : contacts) {
            EXPECT_GT(c.depth_m, 0.0);
            // the face test gives the floor's exact normal; MPR's is within its tolerance of it
            expect_vec_near(c.n_G, Eigen::Vector3d::UnitZ(), 1e-9, "the floor's normal");
            expect_vec_near(c.n_G, f.normal.normalized(), 1e-8, "FCL's normal");
            EXPECT_NEAR(c.p_G.z(), -0.5 * c.depth_m, 1e-6);  // midway through the overlap
          }
          expect_spread(contacts, 1e-6);
          ++checked;
        }
      }
    }
  }
  EXPECT_EQ(checked, 3 * 11 * 5 * 3);
}

TEST(CollisionManifold, SamePosesGiveBitwiseIdenticalManifolds) {
  Scene scene;
  scene.objects = {
      floor_box(),
      object("cup", true, Shape::cylinder(0.035, 0.1), pose(0.1, 0.1, 0.05 - kDepth_m)),
      object("tilted", true, Shape::cylinder(0.05, 0.1),
             pose(-0.2, 0.1, 0.05 - kDepth_m, rot(3.0, Eigen::Vector3d(1, 1, 0)))),
      object("can", true, Shape::cylinder(0.03, 0.15), pose(0.3, -0.3, 0.03 - kDepth_m, ry90())),
      object("rod", true, Shape::capsule(0.01, 0.08), pose(-0.3, -0.3, 0.01 - kDepth_m, rx90())),
      object("edge", true, Shape::cylinder(0.035, 0.1), pose(0.48, 0.0, 0.05 - kDepth_m)),
      object("cup2", true, Shape::cylinder(0.03, 0.08), pose(0.1, 0.1, 0.1 + 0.04 - 2 * kDepth_m)),
  };
  const auto X_GO = initial_poses(scene);
  CollisionWorld world(scene);
  const auto first = step(world, X_GO);
  auto X_moved = X_GO;
  for (auto& X : X_moved) X.translation() += Eigen::Vector3d(0.01, 0.02, 0.003);
  step(world, X_moved);
  const auto again = step(world, X_GO);
  CollisionWorld fresh(scene);
  const auto other = step(fresh, X_GO);

  std::vector<std::pair<int, int>> pairs;
  for (const ContactPoint& c : first)
    if (pairs.empty() || pairs.back() != std::pair{c.body_a, c.body_b})
      pairs.emplace_back(c.body_a, c.body_b);
  const std::vector<std::pair<int, int>> expected{{0, 1}, {0, 2}, {0, 3}, {0, 4}, {0, 5}, {1, 6}};
  EXPECT_EQ(pairs, expected);
  EXPECT_GE(first.size(), 4u + 1u + 2u + 2u + 3u + 4u);
  ASSERT_EQ(again.size(), first.size());
  ASSERT_EQ(other.size(), first.size());
  for (std::size_t i = 0; i < first.size(); ++i) {
    EXPECT_TRUE(same_bits(first[i], again[i])) << "contact " << i;
    EXPECT_TRUE(same_bits(first[i], other[i])) << "contact " << i;
  }
}

// ---- the normal points from body_a (lower index) to body_b, for every shape pair ------------

struct StackCase {
  std::string name;
  Shape lower;
  Eigen::Isometry3d X_G_lower;  // its top at z = 0
  Shape upper;
  Eigen::Isometry3d X_G_upper;  // its bottom at z = -1 mm
  std::size_t points;
};

std::vector<StackCase> stack_cases() {
  const double d = kDepth_m;
  const Shape slab = Shape::box({0.4, 0.4, 0.1});
  const Eigen::Isometry3d X_slab = pose(0, 0, -0.05);
  const Shape drum = Shape::cylinder(0.05, 0.1);  // upright, top at z = 0
  const Eigen::Isometry3d X_drum = pose(0, 0, -0.05);
  return {
      {"box-box", slab, X_slab, Shape::box(Eigen::Vector3d::Constant(0.1)),
       pose(0.02, 0.03, 0.05 - d), 4},
      {"box-sphere", slab, X_slab, Shape::sphere(0.05), pose(0.02, 0.03, 0.05 - d), 1},
      {"box-cylinder", slab, X_slab, Shape::cylinder(0.03, 0.2), pose(0.02, 0.03, 0.03 - d, ry90()),
       2},
      {"box-capsule", slab, X_slab, Shape::capsule(0.01, 0.05), pose(0.02, 0.03, 0.01 - d, ry90()),
       2},
      {"cylinder-capsule", drum, X_drum, Shape::capsule(0.01, 0.05),
       pose(0.0, 0.01, 0.01 - d, ry90()), 2},
      {"sphere-capsule", Shape::sphere(0.05), pose(0, 0, -0.05), Shape::capsule(0.01, 0.05),
       pose(0, 0, 0.01 - d, ry90()), 1},
      {"capsule-capsule", Shape::capsule(0.01, 0.05), pose(0, 0, -0.01, ry90()),
       Shape::capsule(0.01, 0.05), pose(0, 0, 0.01 - d, rx90()), 1},
      {"cylinder-sphere", drum, X_drum, Shape::sphere(0.02), pose(0.01, 0, 0.02 - d), 1},
      {"box-upright cylinder", slab, X_slab, Shape::cylinder(0.03, 0.2),
       pose(0.02, 0.03, 0.1 - d), 4},
      {"cylinder-cylinder", drum, X_drum, Shape::cylinder(0.03, 0.1), pose(0.01, 0, 0.05 - d), 4},
  };
}

TEST(Collision, NormalPointsFromBodyAToBodyBForEveryShapePair) {
  for (const StackCase& k : stack_cases()) {
    for (bool lower_first : {true, false}) {
      SCOPED_TRACE(k.name + (lower_first ? ", lower body first" : ", upper body first"));
      const ObjectSpec lower = object("lower", true, k.lower, k.X_G_lower);
      const ObjectSpec upper = object("upper", true, k.upper, k.X_G_upper);
      Scene scene;
      scene.objects = lower_first ? std::vector{lower, upper} : std::vector{upper, lower};
      CollisionWorld world(scene);
      const auto contacts = step(world, initial_poses(scene));

      // body 0 is below body 1 exactly when the lower body comes first
      const Eigen::Vector3d n_expected = (lower_first ? 1.0 : -1.0) * Eigen::Vector3d::UnitZ();
      ASSERT_EQ(contacts.size(), k.points);
      for (const ContactPoint& c : contacts) {
        EXPECT_EQ(c.body_a, 0);
        EXPECT_EQ(c.body_b, 1);
        EXPECT_NEAR(c.depth_m, kDepth_m, kDepthTol_m);
        expect_vec_near(c.n_G, n_expected, kNormalTol, "normal");
        EXPECT_NEAR(c.n_G.norm(), 1.0, 1e-12);
        EXPECT_GE(c.p_G.z(), -kDepth_m - kPointTol_m);  // inside the overlap slab
        EXPECT_LE(c.p_G.z(), kPointTol_m);
      }
    }
  }
}

TEST(Collision, DeepOverlapStillGivesAUnitNormal) {
  Scene scene;
  // a capsule lying with its axis 20 mm below the floor's top: 30 mm deep
  scene.objects = {floor_box(),
                   object("rod", true, Shape::capsule(0.01, 0.05), pose(0.1, 0.1, -0.02, ry90())),
                   // centred in a static box: no preferred direction at all
                   object("block", false, Shape::box(Eigen::Vector3d::Constant(0.1)),
                          pose(0, 0, 2.0)),
                   object("pin", true, Shape::capsule(0.01, 0.03), pose(0, 0, 2.0))};
  CollisionWorld world(scene);
  const auto contacts = step(world, initial_poses(scene));

  ASSERT_GE(contacts.size(), 3u);  // the rod's two segment ends, then the pin's point(s)
  for (int i = 0; i < 2; ++i) {
    EXPECT_EQ(contacts[i].body_a, 0);
    EXPECT_EQ(contacts[i].body_b, 1);
    EXPECT_NEAR(contacts[i].depth_m, 0.03, kDepthTol_m);
    expect_vec_near(contacts[i].n_G, Eigen::Vector3d::UnitZ(), kNormalTol, "deep capsule normal");
  }
  for (std::size_t i = 2; i < contacts.size(); ++i) {
    EXPECT_EQ(contacts[i].body_a, 2);
    EXPECT_EQ(contacts[i].body_b, 3);
    EXPECT_TRUE(contacts[i].n_G.allFinite());
    EXPECT_TRUE(contacts[i].p_G.allFinite());
    EXPECT_NEAR(contacts[i].n_G.norm(), 1.0, 1e-12);
    EXPECT_GT(contacts[i].depth_m, 0.0);
  }
  EXPECT_EQ(world.skipped_contacts(), 0u);
}

TEST(Collision, ZeroNormalIsSkippedAndCounted) {
  // FCL's sphere-sphere and sphere-capsule give a zero normal for coincident centres
  Scene scene;
  scene.objects = {object("a", true, Shape::sphere(0.05), pose(0, 0, 1)),
                   object("b", true, Shape::sphere(0.03), pose(0, 0, 1)),
                   object("c", true, Shape::capsule(0.01, 0.1), pose(1, 0, 1)),
                   object("d", true, Shape::sphere(0.02), pose(1, 0, 1))};
  CollisionWorld world(scene);
  const auto contacts = step(world, initial_poses(scene));
  EXPECT_EQ(world.candidate_pair_count(), 2u);
  EXPECT_TRUE(contacts.empty());
  EXPECT_EQ(world.skipped_contacts(), 2u);
  step(world, initial_poses(scene));
  EXPECT_EQ(world.skipped_contacts(), 4u);  // a running count
}

// ---- the pair filter -------------------------------------------------------------------------

TEST(Collision, SeparatedBodiesGiveNoPairsAndNoContacts) {
  Scene scene;
  // a turned shape's bounds are a cube around its bounding sphere (FCL): the rod lies 70 mm up
  scene.objects = {floor_box(), object("ball", true, Shape::sphere(0.05), pose(0, 0, 0.06)),
                   object("rod", true, Shape::capsule(0.01, 0.1), pose(0.3, 0.3, 0.08, ry90()))};
  CollisionWorld world(scene);
  const auto contacts = step(world, initial_poses(scene));
  EXPECT_EQ(world.candidate_pair_count(), 0u);
  EXPECT_TRUE(contacts.empty());
}

TEST(Collision, OverlappingBoundsButApartShapesGiveAPairAndNoContact) {
  // a ball off the floor's corner along the diagonal: the boxes around them overlap, the
  // shapes are 0.04 * sqrt(3) - 0.05 = 19 mm apart
  Scene scene;
  scene.objects = {floor_box(), object("ball", true, Shape::sphere(0.05), pose(0.54, 0.54, 0.04))};
  CollisionWorld world(scene);
  const auto contacts = step(world, initial_poses(scene));
  EXPECT_EQ(world.candidate_pair_count(), 1u);
  EXPECT_TRUE(contacts.empty());
}

TEST(Collision, StaticStaticOverlapIsNeverReported) {
  Scene scene;
  scene.objects = {floor_box(),
                   object("panel", false, Shape::box({0.2, 0.2, 0.2}), pose(0, 0, 0)),
                   object("knob", false, Shape::sphere(0.05), pose(0, 0, 0.1)),
                   object("ball", true, Shape::sphere(0.05), pose(0.4, 0.4, 0.05 - kDepth_m))};
  CollisionWorld world(scene);
  const auto contacts = step(world, initial_poses(scene));
  EXPECT_EQ(world.candidate_pair_count(), 1u);
  ASSERT_EQ(contacts.size(), 1u);
  EXPECT_EQ(contacts[0].body_a, 0);
  EXPECT_EQ(contacts[0].body_b, 3);
}

TEST(Collision, StaticObjectsIgnoreTheirPoses) {
  Scene scene;
  scene.objects = {floor_box(), object("ball", true, Shape::sphere(0.05), pose(0, 0, 0.049))};
  CollisionWorld world(scene);
  auto X_GO = initial_poses(scene);
  X_GO[0] = pose(0, 0, 10.0);  // a static object never moves
  const auto contacts = step(world, X_GO);
  ASSERT_EQ(contacts.size(), 1u);
  EXPECT_NEAR(contacts[0].depth_m, kDepth_m, 1e-6);
}

TEST(Collision, DynamicObjectsFollowTheirPoses) {
  Scene scene;
  scene.objects = {floor_box(), object("ball", true, Shape::sphere(0.05), pose(0, 0, 0.5))};
  CollisionWorld world(scene);
  auto X_GO = initial_poses(scene);
  EXPECT_TRUE(step(world, X_GO).empty());
  X_GO[1] = pose(0.2, 0.1, 0.05 - 2e-3);
  const auto contacts = step(world, X_GO);
  ASSERT_EQ(contacts.size(), 1u);
  EXPECT_NEAR(contacts[0].depth_m, 2e-3, 1e-6);
  expect_vec_near(contacts[0].p_G, Eigen::Vector3d(0.2, 0.1, -1e-3), kPointTol_m, "point");
}

TEST(Collision, RejectsBadShapes) {
  Scene scene;
  scene.objects = {object("flat", true, Shape::box({0.1, 0.0, 0.1}), pose(0, 0, 0))};
  EXPECT_THROW(CollisionWorld{scene}, std::invalid_argument);
  scene.objects = {object("dot", true, Shape::sphere(0.0), pose(0, 0, 0))};
  EXPECT_THROW(CollisionWorld{scene}, std::invalid_argument);
  scene.objects = {object("ok", true, Shape::sphere(0.1), pose(0, 0, 0))};
  scene.contact.max_points_per_pair = 0;
  EXPECT_THROW(CollisionWorld{scene}, std::invalid_argument);
}

// ---- the hand --------------------------------------------------------------------------------

// A flat open right hand (all joints zero), wrist at X_GH: link poses in world.
std::array<Eigen::Isometry3d, kLinkCount> flat_hand_links(const HandModel& hand,
                                                          const Eigen::Isometry3d& X_GH) {
  HandLinkPoses fk;
  forward_kinematics(hand, JointAngles{}, fk);
  std::array<Eigen::Isometry3d, kLinkCount> X_GL;
  for (int l = 0; l < kLinkCount; ++l)
    X_GL[l] = X_GH * fk.X_HL[l];
  return X_GL;
}

// A box under the index distal phalanx only, its top `dip_m` above the capsule's lowest line.
// It starts 10 mm past the distal joint, clear of the middle phalanx's end cap (radius 8 mm).
ObjectSpec box_under_index_tip(const HandModel& hand,
                               const std::array<Eigen::Isometry3d, kLinkCount>& X_GL,
                               double dip_m, bool dynamic) {
  const auto distal = static_cast<std::size_t>(Link::kIndexDistal);
  const Eigen::Vector3d p0 = X_GL[distal].translation();
  const double top_m = p0.z() - hand.capsules[distal].radius_m + dip_m;
  const Eigen::Vector3d size(0.030, 0.010, 0.020);
  return object("key", dynamic, Shape::box(size),
                pose(p0.x() + 0.010 + 0.5 * size.x(), p0.y(), top_m - 0.5 * size.z()));
}

TEST(CollisionHand, IndexTipDipsTwoMillimetresIntoABox) {
  const HandModel& hand = shipped_hand();
  const auto X_GL = flat_hand_links(hand, pose(0.2, -0.1, 0.9));
  const auto distal = static_cast<std::size_t>(Link::kIndexDistal);
  // the closed form below needs the phalanx level and along +x
  expect_vec_near(X_GL[distal].linear().col(0), Eigen::Vector3d::UnitX(), 1e-12, "x_L");
  constexpr double dip_m = 2e-3;

  Scene scene;
  scene.hands = {hand};
  scene.objects = {box_under_index_tip(hand, X_GL, dip_m, true)};
  CollisionWorld world(scene);
  ASSERT_TRUE(world.has_hand());
  EXPECT_EQ(world.hand_link_body(0, Link::kPalm), 1);
  const auto contacts = step(world, initial_poses(scene), &X_GL);

  // the phalanx lies on the box: its underside line from the box's edge to the segment's end
  ASSERT_EQ(contacts.size(), 2u);
  const Eigen::Vector3d p0 = X_GL[distal].translation();
  const double r_m = hand.capsules[distal].radius_m, length_m = hand.capsules[distal].length_m;
  for (const ContactPoint& c : contacts) {
    EXPECT_EQ(c.body_a, 0);
    EXPECT_EQ(c.body_b, world.hand_link_body(0, Link::kIndexDistal));
    EXPECT_TRUE(world.is_hand_body(c.body_b));
    EXPECT_NEAR(c.depth_m, dip_m, 1e-6);
    expect_vec_near(c.n_G, Eigen::Vector3d::UnitZ(), kNormalTol, "normal, box -> finger");
    EXPECT_NEAR(c.p_G.y(), p0.y(), 1e-6);
    EXPECT_NEAR(c.p_G.z(), p0.z() - r_m + 0.5 * dip_m, kPointTol_m);
  }
  const double x_lo = std::min(contacts[0].p_G.x(), contacts[1].p_G.x());
  const double x_hi = std::max(contacts[0].p_G.x(), contacts[1].p_G.x());
  EXPECT_NEAR(x_lo, p0.x() + 0.010, kPointTol_m);  // clipped at the box's edge
  EXPECT_NEAR(x_hi, p0.x() + length_m, kPointTol_m);  // the segment's end sphere
}

// How far a tracked link is off an object (the grasp rule's release gap): the flat index tip
// held above a box (FCL's distance) and above a cylinder lying across it (closest points), at
// 0, 3 and 7 mm; in it, 0. link_within agrees at 5 mm.
TEST(CollisionHand, ALinksGapToAnObjectIsItsDistanceOffTheSurface) {
  const HandModel& hand = shipped_hand();
  const auto X_GL = flat_hand_links(hand, pose(0.2, -0.1, 0.9));
  const auto distal = static_cast<std::size_t>(Link::kIndexDistal);
  const Eigen::Vector3d p0 = X_GL[distal].translation();
  const double r_m = hand.capsules[distal].radius_m;
  for (const bool round : {false, true}) {
    for (const double gap_m : {-2e-3, 0.0, 3e-3, 7e-3}) {
      Scene scene;
      scene.hands = {hand};
      if (round) {
        // a 1 cm cylinder along y under the tip's middle: its top gap_m below the capsule
        const double radius_m = 0.01;
        const double x_m = p0.x() + 0.5 * hand.capsules[distal].length_m;
        Eigen::Isometry3d X = pose(x_m, p0.y(), p0.z() - r_m - gap_m - radius_m);
        X.linear() = rx90();
        scene.objects = {object("bar", true, Shape::cylinder(radius_m, 0.05), X)};
      } else {
        scene.objects = {box_under_index_tip(hand, X_GL, -gap_m, true)};
      }
      CollisionWorld world(scene);
      step(world, initial_poses(scene), &X_GL);
      const double measured_m = world.link_gap_m(0, Link::kIndexDistal, X_GL[distal], 0);
      EXPECT_NEAR(measured_m, std::max(0.0, gap_m), 1e-6) << (round ? "cylinder" : "box") << ", " << gap_m;
      EXPECT_EQ(world.link_within(0, Link::kIndexDistal, X_GL[distal], 0, 5e-3), gap_m <= 5e-3)
          << (round ? "cylinder" : "box") << ", " << gap_m;
    }
  }
}

TEST(CollisionHand, DisabledHandGivesNoHandPairs) {
  const HandModel& hand = shipped_hand();
  const auto X_GL = flat_hand_links(hand, pose(0.2, -0.1, 0.9));
  Scene scene;
  scene.hands = {hand};
  scene.objects = {box_under_index_tip(hand, X_GL, 2e-3, true)};
  CollisionWorld world(scene);
  const auto X_GO = initial_poses(scene);

  EXPECT_EQ(step(world, X_GO, &X_GL).size(), 2u);  // the phalanx lying on the box
  // the links keep their last poses in the tree, but no pair with them may come out
  EXPECT_TRUE(step(world, X_GO, nullptr).empty());
  EXPECT_EQ(world.candidate_pair_count(), 0u);
  EXPECT_EQ(step(world, X_GO, &X_GL).size(), 2u);  // and back
}

TEST(CollisionHand, HandAgainstStaticObjectAndLinkAgainstLinkAreNeverPairs) {
  const HandModel& hand = shipped_hand();
  const auto X_GL = flat_hand_links(hand, pose(0.2, -0.1, 0.9));
  Scene scene;
  scene.hands = {hand};
  scene.proxy.enabled = false;  // the paper's kinematic hand: no hand-static pairs at all
  scene.objects = {box_under_index_tip(hand, X_GL, 2e-3, false)};
  CollisionWorld world(scene);
  // the phalanx capsules overlap at every joint, the box overlaps the index tip
  EXPECT_TRUE(step(world, initial_poses(scene), &X_GL).empty());
  EXPECT_EQ(world.candidate_pair_count(), 0u);
}

TEST(CollisionHand, AProxyHandGetsItsStaticContactsApart) {
  const HandModel& hand = shipped_hand();
  const auto X_GL = flat_hand_links(hand, pose(0.2, -0.1, 0.9));
  Scene scene;
  scene.hands = {hand};
  scene.objects = {box_under_index_tip(hand, X_GL, 2e-3, false)};
  CollisionWorld world(scene);
  ASSERT_TRUE(world.reports_hand_static());
  world.set_poses(initial_poses(scene), &X_GL);
  world.find_candidate_pairs();
  std::vector<ContactPoint> contacts, hand_static;
  world.compute_contacts(contacts, &hand_static);
  EXPECT_TRUE(contacts.empty()) << "no force acts between the hand and a static box";
  ASSERT_FALSE(hand_static.empty());
  for (const ContactPoint& c : hand_static) {
    EXPECT_EQ(c.body_a, 0) << "the box first";
    EXPECT_EQ(c.body_b, world.hand_link_body(0, Link::kIndexDistal));
    EXPECT_NEAR(c.depth_m, 2e-3, 1e-6);
  }
  // the same contacts again for links moved 1 mm up: 1 mm shallower
  auto X_GL_up = X_GL;
  for (auto& X : X_GL_up) X.translation().z() += 1e-3;
  world.compute_hand_static_contacts(0, X_GL_up, hand_static);
  ASSERT_FALSE(hand_static.empty());
  for (const ContactPoint& c : hand_static) EXPECT_NEAR(c.depth_m, 1e-3, 1e-6);
}

// ---- determinism and the allocation-free loop ------------------------------------------------

// Static floor and static panel (overlapping each other), four dynamic bodies resting in a
// stack, and the palm 1 mm into a dynamic pad under the palm only (clear of the thumb, which
// hangs lower than the palm's bottom face near the wrist). In pair (1, 3) the body below has the
// higher index.
Scene busy_scene(const Eigen::Isometry3d& X_GH) {
  const double d = kDepth_m;
  const HandModel& hand = shipped_hand();
  const double palm_bottom_m = hand.X_HP.translation().z() - 0.5 * hand.palm_size_m.z();
  const Eigen::Vector3d pad_size(0.08, 0.045, 0.02);
  Eigen::Isometry3d X_GPad = X_GH * pose(0.045, -0.0175, palm_bottom_m + d - 0.5 * pad_size.z());
  Scene scene;
  scene.hands = {hand};
  scene.objects = {
      floor_box(),                                                                          // 0
      object("lid", true, Shape::box({0.1, 0.1, 0.02}), pose(-0.3, 0.2, 0.11 - 2 * d)),     // 1
      object("ball", true, Shape::sphere(0.04), pose(0.3, -0.3, 0.04 - d)),                 // 2
      object("crate", true, Shape::box(Eigen::Vector3d::Constant(0.1)),
             pose(-0.3, 0.2, 0.05 - d)),                                                    // 3
      object("can", true, Shape::cylinder(0.03, 0.15), pose(0.3, 0.3, 0.03 - d, ry90())),  // 4
      object("panel", false, Shape::box({0.2, 0.2, 0.2}), pose(-0.45, -0.45, 0.0)),         // 5
      object("pad", true, Shape::box(pad_size), X_GPad),                                    // 6
  };
  return scene;
}

TEST(Collision, SameSceneSamePosesGiveBitwiseIdenticalSortedContacts) {
  const Eigen::Isometry3d X_GH = pose(0.0, 0.0, 1.0);
  const auto X_GL = flat_hand_links(shipped_hand(), X_GH);
  const Scene scene = busy_scene(X_GH);
  const auto X_GO = initial_poses(scene);
  CollisionWorld world(scene);
  const auto first = step(world, X_GO, &X_GL);

  const int palm = world.hand_link_body(0, Link::kPalm);
  std::vector<std::pair<int, int>> pairs;
  for (const ContactPoint& c : first) {
    EXPECT_LT(c.body_a, c.body_b);
    EXPECT_GT(c.depth_m, 0.0);
    if (pairs.empty() || pairs.back() != std::pair{c.body_a, c.body_b})
      pairs.emplace_back(c.body_a, c.body_b);
  }
  const std::vector<std::pair<int, int>> expected{{0, 2}, {0, 3}, {0, 4}, {1, 3}, {6, palm}};
  EXPECT_EQ(pairs, expected);  // sorted by (body_a, body_b); no static-static (0, 5)
  EXPECT_TRUE(std::is_sorted(first.begin(), first.end(), [](const auto& x, const auto& y) {
    return x.body_a != y.body_a ? x.body_a < y.body_a : x.body_b < y.body_b;
  }));

  // the same world after moving everything elsewhere (the tree refits and rebalances), and a
  // fresh world: identical bits
  auto X_GO_moved = X_GO;
  for (auto& X : X_GO_moved)
    X.translation() += Eigen::Vector3d(0.37, -0.21, 0.5);
  const auto X_GL_moved = flat_hand_links(shipped_hand(), pose(-0.5, 0.4, 1.2));
  step(world, X_GO_moved, &X_GL_moved);
  const auto again = step(world, X_GO, &X_GL);
  CollisionWorld fresh(scene);
  const auto other = step(fresh, X_GO, &X_GL);

  ASSERT_EQ(again.size(), first.size());
  ASSERT_EQ(other.size(), first.size());
  for (std::size_t i = 0; i < first.size(); ++i) {
    EXPECT_TRUE(same_bits(first[i], again[i])) << "contact " << i;
    EXPECT_TRUE(same_bits(first[i], other[i])) << "contact " << i;
  }
}

TEST(Collision, StepsAllocateNothingOnceWarm) {
  const Eigen::Isometry3d X_GH = pose(0.0, 0.0, 1.0);
  const auto X_GL = flat_hand_links(shipped_hand(), X_GH);
  const auto X_GL_moved = flat_hand_links(shipped_hand(), pose(0.01, -0.02, 1.003));
  const Scene scene = busy_scene(X_GH);
  const auto X_GO = initial_poses(scene);
  auto X_GO_moved = X_GO;
  for (auto& X : X_GO_moved)
    X.translation() += Eigen::Vector3d(0.002, -0.001, 0.0005);
  CollisionWorld world(scene);
  std::vector<ContactPoint> contacts;
  for (int i = 0; i < 3; ++i) {
    step(world, X_GO, &X_GL);
    world.compute_contacts(contacts);
  }
  const ContactPoint* buffer = contacts.data();

  // FCL's narrowphase allocates internally (its per-pair contact vector, libccd's shape copies),
  // so only the broadphase half is counted; the output buffer must simply stay put.
  g_allocations = 0;
  for (int i = 0; i < 20; ++i) {
    const bool moved = i % 2 == 1;
    g_count_allocations = true;
    world.set_poses(moved ? X_GO_moved : X_GO, i % 5 == 4 ? nullptr : moved ? &X_GL_moved : &X_GL);
    world.find_candidate_pairs();
    g_count_allocations = false;
    world.compute_contacts(contacts);
    EXPECT_FALSE(contacts.empty());
  }
  EXPECT_EQ(g_allocations.load(), 0);
  EXPECT_EQ(contacts.data(), buffer);
}

}  // namespace
}  // namespace vcockpit::physics
