// Collision with model meshes (collision.cpp's mesh narrowphase, face_vertex_contacts): the normal
// convention of every other pair holds for a static triangle mesh in both body orders, a box on
// it rests on its four corners and a ball on one point, and a moving mesh's hull on a box rests
// on its bottom corners. (Not in collision_test: its allocation counter replaces operator new,
// and FCL's BVH arrays, allocated inside libfcl, would be freed by the replacement under ASan.)

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "model/convex_hull.hpp"
#include "physics_node/physics/collision.hpp"
#include "physics_node/physics/scene.hpp"
#include "tests/support/collision_scenes.hpp"

namespace vcockpit::physics {
namespace {

constexpr double kNormalTol = 1e-6;
constexpr double kDepth_m = 1e-3;  // how far bodies are pushed into each other

using test::expect_vec_near;
using test::floor_box;
using test::initial_poses;
using test::object;
using test::pose;
using test::step;

// A 1 m square of two triangles (z = 0, facing +z) as a static mesh object at `index` 0 or last.
ObjectSpec mesh_floor() {
  auto mesh = std::make_shared<model::TriangleMesh>();
  mesh->vertices_m = {{-0.5, -0.5, 0}, {0.5, -0.5, 0}, {0.5, 0.5, 0}, {-0.5, 0.5, 0}};
  mesh->triangles = {{0, 1, 2}, {0, 2, 3}};
  return object("mesh floor", false, Shape::triangle_mesh(mesh, nullptr), pose(0, 0, 0));
}

// FCL 0.7's mesh pairs give the normal from the mesh in either order, a negative depth for a
// sphere and the point on the triangle; collision.cpp's mesh narrowphase turns them into the
// convention of every other pair, whichever body comes first.
TEST(Collision, MeshPairsFollowTheConventionInBothOrders) {
  for (bool mesh_first : {true, false}) {
    for (bool ball : {true, false}) {
      const Shape shape = ball ? Shape::sphere(0.05) : Shape::box(Eigen::Vector3d::Constant(0.1));
      // on the shared diagonal of the two triangles: one point, not one per triangle
      const ObjectSpec body = object("body", true, shape, pose(0.1, 0.1, 0.05 - kDepth_m));
      Scene scene;
      scene.objects = mesh_first ? std::vector<ObjectSpec>{mesh_floor(), body}
                                 : std::vector<ObjectSpec>{body, mesh_floor()};
      const auto contacts = [&] {
        CollisionWorld world(scene);
        return step(world, initial_poses(scene));
      }();
      const std::string what =
          std::string(ball ? "ball" : "box") + (mesh_first ? ", mesh first" : ", mesh last");
      ASSERT_EQ(contacts.size(), ball ? 1u : 4u) << what;
      for (const ContactPoint& c : contacts) {
        EXPECT_NEAR(c.depth_m, kDepth_m, 1e-6) << what;
        expect_vec_near(c.n_G, Eigen::Vector3d(0, 0, mesh_first ? 1.0 : -1.0), kNormalTol,
                        what + ": normal from body_a to body_b");
        EXPECT_NEAR(c.p_G.z(), -0.5 * kDepth_m, 1e-6) << what << ": midway through the overlap";
      }
    }
  }
}

// A moving model part (its convex hull) lying on a box floor rests on its corners, not on MPR's
// one point: the chamfered cap of tests/data/models, 1 mm into the floor.
TEST(Collision, AHullOnABoxRestsOnItsBottomCorners) {
  auto cap = std::make_shared<model::TriangleMesh>();
  const double s = 0.012, c = 0.002, hz = 0.006;
  for (double z : {-hz, hz - c})
    for (int k = 0; k < 4; ++k)
      cap->vertices_m.emplace_back(k & 1 ? s : -s, k & 2 ? s : -s, z);
  for (int k = 0; k < 4; ++k)
    cap->vertices_m.emplace_back(k & 1 ? s - c : c - s, k & 2 ? s - c : c - s, hz);
  auto hull = std::make_shared<model::TriangleMesh>(model::convex_hull(*cap));
  Scene scene;
  scene.objects = {floor_box(), object("cap", true, Shape::triangle_mesh(cap, hull),
                                       pose(0.1, 0.2, hz - kDepth_m))};
  const auto contacts = [&] {
    CollisionWorld world(scene);
    return step(world, initial_poses(scene));
  }();
  ASSERT_EQ(contacts.size(), 4u);
  for (const ContactPoint& p : contacts) {
    EXPECT_NEAR(p.depth_m, kDepth_m, 1e-9);
    expect_vec_near(p.n_G, Eigen::Vector3d::UnitZ(), kNormalTol, "normal, floor -> cap");
    EXPECT_NEAR(std::abs(p.p_G.x() - 0.1), s, 1e-9) << "under a bottom corner";
    EXPECT_NEAR(std::abs(p.p_G.y() - 0.2), s, 1e-9);
  }
}

// A round body on a mesh rests on a manifold, as on a box, not on FCL's one point per triangle: a
// cylinder standing on the two-triangle floor rests on its rim (4 points, each a radius from its
// axis, all 1 mm deep), and a cylinder or a capsule lying across the triangles' shared diagonal on
// the two ends of its lowest line (and the point where that line crosses the diagonal).
TEST(Collision, ARoundBodyOnAMeshRestsOnItsRimOrItsLine) {
  const double r = 0.03, half = 0.05;
  {
    Scene scene;
    scene.objects = {mesh_floor(), object("cylinder", true, Shape::cylinder(r, 2 * half),
                                          pose(0.05, 0.02, half - kDepth_m))};
    CollisionWorld world(scene);
    const auto contacts = step(world, initial_poses(scene));
    ASSERT_EQ(contacts.size(), 4u);
    for (const ContactPoint& c : contacts) {
      EXPECT_NEAR(c.depth_m, kDepth_m, 1e-9);
      expect_vec_near(c.n_G, Eigen::Vector3d::UnitZ(), kNormalTol, "normal, floor -> cylinder");
      EXPECT_NEAR((c.p_G.head<2>() - Eigen::Vector2d(0.05, 0.02)).norm(), r, 1e-9) << "on the rim";
      EXPECT_NEAR(c.p_G.z(), -0.5 * kDepth_m, 1e-9);
    }
  }
  // lying along x, across the diagonal y = x of the floor's two triangles
  const Eigen::Matrix3d along_x = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY()).toRotationMatrix();
  for (const bool capsule : {false, true}) {
    Scene scene;
    const Shape shape = capsule ? Shape::capsule(r, 2 * half) : Shape::cylinder(r, 2 * half);
    scene.objects = {mesh_floor(), object("round", true, shape, pose(0.0, 0.0, r - kDepth_m, along_x))};
    CollisionWorld world(scene);
    const auto contacts = step(world, initial_poses(scene));
    const std::string what = capsule ? "capsule" : "cylinder";
    ASSERT_GE(contacts.size(), 2u) << what;
    ASSERT_LE(contacts.size(), 3u) << what << ": the line's ends and where it crosses the diagonal";
    double lo_x = 1.0, hi_x = -1.0;
    for (const ContactPoint& c : contacts) {
      EXPECT_NEAR(c.depth_m, kDepth_m, 1e-9) << what;
      expect_vec_near(c.n_G, Eigen::Vector3d::UnitZ(), kNormalTol, what + ": normal");
      EXPECT_NEAR(c.p_G.y(), 0.0, 1e-9) << what;
      lo_x = std::min(lo_x, c.p_G.x());
      hi_x = std::max(hi_x, c.p_G.x());
    }
    EXPECT_NEAR(lo_x, -half, 1e-9) << what;
    EXPECT_NEAR(hi_x, half, 1e-9) << what;
  }
}

// A box on a part: a box resting on a moving mesh's hull (a 4 cm cube) larger than itself rests on
// its own four bottom corners, found on the hull's top face (MPR gives one point); a hull on a
// larger box the same, on the hull's corners (the box's face is then the reference).
TEST(Collision, ABoxOnAHullAndAHullOnABoxRestOnTheSmallerBodysCorners) {
  const auto hull_cube = [](double half) {
    auto mesh = std::make_shared<model::TriangleMesh>();
    for (int k = 0; k < 8; ++k)
      mesh->vertices_m.emplace_back(k & 1 ? half : -half, k & 2 ? half : -half, k & 4 ? half : -half);
    auto hull = std::make_shared<model::TriangleMesh>(model::convex_hull(*mesh));
    return Shape::triangle_mesh(hull, hull);
  };
  for (const bool box_on_top : {true, false}) {
    const double below = 0.04, above = 0.02;
    Scene scene;
    const Shape lower = box_on_top ? hull_cube(below) : Shape::box(Eigen::Vector3d::Constant(2 * below));
    const Shape upper = box_on_top ? Shape::box(Eigen::Vector3d::Constant(2 * above)) : hull_cube(above);
    scene.objects = {object("below", true, lower, pose(0.0, 0.0, 0.0)),
                     object("above", true, upper, pose(0.003, 0.002, below + above - kDepth_m))};
    CollisionWorld world(scene);
    const auto contacts = step(world, initial_poses(scene));
    const std::string what = box_on_top ? "box on a hull" : "hull on a box";
    ASSERT_EQ(contacts.size(), 4u) << what;
    for (const ContactPoint& c : contacts) {
      EXPECT_NEAR(c.depth_m, kDepth_m, 1e-9) << what;
      expect_vec_near(c.n_G, Eigen::Vector3d::UnitZ(), kNormalTol, what + ": normal, below -> above");
      EXPECT_NEAR(std::abs(c.p_G.x() - 0.003), above, 1e-9) << what << ": under a corner";
      EXPECT_NEAR(std::abs(c.p_G.y() - 0.002), above, 1e-9) << what;
      EXPECT_NEAR(c.p_G.z(), below - 0.5 * kDepth_m, 1e-9) << what;
    }
  }
}

// A cylinder standing on a closed mesh block (its top and its side walls triangles) and hanging
// 1 cm over the top's edge, 1 mm into the top: it rests on the top's rim points alone. The wall it
// dips into is no face it rests on (FCL's normal there is not the wall's, turned toward the
// cylinder), so no point pushes it sideways by its overhang.
TEST(Collision, ARoundBodyOverAMeshEdgeIsNotPushedSidewaysByTheWall) {
  auto block = std::make_shared<model::TriangleMesh>();
  const double h = 0.1;  // a 20 cm cube, top at z = 0
  for (int k = 0; k < 8; ++k)
    block->vertices_m.emplace_back(k & 1 ? h : -h, k & 2 ? h : -h, k & 4 ? 0.0 : -2 * h);
  const auto full = model::convex_hull(*block);  // its 12 triangles, facing out
  block->triangles = full.triangles;
  block->vertices_m = full.vertices_m;
  const double r = 0.03;
  Scene scene;
  scene.objects = {object("block", false, Shape::triangle_mesh(block, nullptr), pose(0, 0, 0)),
                   object("cup", true, Shape::cylinder(r, 0.1), pose(h - r + 0.01, 0.0, 0.05 - kDepth_m))};
  CollisionWorld world(scene);
  const auto contacts = step(world, initial_poses(scene));
  ASSERT_GE(contacts.size(), 1u);
  for (const ContactPoint& c : contacts) {
    expect_vec_near(c.n_G, Eigen::Vector3d::UnitZ(), 1e-3, "normal, block -> cup");
    EXPECT_LT(c.depth_m, 1.5 * kDepth_m) << "at " << c.p_G.transpose();
    EXPECT_LE(c.p_G.x(), h + 1e-9) << "over the top";
  }
}

// A box on a moving part whose hull was made in another orientation (its vertices floats, as a
// model file gives them, so its sloped faces are flat only to rounding): the part turned so that
// face is its top, the box rests on its four corners. (The face's triangles are found within
// 1e-6 of the part's size; here a tolerance of 1e-9 m found them too.)
TEST(Collision, ABoxRestsOnAHullsFaceThatIsFlatOnlyToRounding) {
  const Eigen::Matrix3d R = (Eigen::AngleAxisd(0.35, Eigen::Vector3d::UnitX()) *
                             Eigen::AngleAxisd(0.52, Eigen::Vector3d::UnitY()) *
                             Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ()))
                                .toRotationMatrix();
  auto mesh = std::make_shared<model::TriangleMesh>();
  const double below = 0.3, above = 0.02;  // a 60 cm part: its floats are 3e-8 m apart
  for (int k = 0; k < 8; ++k) {
    const Eigen::Vector3d v = R * Eigen::Vector3d(k & 1 ? below : -below, k & 2 ? below : -below,
                                                  k & 4 ? below : -below);
    mesh->vertices_m.push_back(v.cast<float>().cast<double>());
  }
  auto hull = std::make_shared<model::TriangleMesh>(model::convex_hull(*mesh));
  Scene scene;
  scene.objects = {object("part", true, Shape::triangle_mesh(hull, hull), pose(0, 0, 0, R.transpose())),
                   object("box", true, Shape::box(Eigen::Vector3d::Constant(2 * above)),
                          pose(0.003, 0.002, below + above - kDepth_m))};
  CollisionWorld world(scene);
  const auto contacts = step(world, initial_poses(scene));
  ASSERT_EQ(contacts.size(), 4u);
  for (const ContactPoint& c : contacts) {
    EXPECT_NEAR(c.depth_m, kDepth_m, 1e-6);
    expect_vec_near(c.n_G, Eigen::Vector3d::UnitZ(), 1e-5, "normal, part -> box");
    EXPECT_NEAR(std::abs(c.p_G.x() - 0.003), above, 1e-6) << "under a corner";
    EXPECT_NEAR(std::abs(c.p_G.y() - 0.002), above, 1e-6);
  }
}

}  // namespace
}  // namespace vcockpit::physics
