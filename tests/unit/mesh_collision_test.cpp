// Collision with model meshes (collision.cpp's mesh narrowphase, face_vertex_contacts): the normal
// convention of every other pair holds for a static triangle mesh in both body orders, a box on
// it rests on its four corners and a ball on one point, and a moving mesh's hull on a box rests
// on its bottom corners. (Not in collision_test: its allocation counter replaces operator new,
// and FCL's BVH arrays, allocated inside libfcl, would be freed by the replacement under ASan.)

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace vcockpit::physics
