#pragma once
// Contact manifolds for flat contacts of round shapes (box-cylinder, box-capsule,
// cylinder-cylinder, cylinder-capsule). libccd's MPR gives ONE point for a cylinder standing on a
// box face, a cylinder or capsule lying on one, a cup on a cup; one point gives no torsional or
// rocking support, so those pairs get a manifold built from the narrowphase's normal n (kept as
// it is) in the spirit of Jolt's and Bullet's face clipping:
// - Reference face: the face of one body that n is perpendicular to (|n . face normal| >=
//   kFaceAlignCos): a box face first, else a cylinder's cap (the larger cylinder's first). For a
//   face contact MPR's normal is exactly the face's (the Minkowski difference is flat there); a
//   normal off every face means an edge or rim contact, which keeps FCL's single point.
// - Incident feature of the other body, the part facing the reference along -n: a cylinder's
//   cap rim (kRimVertices points fixed on the body, plus the rim's exact deepest point) when its
//   axis is within 45 deg of n, else the two ends of its side line (exact, the deeper one is the
//   deepest point); a capsule's two segment-end spheres' deepest points.
// - The incident polygon (or segment) is clipped to the reference face's extent (Sutherland-
//   Hodgman against the face's side planes: a box face's rectangle, or a cap's circumscribed
//   kReferenceCapSides-gon), so an overhang keeps the part over the face plus the crossing points.
// - Each point's depth is its distance below the reference body's supporting plane along n (the
//   plane through its extreme point along n), so the deepest point's depth is the overlap along n,
//   which is MPR's depth; points with depth <= 0 are dropped. A point is reported midway between
//   the surfaces (q + depth/2 n, as FCL places its points), with the narrowphase's normal.
// - Reduction to max_points (at most 4): the deepest (ties go to the lower index, so a level cup
//   keeps the same 4 rim points and its friction anchors), the farthest from it, then the points
//   adding the most area (Bullet's and Jolt's rule). Near-duplicates are never picked: a single
//   penetrating rim point stays one point. The tie (1e-4 of the depth, at most 0.1 um) keeps the
//   reported depth within 0.1 um of MPR's.
// If nothing survives (or the features are unsupported) the caller keeps its single point.
// Plain Eigen in and out (no FCL), fixed-size work space, no allocation.

#include <Eigen/Geometry>
#include <array>

#include "physics_node/physics/face_vertex_contacts.hpp"
#include "physics_node/physics/scene.hpp"

namespace vcockpit::physics {

constexpr int kRimVertices = 8;         // a cap rim as the incident feature
constexpr int kReferenceCapSides = 16;  // a cap as the reference face: circumscribed polygon
constexpr int kMaxPolygon = kRimVertices + kReferenceCapSides + 8;  // clipping adds <= 1 a plane
constexpr int kMaxCandidates = kMaxPolygon + 1;                     // + a rim's deepest point
constexpr int kMaxManifold = 4;

// A body as the clipper sees it: its shape centred on its frame, the axis along z.
struct ClipBody {
  ShapeKind shape = ShapeKind::kBox;
  Eigen::Isometry3d X_GB = Eigen::Isometry3d::Identity();
  double radius_m = 0.0;                                  // cylinder and capsule
  double half_length_m = 0.0;                             // cylinder; capsule without its end caps
  Eigen::Vector3d half_size_m = Eigen::Vector3d::Zero();  // box
};

// One manifold point: midway between the surfaces, and how deep (m, > 0).
struct ManifoldPoint {
  Eigen::Vector3d p_G = Eigen::Vector3d::Zero();
  double depth_m = 0.0;
};

// The reference face: inside its extent iff side_n[k] . p <= side_d[k] for every side; a point
// p of the other body is top_m - n_RI . p deep into the reference body (n_RI from it outward).
struct ReferenceFace {
  std::array<Eigen::Vector3d, kReferenceCapSides> side_n;
  std::array<double, kReferenceCapSides> side_d{};
  int sides = 0;
  double top_m = 0.0;
  // a cap: the sides are tangent to this disk, so a point over the disk is inside them all
  bool disk = false;
  Eigen::Vector3d disk_centre = Eigen::Vector3d::Zero();
  Eigen::Vector3d disk_axis = Eigen::Vector3d::UnitZ();
  double disk_radius_m = 0.0;

  bool over_disk(const Eigen::Vector3d& p) const {
    const Eigen::Vector3d d = p - disk_centre;
    const double along = d.dot(disk_axis);
    return d.squaredNorm() - along * along <= disk_radius_m * disk_radius_m;
  }
};

// The incident feature: a convex polygon (or a segment) on the other body's surface, plus
// optionally one more point (a cap rim's exact deepest point) tested on its own.
struct IncidentFeature {
  std::array<Eigen::Vector3d, kMaxPolygon> v;
  int count = 0;
  bool segment = false;
  bool has_extra = false;
  Eigen::Vector3d extra = Eigen::Vector3d::Zero();
};

struct Candidate {
  Eigen::Vector3d q = Eigen::Vector3d::Zero();  // on the incident body's surface
  double depth_m = 0.0;
};

// Whether the flat contacts of two shapes get a manifold (a box or a cylinder with a round body).
bool wants_manifold(ShapeKind a, ShapeKind b);

// At most max_out (<= 4) spread points of `cand`: the deepest (ties to the lower index), the
// farthest from it, the one making the largest triangle with those two, and the one adding the
// most area outside that triangle. Near-duplicates and collinear extras are never picked.
// Indices into cand in `pick`; returns how many.
int reduce_manifold(const std::array<Candidate, kMaxCandidates>& cand, int n,
                    const Eigen::Vector3d& normal, int max_out,
                    std::array<int, kMaxManifold>& pick);

class ManifoldClipper {
 public:
  explicit ManifoldClipper(int max_points = kMaxManifold);  // clamped to [1, kMaxManifold]

  // The manifold of bodies a and b for the unit normal n_ab (from a to b) into `out`, the deepest
  // first; returns its size, 0 when the contact is not a face contact or nothing survives.
  int clip(const ClipBody& a, const ClipBody& b, const Eigen::Vector3d& n_ab,
           std::array<ManifoldPoint, kMaxManifold>& out);

  // The manifold of a round body (a cylinder or capsule) on a flat convex face of another body
  // (a static mesh's triangle, which FCL touches at one point): the round body's feature facing
  // the face clipped to the face's sides, each point's depth below the face's plane along its
  // normal (face.n_G, out of the face toward the round body), kept when in (0, max_depth_m]
  // (deeper is past a thin part's far side). Midway points, the deepest first; 0 when nothing
  // survives or `round` is not a cylinder or capsule.
  int clip_on_face(const FlatFace& face, const ClipBody& round, double max_depth_m,
                   std::array<ManifoldPoint, kMaxManifold>& out);

 private:
  int max_points_;
  // work space, kept between calls so nothing is allocated or zeroed per pair
  ReferenceFace reference_;
  IncidentFeature incident_;
  std::array<Eigen::Vector3d, kMaxPolygon> clip_scratch_;
  std::array<Candidate, kMaxCandidates> candidates_;
  std::array<int, kMaxManifold> picked_{};
};

}  // namespace vcockpit::physics
