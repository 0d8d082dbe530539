#include "physics_node/physics/fcl_geometry.hpp"

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/sphere.h>

#include <stdexcept>
#include <string>
#include <vector>

namespace vcockpit::physics {
namespace {

void require(bool ok, const std::string& message) {
  if (!ok) throw std::invalid_argument(message);
}

// A static mesh: its triangles in a bounding volume hierarchy (oriented boxes with swept-sphere
// rectangles, FCL's choice for collision and distance alike).
std::shared_ptr<fcl::CollisionGeometryd> triangle_geometry(const model::TriangleMesh& mesh) {
  auto bvh = std::make_shared<fcl::BVHModel<fcl::OBBRSSd>>();
  std::vector<fcl::Triangle> triangles;
  triangles.reserve(mesh.triangles.size());
  for (const auto& t : mesh.triangles)
    triangles.emplace_back(t[0], t[1], t[2]);
  bvh->beginModel(static_cast<int>(triangles.size()), static_cast<int>(mesh.vertices_m.size()));
  bvh->addSubModel(mesh.vertices_m, triangles);
  bvh->endModel();
  bvh->computeLocalAABB();
  return bvh;
}

// A moving mesh: its convex hull (FCL's Convex: the vertices and each face as its vertex count
// then its indices).
std::shared_ptr<fcl::CollisionGeometryd> convex_geometry(const model::TriangleMesh& hull) {
  auto vertices = std::make_shared<std::vector<Eigen::Vector3d>>(hull.vertices_m);
  auto faces = std::make_shared<std::vector<int>>();
  faces->reserve(4 * hull.triangles.size());
  for (const auto& t : hull.triangles)
    faces->insert(faces->end(),
                  {3, static_cast<int>(t[0]), static_cast<int>(t[1]), static_cast<int>(t[2])});
  auto convex =
      std::make_shared<fcl::Convexd>(vertices, static_cast<int>(hull.triangles.size()), faces,
                                     /*throw_if_invalid=*/false);
  convex->computeLocalAABB();
  return convex;
}

}  // namespace

std::shared_ptr<fcl::CollisionGeometryd> fcl_geometry(const Shape& s, bool moving) {
  switch (s.kind) {
    case ShapeKind::kBox:
      require((s.box_size_m.array() > 0.0).all(), "box size must be positive");
      return std::make_shared<fcl::Boxd>(s.box_size_m);
    case ShapeKind::kSphere:
      require(s.radius_m > 0.0, "sphere radius must be positive");
      return std::make_shared<fcl::Sphered>(s.radius_m);
    case ShapeKind::kCapsule:
      require(s.radius_m > 0.0 && s.length_m >= 0.0, "bad capsule radius or length");
      return std::make_shared<fcl::Capsuled>(s.radius_m, s.length_m);
    case ShapeKind::kCylinder:
      require(s.radius_m > 0.0 && s.length_m > 0.0, "bad cylinder radius or length");
      return std::make_shared<fcl::Cylinderd>(s.radius_m, s.length_m);
    case ShapeKind::kMesh:
      require(s.mesh != nullptr && (s.hull != nullptr || !moving),
              "a mesh shape without its mesh (or a moving one without its hull)");
      // a static object's own triangles; a moving one's hull
      return moving ? convex_geometry(*s.hull) : triangle_geometry(*s.mesh);
  }
  throw std::invalid_argument("unknown shape kind");
}

}  // namespace vcockpit::physics
