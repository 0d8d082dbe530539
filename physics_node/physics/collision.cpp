#include "physics_node/physics/collision.hpp"

#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/collision_object.h>
#include <fcl/narrowphase/distance.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "common/assert.hpp"
#include "physics_node/physics/broadphase.hpp"
#include "physics_node/physics/face_vertex_contacts.hpp"
#include "physics_node/physics/fcl_geometry.hpp"
#include "physics_node/physics/manifold_clipper.hpp"
#include "physics_node/physics/segment_contact.hpp"

// What FCL 0.7.0 (Debian, libccd solver) does, measured here (tests/unit/collision_test.cpp
// keeps the measurements honest):
//
// - Normal: from the first object passed to fcl::collide to the second, for every pair we use, in
//   both argument orders: box-box, box-sphere, box-cylinder, box-capsule, capsule-cylinder,
//   capsule-sphere, capsule-capsule, sphere-cylinder. So body_a = lower index goes first and
//   no flip is needed. (For exactly concentric bodies the direction is arbitrary, but unit.)
// - Algorithms: box-box (4-point manifold for a face, points midway between the surfaces),
//   sphere-box, sphere-sphere, sphere-capsule and sphere-cylinder are closed-form and exact,
//   but for sphere-capsule's point (corrected below, see contact_point). Sphere-sphere and
//   sphere-capsule give a zero normal for a sphere centred on the other's centre or axis: such
//   points are dropped and counted (skipped_contacts).
//   A capsule against a cylinder or capsule is exact from closest points while its segment stays
//   outside the other body (segment_contact.hpp): MPR's normal swings on elongated bodies.
//   Every other pair (and those deeper) goes through libccd's MPR (ccdMPRPenetration), not EPA: the normal is that
//   of the Minkowski-difference face crossed by the ray between the two centres, and the depth
//   that face's distance from the origin. That is exact for a flat face (a capsule or cylinder
//   on a box) and sensible, if not minimal, for deep overlaps.
// - MPR's depth error at FCL's default gjk_tolerance (1e-6) reached 7e-7 m for a capsule lying
//   on a box, a pose-dependent few percent of a resting depth m g / k_eff; at 1e-9 it is below
//   1e-10 m for +0.1-0.4 us per pair (about 0.8-1.7 us per MPR pair, 0.1-0.2 us for the
//   closed-form sphere pairs, 0.6 us for box-box).
// - FCL's own GJK/EPA (GST_INDEP) returns negative depths and normals along the wrong axis for
//   capsule and cylinder pairs in 0.7.0: not usable.
// - MPR gives ONE point for flat contacts of round shapes: a cylinder standing on a box face, a
//   cylinder or capsule lying on one, a cup on a cup. One point gives no torsional or rocking
//   support (an upright cup spun at 1.2 deg/s with no input), so those pairs get a manifold here.
//
// Those manifolds are built by manifold_clipper.hpp from FCL's normal (kept as it is); if nothing
// survives (or the features are unsupported), FCL's point is kept. Cost: +0.06-0.25 us per pair
// on top of MPR's 0.5-1.1 us.

namespace vcockpit::physics {
namespace {

using Geometry = std::shared_ptr<fcl::CollisionGeometryd>;

constexpr double kMprTolerance_m = 1e-9;  // see above
// A mesh pair: the triangles asked of FCL, how far past a triangle's edge a vertex still rests
// on it, and how near two points are one (the same vertex over two triangles of one plane).
constexpr std::size_t kMeshTriangles = 32;
constexpr double kFaceSlack_m = 1e-6;
constexpr double kMergeDistance_m = 1e-4;
// A hull's face that a contact normal is within 5 deg of is the face it rests on.
constexpr double kHullFaceCos = 0.99619469809174553;

using BodyKind = BroadphaseBody;  // static, dynamic or a hand link

// What an FCL object's user data points at. Shapes are centred on their frame, axis along z.
struct Body {
  int index = -1;
  BodyKind kind = BodyKind::kStatic;
  ShapeKind shape = ShapeKind::kBox;
  double radius_m = 0.0;       // sphere, capsule and cylinder
  double half_length_m = 0.0;  // capsule (without its end caps) and cylinder
  Eigen::Vector3d half_size_m = Eigen::Vector3d::Zero();  // box
};

Body make_body(int index, BodyKind kind, const Shape& shape) {
  Body b;
  b.index = index;
  b.kind = kind;
  b.shape = shape.kind;
  b.radius_m = shape.radius_m;
  b.half_length_m = 0.5 * shape.length_m;
  b.half_size_m = 0.5 * shape.box_size_m;
  return b;
}

void require(bool ok, const std::string& message) {
  if (!ok) throw std::invalid_argument("CollisionWorld: " + message);
}

Geometry object_geometry(const ObjectSpec& spec) {
  try {
    return fcl_geometry(spec.shape, spec.dynamic);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument("CollisionWorld: object '" + spec.name + "': " + e.what());
  }
}

// Ry(+90 deg), exactly: FCL's capsule axis z onto the phalanx axis x_L.
Eigen::Matrix3d z_onto_x() {
  Eigen::Matrix3d R;
  // clang-format off
  R << 0.0, 0.0, 1.0,
       0.0, 1.0, 0.0,
      -1.0, 0.0, 0.0;
  // clang-format on
  return R;
}

}  // namespace

struct CollisionWorld::Impl {
  std::vector<Body> bodies;  // never resized after construction: user data points into it
  std::vector<std::unique_ptr<fcl::CollisionObjectd>> objects;  // body order
  std::vector<Shape> shapes;                                      // body order
  // a moving mesh's hull: each triangle's outward unit normal in the body's frame, and how far
  // off one face's plane its triangles may be (empty and 0 for any other body)
  std::vector<std::vector<Eigen::Vector3d>> hull_normals;
  std::vector<double> hull_plane_tol_m;
  // per hand: link frame -> collision geometry frame
  std::vector<std::array<Eigen::Isometry3d, kLinkCount>> X_LC;
  std::unique_ptr<SweepAndPrune> broadphase;

  std::vector<BodyPair> pairs;
  fcl::CollisionRequestd request;
  fcl::CollisionResultd result;
  std::size_t contact_capacity = 0;
  std::uint64_t skipped = 0;

  // mesh pairs: up to kMeshTriangles triangles asked of FCL, reduced to max_points
  fcl::CollisionRequestd mesh_request;
  int max_points = 4;
  std::vector<Eigen::Vector3d> vertices_G;
  std::vector<FaceContact> face_contacts;
  std::vector<FlatFace> faces;  // a reference body's faces a contact rests on

  ManifoldClipper clipper;  // flat contacts' manifolds (fixed work space)
  std::array<ManifoldPoint, kMaxManifold> manifold_points;

  void add_body(const Geometry& geometry, const Eigen::Isometry3d& X_GC, BodyKind kind,
                const Shape& shape) {
    bodies.push_back(make_body(static_cast<int>(bodies.size()), kind, shape));
    objects.push_back(std::make_unique<fcl::CollisionObjectd>(geometry, X_GC));
    shapes.push_back(shape);
    std::vector<Eigen::Vector3d>& normals = hull_normals.emplace_back();
    double plane_tol_m = 0.0;
    if (shape.kind == ShapeKind::kMesh && kind != BodyKind::kStatic && shape.hull) {
      const model::TriangleMesh& hull = *shape.hull;
      for (const auto& t : hull.triangles) {
        const Eigen::Vector3d& a = hull.vertices_m[t[0]];
        normals.push_back((hull.vertices_m[t[1]] - a).cross(hull.vertices_m[t[2]] - a).normalized());
      }
      // the model's vertices are floats, so a sloped face's corners are off its plane by ~1e-7
      // of the part's size: one face's triangles are those within 1e-6 of it
      plane_tol_m = 1e-6 * shape.bounding_radius_m();
    }
    hull_plane_tol_m.push_back(plane_tol_m);
  }

  void place(int body, const Eigen::Isometry3d& X_GC) {
    const auto i = static_cast<std::size_t>(body);
    objects[i]->setTransform(X_GC);
    broadphase->set_box(body, shape_aabb(shapes[i], X_GC));
  }

  // Appends the pair's points with positive depth; bad ones are counted and dropped.
  void narrowphase(const BodyPair& pair, std::vector<ContactPoint>& out) {
    if (is_static_mesh(pair.lo) || is_static_mesh(pair.hi)) {
      mesh_narrowphase(pair, out);
      return;
    }
    const std::size_t first = out.size();
    // a box and a round body: the least overlap over the box's face normals first
    const bool box_round = box_and_round(pair);
    FaceOverlap face;
    if (box_round) {
      face = least_face_overlap(pair);
      if (face.depth_m <= kMprTolerance_m) return;  // a separating axis: apart or only touching
      if (face_contact_is_certain(face)) {
        out.push_back(face_contact(pair, face));
        finish_manifold(pair, first, out);
        return;
      }
    }
    // a capsule and a cylinder or capsule: exact from closest points while the capsule's segment
    // stays outside the other body (segment_contact.hpp); deeper, MPR decides
    if (segment_pair(pair)) {
      if (segment_narrowphase(pair, first, out)) return;
    }
    result.clear();
    fcl::collide(objects[static_cast<std::size_t>(pair.lo)].get(),
                 objects[static_cast<std::size_t>(pair.hi)].get(), request, result);
    for (std::size_t i = 0; i < result.numContacts(); ++i) {
      const fcl::Contactd& c = result.getContact(i);
      const double depth_m = c.penetration_depth;
      if (depth_m <= 0.0) continue;  // touching: no force
      const double norm = c.normal.norm();
      if (!std::isfinite(depth_m) || !c.pos.allFinite() || !(norm > 0.5 && norm < 2.0)) {
        ++skipped;  // zero or NaN normal (or NaN depth, point): no direction to push along
        continue;
      }
      const Eigen::Vector3d n = c.normal / norm;
      out.push_back({pair.lo, pair.hi, contact_point(pair, c.pos, n, depth_m), n, depth_m});
    }
    if (polyhedral_with_hull(pair) && out.size() == first + 1) polyhedral_faces(pair, first, out);
    // MPR's normal is not always the direction of least overlap: with a body exactly touching a
    // box face (a short cylinder standing on a floor) libccd can return a direction along the
    // face with the overlap across the whole box (1.7 m), which would throw the body away. The
    // box's face normal of least overlap wins when it is less by more than MPR's own tolerance
    // (MPR's exact face normals are kept as they are).
    if (box_round && out.size() == first + 1) {
      ContactPoint& c = out.back();
      if (face.depth_m < c.depth_m - kMprTolerance_m) c = face_contact(pair, face);
      if (c.depth_m <= kMprTolerance_m) {
        out.pop_back();  // only touching: no force
        return;
      }
    }
    finish_manifold(pair, first, out);
  }

  bool is_static_mesh(int body) const {
    const Body& b = bodies[static_cast<std::size_t>(body)];
    return b.shape == ShapeKind::kMesh && b.kind == BodyKind::kStatic;
  }

  // A body against a static triangle mesh. FCL 0.7's mesh pairs give, in either argument order,
  // the normal from the mesh toward the other body, a sphere's depth negative, and the point on
  // the triangle: one point per triangle touched (tests/unit/collision_test.cpp, "Mesh"). So
  // the depth is taken as its magnitude, the point moved midway, and a body with a flat side gets
  // a manifold on each triangle it touches: a box's or a convex hull's vertices under the
  // triangle (face_vertex_contacts.hpp), a cylinder's or capsule's feature facing it clipped to
  // the triangle (manifold_clipper.hpp), so it rests on a mesh as on a box. A sphere keeps its
  // one point.
  void mesh_narrowphase(const BodyPair& pair, std::vector<ContactPoint>& out) {
    const int mesh = is_static_mesh(pair.lo) ? pair.lo : pair.hi;
    const int other = mesh == pair.lo ? pair.hi : pair.lo;
    const fcl::CollisionObjectd& mesh_object = *objects[static_cast<std::size_t>(mesh)];
    result.clear();
    fcl::collide(&mesh_object, objects[static_cast<std::size_t>(other)].get(), mesh_request, result);
    if (result.numContacts() == 0) return;
    const model::TriangleMesh& triangles = *shapes[static_cast<std::size_t>(mesh)].mesh;
    const Eigen::Isometry3d& X_GM = mesh_object.getTransform();
    const bool polyhedral = incident_vertices(other, vertices_G);
    // (a hand link keeps FCL's points: the proxy hand stops it at the surface itself, and on a
    // mesh of two large triangles the manifold unsettled it: ProxyHand/PressedIntoTheConsole)
    const bool round = is_round(bodies[static_cast<std::size_t>(other)].shape) &&
                       bodies[static_cast<std::size_t>(other)].kind != BodyKind::kHand;
    face_contacts.clear();
    for (std::size_t i = 0; i < result.numContacts(); ++i) {
      const fcl::Contactd& c = result.getContact(i);
      const double depth_m = std::abs(c.penetration_depth);
      const double norm = c.normal.norm();
      if (!std::isfinite(depth_m) || !c.pos.allFinite() || !(norm > 0.5 && norm < 2.0)) {
        ++skipped;
        continue;
      }
      if (depth_m <= kMprTolerance_m) continue;  // only touching
      const Eigen::Vector3d n = c.normal / norm;  // mesh -> other
      const std::size_t before = face_contacts.size();
      const int t = c.o1 == mesh_object.collisionGeometry().get() ? c.b1 : c.b2;
      if ((polyhedral || round) && t >= 0 && static_cast<std::size_t>(t) < triangles.triangles.size()) {
        FlatFace face;
        const auto& tri = triangles.triangles[static_cast<std::size_t>(t)];
        for (int k = 0; k < 3; ++k)
          face.corners_G[static_cast<std::size_t>(k)] = X_GM * triangles.vertices_m[tri[static_cast<std::size_t>(k)]];
        face.n_G = (face.corners_G[1] - face.corners_G[0]).cross(face.corners_G[2] - face.corners_G[0]).normalized();
        // the side the other body is on: FCL's normal's, or for a round body its centre's (FCL's
        // cylinder-triangle normal can be far off the face's: 76 deg, tests/unit/mesh_collision_test)
        const Eigen::Vector3d toward = round ? Eigen::Vector3d(objects[static_cast<std::size_t>(other)]->getTranslation() -
                                                               face.corners_G[0])
                                             : n;
        if (face.n_G.dot(toward) < 0.0) {  // the triangle's back: the other body came from behind
          face.n_G = -face.n_G;
          std::swap(face.corners_G[1], face.corners_G[2]);
        }
        if (polyhedral) {
          face_vertex_contacts(face, vertices_G, 1.5 * depth_m + kFaceSlack_m, kFaceSlack_m, face_contacts);
        } else if (face.n_G.dot(n) > 0.0) {
          // (a face turned away from FCL's normal is one the body is not resting on: a closed
          // mesh's side wall that a body overhanging the top's edge dips into keeps FCL's point,
          // not rim points pushed sideways by the overhang)
          // FCL's depth bounds the points (deeper is past a thin part's far side, or the overhang
          // of a body dipping into a side wall)
          const int kept = clipper.clip_on_face(face, clip_body(other), 1.5 * depth_m + kFaceSlack_m,
                                                manifold_points);
          for (int k = 0; k < kept; ++k)
            face_contacts.push_back({manifold_points[static_cast<std::size_t>(k)].p_G, face.n_G,
                                     manifold_points[static_cast<std::size_t>(k)].depth_m});
        }
      }
      if (face_contacts.size() == before) face_contacts.push_back({c.pos - (0.5 * depth_m) * n, n, depth_m});
    }
    emit_face_contacts(pair, mesh, out);
  }

  // face_contacts, reduced to max_points, as the pair's points; their normals point out of
  // `reference` (the mesh, the box), turned to run from body lo to body hi.
  void emit_face_contacts(const BodyPair& pair, int reference, std::vector<ContactPoint>& out) {
    reduce_face_contacts(face_contacts, max_points, kMergeDistance_m);
    for (const FaceContact& f : face_contacts)
      out.push_back({pair.lo, pair.hi, f.p_G, reference == pair.lo ? f.n_G : Eigen::Vector3d(-f.n_G),
                     f.depth_m});
  }

  // The world vertices of a polyhedral body (a box's corners, a moving mesh's hull): false for a
  // round one.
  bool incident_vertices(int body, std::vector<Eigen::Vector3d>& out) const {
    out.clear();
    const Body& b = bodies[static_cast<std::size_t>(body)];
    const Eigen::Isometry3d& X = objects[static_cast<std::size_t>(body)]->getTransform();
    if (b.shape == ShapeKind::kBox) {
      for (int k = 0; k < 8; ++k)
        out.push_back(X * Eigen::Vector3d(k & 1 ? b.half_size_m.x() : -b.half_size_m.x(),
                                          k & 2 ? b.half_size_m.y() : -b.half_size_m.y(),
                                          k & 4 ? b.half_size_m.z() : -b.half_size_m.z()));
      return true;
    }
    const Shape& s = shapes[static_cast<std::size_t>(body)];
    if (b.shape == ShapeKind::kMesh && s.hull) {
      for (const Eigen::Vector3d& v : s.hull->vertices_m) out.push_back(X * v);
      return true;
    }
    return false;
  }

  bool is_hull(int body) const {
    const Body& b = bodies[static_cast<std::size_t>(body)];
    return b.shape == ShapeKind::kMesh && b.kind != BodyKind::kStatic;
  }

  bool is_polyhedral(int body) const {
    return bodies[static_cast<std::size_t>(body)].shape == ShapeKind::kBox || is_hull(body);
  }

  // A moving mesh's hull and a box. (Two hulls keep MPR's point: with a manifold the chamfered
  // cap dropped on another rocked from corner to corner and fell off, where MPR's one point near
  // the middle let it settle; tests/scenario/mesh_ramp_test.cpp.)
  bool polyhedral_with_hull(const BodyPair& pair) const {
    return is_polyhedral(pair.lo) && is_polyhedral(pair.hi) && is_hull(pair.lo) != is_hull(pair.hi);
  }

  // The faces of `body` that a contact with normal n_out (out of it) rests on, into `faces`: a
  // box's face nearest n_out; a hull's triangles of the face within kHullFaceCos of n_out (none
  // when it touches by an edge or a corner).
  void supporting_faces(int body, const Eigen::Vector3d& n_out, std::vector<FlatFace>& faces) const {
    faces.clear();
    const Body& b = bodies[static_cast<std::size_t>(body)];
    const Eigen::Isometry3d& X_GB = objects[static_cast<std::size_t>(body)]->getTransform();
    if (b.shape == ShapeKind::kBox) {
      int axis = 0;
      double best = -1.0;
      for (int i = 0; i < 3; ++i) {
        const double along = std::abs(X_GB.linear().col(i).dot(n_out));
        if (along > best) {
          best = along;
          axis = i;
        }
      }
      const double sign = X_GB.linear().col(axis).dot(n_out) >= 0.0 ? 1.0 : -1.0;
      FlatFace face;
      face.n_G = sign * X_GB.linear().col(axis);
      face.corner_count = 4;
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      const Eigen::Vector3d h = b.half_size_m;
      constexpr double kSigns[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
      for (int k = 0; k < 4; ++k) {
        Eigen::Vector3d p_B = Eigen::Vector3d::Zero();
        p_B[axis] = sign * h[axis];
        p_B[u] = kSigns[k][0] * h[u];
        p_B[v] = kSigns[k][1] * h[v];
        face.corners_G[static_cast<std::size_t>(k)] = X_GB * p_B;
      }
      // counter-clockwise about the face's normal
      const auto& c = face.corners_G;
      if ((c[1] - c[0]).cross(c[2] - c[0]).dot(face.n_G) < 0.0) std::swap(face.corners_G[1], face.corners_G[3]);
      faces.push_back(face);
      return;
    }
    const model::TriangleMesh& hull = *shapes[static_cast<std::size_t>(body)].hull;
    const std::vector<Eigen::Vector3d>& normals = hull_normals[static_cast<std::size_t>(body)];
    const Eigen::Vector3d n_B = X_GB.linear().transpose() * n_out;
    std::size_t best = 0;
    double best_cos = -2.0;
    for (std::size_t i = 0; i < normals.size(); ++i) {
      const double along = normals[i].dot(n_B);
      if (along > best_cos) {
        best_cos = along;
        best = i;
      }
    }
    if (!(best_cos >= kHullFaceCos)) return;
    const Eigen::Vector3d& best_n = normals[best];
    const double plane_m = best_n.dot(hull.vertices_m[hull.triangles[best][0]]);
    const double plane_tol_m = hull_plane_tol_m[static_cast<std::size_t>(body)];
    for (std::size_t i = 0; i < hull.triangles.size(); ++i) {
      const auto& t = hull.triangles[i];
      const Eigen::Vector3d& n = normals[i];
      if (n.dot(best_n) < 1.0 - 1e-6 ||
          std::abs(best_n.dot(hull.vertices_m[t[0]]) - plane_m) > plane_tol_m)
        continue;
      FlatFace face;  // hull triangles run counter-clockwise seen from outside
      face.n_G = X_GB.linear() * n;
      face.corner_count = 3;
      for (int k = 0; k < 3; ++k)
        face.corners_G[static_cast<std::size_t>(k)] = X_GB * hull.vertices_m[t[static_cast<std::size_t>(k)]];
      face.corners_G[3] = face.corners_G[2];  // unused: a triangle
      faces.push_back(face);
    }
  }

  // A moving mesh's hull and a box (a part on a table, a box on a part): MPR's one point becomes
  // each body's vertices under the face of the other that the contact rests on, so it rests flat
  // (face_vertex_contacts.hpp). Both ways round: a small part's corners on a large box's face,
  // and a large box's corners on a small part's face are both found.
  void polyhedral_faces(const BodyPair& pair, std::size_t first, std::vector<ContactPoint>& out) {
    const ContactPoint single = out[first];
    face_contacts.clear();
    for (const bool lo_reference : {true, false}) {
      const int reference = lo_reference ? pair.lo : pair.hi;
      const int incident = lo_reference ? pair.hi : pair.lo;
      supporting_faces(reference, lo_reference ? single.n_G : Eigen::Vector3d(-single.n_G), faces);
      if (faces.empty()) continue;
      incident_vertices(incident, vertices_G);
      const std::size_t before = face_contacts.size();
      for (const FlatFace& face : faces)
        face_vertex_contacts(face, vertices_G, 1.5 * single.depth_m + kFaceSlack_m, kFaceSlack_m,
                             face_contacts);
      if (!lo_reference)  // every normal from lo to hi, as emit_face_contacts takes lo's
        for (std::size_t k = before; k < face_contacts.size(); ++k) face_contacts[k].n_G = -face_contacts[k].n_G;
    }
    if (face_contacts.empty()) return;  // an edge or a corner: MPR's point stays
    out.resize(first);
    emit_face_contacts(pair, pair.lo, out);
  }

  bool segment_pair(const BodyPair& pair) const {
    const ShapeKind a = bodies[static_cast<std::size_t>(pair.lo)].shape;
    const ShapeKind b = bodies[static_cast<std::size_t>(pair.hi)].shape;
    return (a == ShapeKind::kCapsule && is_round(b)) || (b == ShapeKind::kCapsule && is_round(a));
  }

  RoundBody round_body(int body) const {
    const Body& b = bodies[static_cast<std::size_t>(body)];
    RoundBody r;
    r.kind = b.shape == ShapeKind::kCapsule ? RoundBody::Kind::kCapsule : RoundBody::Kind::kCylinder;
    r.X_GB = objects[static_cast<std::size_t>(body)]->getTransform();
    r.radius_m = b.radius_m;
    r.half_length_m = b.half_length_m;
    return r;
  }

  // True when decided here (a point appended, or apart); false leaves the pair to MPR.
  bool segment_narrowphase(const BodyPair& pair, std::size_t first, std::vector<ContactPoint>& out) {
    // the capsule is the first capsule of the pair; the other body its round partner
    const bool lo_capsule = bodies[static_cast<std::size_t>(pair.lo)].shape == ShapeKind::kCapsule;
    const int capsule = lo_capsule ? pair.lo : pair.hi;
    const int other = lo_capsule ? pair.hi : pair.lo;
    const Body& c = bodies[static_cast<std::size_t>(capsule)];
    const Eigen::Isometry3d& X_GC = objects[static_cast<std::size_t>(capsule)]->getTransform();
    const Eigen::Vector3d axis_G = X_GC.linear().col(2) * c.half_length_m;
    const SegmentContact s = segment_contact(X_GC.translation() - axis_G,
                                             X_GC.translation() + axis_G, c.radius_m,
                                             round_body(other));
    if (!s.resolved) return false;
    if (s.depth_m <= kMprTolerance_m) return true;  // apart or only touching
    // n from body lo to body hi; s.n_G points out of `other` toward the capsule
    const Eigen::Vector3d n_ab = other == pair.lo ? s.n_G : Eigen::Vector3d(-s.n_G);
    out.push_back({pair.lo, pair.hi, s.p_G, n_ab, s.depth_m});
    finish_manifold(pair, first, out);
    return true;
  }

  // MPR's (or the face test's) single point of a flat contact becomes a manifold (see the header
  // comment).
  void finish_manifold(const BodyPair& pair, std::size_t first, std::vector<ContactPoint>& out) {
    if (out.size() == first + 1 && wants_manifold(pair)) {
      const ContactPoint single = out.back();
      out.pop_back();
      if (!manifold(pair, single.n_G, out)) out.push_back(single);
    }
  }

  // The least overlap of a box and a round body over the box's three face normals, each taken
  // toward the round body's centre: a separating axis when not positive.
  struct FaceOverlap {
    int box = -1;
    int round = -1;
    int axis = -1;                                  // of the box
    double sign = 1.0;                              // the face on that axis facing the round body
    Eigen::Vector3d u_G = Eigen::Vector3d::Zero();  // its normal, from the box toward the round body
    double depth_m = 0.0;
    Eigen::Vector3d q_G = Eigen::Vector3d::Zero();  // the round body's deepest point along -u
  };

  FaceOverlap least_face_overlap(const BodyPair& pair) const {
    FaceOverlap f;
    const bool box_is_lo = bodies[static_cast<std::size_t>(pair.lo)].shape == ShapeKind::kBox;
    f.box = box_is_lo ? pair.lo : pair.hi;
    f.round = box_is_lo ? pair.hi : pair.lo;
    const Eigen::Isometry3d& X_GB = objects[static_cast<std::size_t>(f.box)]->getTransform();
    const Eigen::Matrix3d& R = X_GB.linear();
    const Eigen::Vector3d to_round = objects[static_cast<std::size_t>(f.round)]->getTranslation() -
                                     X_GB.translation();
    for (int i = 0; i < 3; ++i) {
      const double s = R.col(i).dot(to_round) >= 0.0 ? 1.0 : -1.0;
      const Eigen::Vector3d u = s * R.col(i);
      const double d = support(f.box, u).dot(u) - support(f.round, -u).dot(u);
      if (f.axis < 0 || d < f.depth_m) {
        f.axis = i;
        f.sign = s;
        f.u_G = u;
        f.depth_m = d;
      }
    }
    f.q_G = support(f.round, -f.u_G);
    return f;
  }

  // A face contact, without MPR, where the answer is certain (most resting contacts): the round
  // body's deepest point q lies in the box no nearer any other face than the least overlap d.
  // Every direction's overlap is then at least q's distance from the box's boundary, d, so (u, d)
  // is the penetration itself, what MPR converges to. Otherwise (an edge, a corner, a deep
  // overlap) MPR decides.
  bool face_contact_is_certain(const FaceOverlap& f) const {
    const Body& b = bodies[static_cast<std::size_t>(f.box)];
    const Eigen::Isometry3d& X_GB = objects[static_cast<std::size_t>(f.box)]->getTransform();
    const Eigen::Vector3d q_B = X_GB.linear().transpose() * (f.q_G - X_GB.translation());
    for (int j = 0; j < 3; ++j) {
      // q's distance from the other faces: the far face of the axis, both faces of the others
      const double to_faces = j == f.axis ? b.half_size_m[j] + f.sign * q_B[j]
                                          : b.half_size_m[j] - std::abs(q_B[j]);
      if (to_faces < f.depth_m) return false;
    }
    return true;
  }

  // The contact along the face normal: midway between the surfaces, under the round body's
  // deepest point; the normal from body lo to body hi.
  ContactPoint face_contact(const BodyPair& pair, const FaceOverlap& f) const {
    ContactPoint c;
    c.body_a = pair.lo;
    c.body_b = pair.hi;
    c.n_G = f.box == pair.lo ? f.u_G : Eigen::Vector3d(-f.u_G);
    c.depth_m = f.depth_m;
    c.p_G = f.q_G + (0.5 * f.depth_m) * f.u_G;
    return c;
  }

  static bool is_round(ShapeKind k) { return k == ShapeKind::kCylinder || k == ShapeKind::kCapsule; }

  bool box_and_round(const BodyPair& pair) const {
    const ShapeKind a = bodies[static_cast<std::size_t>(pair.lo)].shape;
    const ShapeKind b = bodies[static_cast<std::size_t>(pair.hi)].shape;
    return (a == ShapeKind::kBox && is_round(b)) || (b == ShapeKind::kBox && is_round(a));
  }

  // The farthest point of a body along d (world), for the shapes the collision world holds.
  Eigen::Vector3d support(int body, const Eigen::Vector3d& d) const {
    const Body& b = bodies[static_cast<std::size_t>(body)];
    const Eigen::Isometry3d& X = objects[static_cast<std::size_t>(body)]->getTransform();
    const Eigen::Vector3d c = X.translation();
    const Eigen::Vector3d a = X.linear().col(2);
    const double along = d.dot(a);
    switch (b.shape) {
      case ShapeKind::kBox: {
        const Eigen::Vector3d local = X.linear().transpose() * d;
        Eigen::Vector3d v;
        for (int i = 0; i < 3; ++i) v[i] = local[i] >= 0.0 ? b.half_size_m[i] : -b.half_size_m[i];
        return X * v;
      }
      case ShapeKind::kSphere:
        return c + b.radius_m * d.normalized();
      case ShapeKind::kCapsule:
        return c + (along >= 0.0 ? b.half_length_m : -b.half_length_m) * a + b.radius_m * d.normalized();
      case ShapeKind::kCylinder: {
        const Eigen::Vector3d across = d - along * a;
        const double norm = across.norm();
        Eigen::Vector3d p = c + (along >= 0.0 ? b.half_length_m : -b.half_length_m) * a;
        if (norm > 1e-12) p += (b.radius_m / norm) * across;
        return p;
      }
      case ShapeKind::kMesh:  // (asked only of a box and a round body)
        break;
    }
    return c;
  }

  bool wants_manifold(const BodyPair& pair) const {
    return physics::wants_manifold(bodies[static_cast<std::size_t>(pair.lo)].shape,
                                   bodies[static_cast<std::size_t>(pair.hi)].shape);
  }

  // A body as the manifold clipper sees it.
  ClipBody clip_body(int body) const {
    const Body& b = bodies[static_cast<std::size_t>(body)];
    return {b.shape, objects[static_cast<std::size_t>(body)]->getTransform(), b.radius_m,
            b.half_length_m, b.half_size_m};
  }

  // Appends the pair's manifold for FCL's normal n_ab; false (nothing appended) when the contact
  // is not a face contact or nothing survives clipping.
  bool manifold(const BodyPair& pair, const Eigen::Vector3d& n_ab, std::vector<ContactPoint>& out) {
    const int kept = clipper.clip(clip_body(pair.lo), clip_body(pair.hi), n_ab, manifold_points);
    for (int i = 0; i < kept; ++i) {
      const ManifoldPoint& p = manifold_points[static_cast<std::size_t>(i)];
      out.push_back({pair.lo, pair.hi, p.p_G, n_ab, p.depth_m});
    }
    return kept > 0;
  }

  // FCL 0.7's sphere-capsule routine puts the point at the capsule's axis point moved `depth`
  // toward the sphere, i.e. inside the capsule, a capsule radius away from the overlap. That
  // skews friction torques, so it is replaced by the midpoint of the overlap along the normal,
  // as FCL's other closed-form pairs place it: the sphere's deepest point backed off depth / 2.
  Eigen::Vector3d contact_point(const BodyPair& pair, const Eigen::Vector3d& p_fcl,
                                const Eigen::Vector3d& n_ab, double depth_m) const {
    const Body& a = bodies[static_cast<std::size_t>(pair.lo)];
    const Body& b = bodies[static_cast<std::size_t>(pair.hi)];
    const bool a_sphere = a.shape == ShapeKind::kSphere && b.shape == ShapeKind::kCapsule;
    const bool b_sphere = b.shape == ShapeKind::kSphere && a.shape == ShapeKind::kCapsule;
    if (!a_sphere && !b_sphere) return p_fcl;
    const Body& sphere = a_sphere ? a : b;
    const Eigen::Vector3d n_sc = a_sphere ? n_ab : Eigen::Vector3d(-n_ab);  // sphere -> capsule
    const Eigen::Vector3d c_s = objects[static_cast<std::size_t>(sphere.index)]->getTranslation();
    return c_s + (sphere.radius_m - 0.5 * depth_m) * n_sc;
  }
};

CollisionWorld::CollisionWorld(const Scene& scene) : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  object_count_ = static_cast<int>(scene.objects.size());
  hand_count_ = static_cast<int>(scene.hands.size());
  require(scene.contact.max_points_per_pair >= 1, "contact.max_points_per_pair must be >= 1");

  const std::size_t body_count =
      scene.objects.size() + static_cast<std::size_t>(hand_count_ * kLinkCount);
  m.bodies.reserve(body_count);
  m.objects.reserve(body_count);

  for (const ObjectSpec& spec : scene.objects)
    m.add_body(object_geometry(spec), spec.X_GO,
               spec.control >= 0 ? BodyKind::kControl
                                 : (spec.dynamic ? BodyKind::kDynamic : BodyKind::kStatic),
               spec.shape);

  m.X_LC.resize(scene.hands.size());
  for (std::size_t h = 0; h < scene.hands.size(); ++h) {
    const HandModel& hand = scene.hands[h];
    std::array<Eigen::Isometry3d, kLinkCount>& X_LC_h = m.X_LC[h];
    require((hand.palm_size_m.array() > 0.0).all(), "hand palm size must be positive");
    // link frames start at the identity; the hand stays disabled until the first set_poses
    X_LC_h[static_cast<std::size_t>(Link::kPalm)] = Eigen::Isometry3d::Identity();
    m.add_body(std::make_shared<fcl::Boxd>(hand.palm_size_m), Eigen::Isometry3d::Identity(),
               BodyKind::kHand, Shape::box(hand.palm_size_m));
    for (int l = 1; l < kLinkCount; ++l) {
      const Capsule& capsule = hand.capsules[static_cast<std::size_t>(l)];
      require(capsule.radius_m > 0.0 && capsule.length_m >= 0.0,
              "bad capsule for hand link " + std::string(link_name(static_cast<Link>(l))));
      // the capsule spans [0, length] on x_L; FCL's is centred on its own z
      Eigen::Isometry3d X_LC = Eigen::Isometry3d::Identity();
      X_LC.translation() = Eigen::Vector3d(0.5 * capsule.length_m, 0.0, 0.0);
      X_LC.linear() = z_onto_x();
      X_LC_h[static_cast<std::size_t>(l)] = X_LC;
      m.add_body(std::make_shared<fcl::Capsuled>(capsule.radius_m, capsule.length_m), X_LC,
                 BodyKind::kHand, Shape::capsule(capsule.radius_m, capsule.length_m));
    }
  }

  // user data only once the vector is final
  for (std::size_t i = 0; i < m.objects.size(); ++i) m.objects[i]->setUserData(&m.bodies[i]);
  std::vector<BodyKind> kinds;
  for (const Body& b : m.bodies) kinds.push_back(b.kind);
  m.broadphase = std::make_unique<SweepAndPrune>(std::move(kinds));
  report_hand_static_ = hand_count_ > 0 && scene.proxy.enabled;
  m.broadphase->set_report_hand_static(report_hand_static_);
  for (std::size_t i = 0; i < m.objects.size(); ++i)
    m.place(static_cast<int>(i), m.objects[i]->getTransform());

  m.pairs.reserve(8 * body_count);
  m.request = fcl::CollisionRequestd(static_cast<std::size_t>(scene.contact.max_points_per_pair),
                                     /*enable_contact=*/true);
  m.request.gjk_tolerance = kMprTolerance_m;
  m.mesh_request = fcl::CollisionRequestd(kMeshTriangles, /*enable_contact=*/true);
  m.mesh_request.gjk_tolerance = kMprTolerance_m;
  m.max_points = scene.contact.max_points_per_pair;
  m.clipper = ManifoldClipper(std::min(scene.contact.max_points_per_pair, kMaxManifold));
  m.contact_capacity = 4 * body_count * static_cast<std::size_t>(scene.contact.max_points_per_pair);
}

CollisionWorld::~CollisionWorld() = default;

void CollisionWorld::set_object_poses(const std::vector<Eigen::Isometry3d>& X_GO) {
  Impl& m = *impl_;
  VCOCKPIT_ASSERT(static_cast<int>(X_GO.size()) == object_count_, "one pose per object");
  const int n = std::min(object_count_, static_cast<int>(X_GO.size()));
  for (int i = 0; i < n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    // a body where it was placed last keeps its transform and box (a resting control or object)
    if (m.bodies[k].kind != BodyKind::kStatic &&
        !(m.objects[k]->getTransform().matrix() == X_GO[k].matrix()))
      m.place(i, X_GO[k]);
  }
}

void CollisionWorld::set_hand_poses(int hand, const std::array<Eigen::Isometry3d, kLinkCount>* X_GL) {
  Impl& m = *impl_;
  VCOCKPIT_ASSERT(0 <= hand && hand < hand_count_, "a hand of this world");
  const bool enabled = X_GL != nullptr;
  for (int l = 0; l < kLinkCount; ++l) {
    const int body = hand_link_body(hand, static_cast<Link>(l));
    m.broadphase->set_enabled(body, enabled);
    if (enabled)
      m.place(body, (*X_GL)[static_cast<std::size_t>(l)] *
                        m.X_LC[static_cast<std::size_t>(hand)][static_cast<std::size_t>(l)]);
  }
}

void CollisionWorld::set_poses(const std::vector<Eigen::Isometry3d>& X_GO,
                               const std::array<Eigen::Isometry3d, kLinkCount>* X_GL) {
  set_object_poses(X_GO);
  if (hand_count_ > 0) set_hand_poses(0, X_GL);
}

void CollisionWorld::find_candidate_pairs() {
  Impl& m = *impl_;
  m.broadphase->find_pairs(m.pairs);
}

void CollisionWorld::compute_contacts(std::vector<ContactPoint>& out,
                                      std::vector<ContactPoint>* hand_static) {
  Impl& m = *impl_;
  out.clear();
  if (out.capacity() < m.contact_capacity) out.reserve(m.contact_capacity);
  if (hand_static != nullptr) {
    hand_static->clear();
    if (hand_static->capacity() < 64) hand_static->reserve(64);
  }
  for (const BodyPair& pair : m.pairs) {
    const bool hand_pair = pair.lo < object_count_ && pair.hi >= object_count_;
    if (hand_pair && m.bodies[static_cast<std::size_t>(pair.lo)].kind == BodyKind::kStatic) {
      if (hand_static != nullptr) m.narrowphase(pair, *hand_static);
      continue;
    }
    m.narrowphase(pair, out);
  }
}

void CollisionWorld::compute_hand_static_contacts(
    int hand, const std::array<Eigen::Isometry3d, kLinkCount>& X_GL, std::vector<ContactPoint>& out) {
  Impl& m = *impl_;
  out.clear();
  if (hand < 0 || hand >= hand_count_) return;
  for (int l = 0; l < kLinkCount; ++l) {
    const int body = hand_link_body(hand, static_cast<Link>(l));
    m.objects[static_cast<std::size_t>(body)]->setTransform(
        X_GL[static_cast<std::size_t>(l)] *
        m.X_LC[static_cast<std::size_t>(hand)][static_cast<std::size_t>(l)]);
  }
  const int first = hand_link_body(hand, Link::kPalm);
  for (const BodyPair& pair : m.pairs) {
    if (pair.lo < object_count_ && pair.hi >= first && pair.hi < first + kLinkCount &&
        m.bodies[static_cast<std::size_t>(pair.lo)].kind == BodyKind::kStatic)
      m.narrowphase(pair, out);
  }
}

void CollisionWorld::set_object_asleep(int object, bool asleep) {
  VCOCKPIT_ASSERT(0 <= object && object < object_count_, "an object of this world");
  impl_->broadphase->set_asleep(object, asleep);
}

Aabb CollisionWorld::hand_link_box(int hand, Link link, const Eigen::Isometry3d& X_GL) const {
  const Impl& m = *impl_;
  const auto l = static_cast<std::size_t>(link);
  return shape_aabb(m.shapes[static_cast<std::size_t>(hand_link_body(hand, link))],
                    X_GL * m.X_LC[static_cast<std::size_t>(hand)][l]);
}

bool CollisionWorld::link_overlaps(int hand, Link link, const Eigen::Isometry3d& X_GL,
                                   int object) const {
  const Impl& m = *impl_;
  VCOCKPIT_ASSERT(0 <= hand && hand < hand_count_ && 0 <= object && object < object_count_,
                  "a hand link and an object");
  const auto body = static_cast<std::size_t>(hand_link_body(hand, link));
  const auto o = static_cast<std::size_t>(object);
  if (!hand_link_box(hand, link, X_GL).overlaps(shape_aabb(m.shapes[o], m.objects[o]->getTransform())))
    return false;
  // (FCL hands out its geometry as const; the probe never changes it)
  const fcl::CollisionObjectd probe(
      std::const_pointer_cast<fcl::CollisionGeometryd>(m.objects[body]->collisionGeometry()),
      X_GL * m.X_LC[static_cast<std::size_t>(hand)][static_cast<std::size_t>(link)]);
  const fcl::CollisionRequestd request;  // yes or no: no contacts wanted
  fcl::CollisionResultd result;
  fcl::collide(&probe, m.objects[o].get(), request, result);
  return result.isCollision();
}

bool CollisionWorld::link_within(int hand, Link link, const Eigen::Isometry3d& X_GL, int object,
                                 double gap_m) const {
  const Impl& m = *impl_;
  VCOCKPIT_ASSERT(0 <= hand && hand < hand_count_ && 0 <= object && object < object_count_,
                  "a hand link and an object");
  const auto o = static_cast<std::size_t>(object);
  Aabb box = hand_link_box(hand, link, X_GL);
  box.lo.array() -= gap_m;
  box.hi.array() += gap_m;
  if (!box.overlaps(shape_aabb(m.shapes[o], m.objects[o]->getTransform()))) return false;
  return link_gap_m(hand, link, X_GL, object) <= gap_m;
}

double CollisionWorld::link_gap_m(int hand, Link link, const Eigen::Isometry3d& X_GL, int object) const {
  const Impl& m = *impl_;
  VCOCKPIT_ASSERT(0 <= hand && hand < hand_count_ && 0 <= object && object < object_count_,
                  "a hand link and an object");
  const auto body = static_cast<std::size_t>(hand_link_body(hand, link));
  const auto o = static_cast<std::size_t>(object);
  const Eigen::Isometry3d X_GC =
      X_GL * m.X_LC[static_cast<std::size_t>(hand)][static_cast<std::size_t>(link)];
  const Body& link_body = m.bodies[body];
  if (link_body.shape == ShapeKind::kCapsule && Impl::is_round(m.bodies[o].shape)) {
    // a capsule link and a cylinder or capsule: closest points (segment_contact.hpp), as the
    // narrowphase finds them; a segment reaching inside the body overlaps it
    const Eigen::Vector3d axis_G = X_GC.linear().col(2) * link_body.half_length_m;
    const SegmentContact s = segment_contact(X_GC.translation() - axis_G,
                                             X_GC.translation() + axis_G, link_body.radius_m,
                                             m.round_body(object));
    return s.resolved ? std::max(0.0, -s.depth_m) : 0.0;
  }
  const fcl::CollisionObjectd probe(
      std::const_pointer_cast<fcl::CollisionGeometryd>(m.objects[body]->collisionGeometry()),
      X_GC);
  const fcl::DistanceRequestd request;
  fcl::DistanceResultd result;
  fcl::distance(&probe, m.objects[o].get(), request, result);
  return std::max(0.0, result.min_distance);  // (an overlap gives zero or less)
}

std::size_t CollisionWorld::candidate_pair_count() const { return impl_->pairs.size(); }

std::uint64_t CollisionWorld::skipped_contacts() const { return impl_->skipped; }

}  // namespace vcockpit::physics
