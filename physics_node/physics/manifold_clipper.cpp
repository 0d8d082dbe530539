#include "physics_node/physics/manifold_clipper.hpp"

#include <algorithm>
#include <cmath>

// The arithmetic here moved verbatim out of collision.cpp: every expression is as it was, so the
// manifolds are bit-identical to what they were.

namespace vcockpit::physics {
namespace {

constexpr double kFaceAlignCos = 0.9999;  // n within 0.81 deg of a face's normal
constexpr double kCapFacingCos = 0.70710678118654752;  // |axis . n| >= cos 45 deg: the cap faces
constexpr double kMinSpread_m = 1e-6;     // closer points (or thinner triangles) are one point
constexpr double kDepthTieRel = 1e-4;     // depths this close (relative, and at most
constexpr double kDepthTieMax_m = 1e-7;   // this far apart) count as equal for the deepest
constexpr double kTieRel = 1e-9;          // distances and areas this close count as equal

struct Unit2 {
  double c = 1.0;
  double s = 0.0;
};

template <int N>
std::array<Unit2, N> polygon_directions() {
  std::array<Unit2, N> out{};
  constexpr double kPi = 3.14159265358979323846;
  for (int k = 0; k < N; ++k) {
    const double angle = 2.0 * kPi * k / N;
    out[static_cast<std::size_t>(k)] = {std::cos(angle), std::sin(angle)};
  }
  return out;
}

const std::array<Unit2, kRimVertices>& rim_directions() {
  static const std::array<Unit2, kRimVertices> table = polygon_directions<kRimVertices>();
  return table;
}
const std::array<Unit2, kReferenceCapSides>& cap_side_directions() {
  static const std::array<Unit2, kReferenceCapSides> table =
      polygon_directions<kReferenceCapSides>();
  return table;
}

// The box face whose normal n_RI (from the box toward the other body) is along.
bool box_reference(const ClipBody& box, const Eigen::Isometry3d& X, const Eigen::Vector3d& n_RI,
                   ReferenceFace& ref) {
  const Eigen::Matrix3d R = X.linear();
  const Eigen::Vector3d c = X.translation();
  int face_axis = 0;
  double best = -1.0;
  ref.top_m = n_RI.dot(c);
  for (int i = 0; i < 3; ++i) {
    const double along = std::abs(R.col(i).dot(n_RI));
    ref.top_m += along * box.half_size_m[i];
    if (along > best) {
      best = along;
      face_axis = i;
    }
  }
  if (best < kFaceAlignCos) return false;
  ref.sides = 0;
  ref.disk = false;
  for (int i = 0; i < 3; ++i) {
    if (i == face_axis) continue;
    const Eigen::Vector3d u = R.col(i);
    const double uc = u.dot(c);
    ref.side_n[static_cast<std::size_t>(ref.sides)] = u;
    ref.side_d[static_cast<std::size_t>(ref.sides++)] = uc + box.half_size_m[i];
    ref.side_n[static_cast<std::size_t>(ref.sides)] = -u;
    ref.side_d[static_cast<std::size_t>(ref.sides++)] = -uc + box.half_size_m[i];
  }
  return true;
}

// The cylinder cap n_RI is along (either cap: the one facing the other body).
bool cap_reference(const ClipBody& cylinder, const Eigen::Isometry3d& X,
                   const Eigen::Vector3d& n_RI, ReferenceFace& ref) {
  const Eigen::Matrix3d R = X.linear();
  const Eigen::Vector3d c = X.translation();
  const Eigen::Vector3d a = R.col(2);
  const double an = a.dot(n_RI);
  if (std::abs(an) < kFaceAlignCos) return false;
  const Eigen::Vector3d cap = c + (an > 0.0 ? cylinder.half_length_m : -cylinder.half_length_m) * a;
  const Eigen::Vector3d e1 = R.col(0), e2 = R.col(1);
  const auto& dirs = cap_side_directions();
  for (int k = 0; k < kReferenceCapSides; ++k) {
    const Unit2& d = dirs[static_cast<std::size_t>(k)];
    const Eigen::Vector3d m = d.c * e1 + d.s * e2;
    ref.side_n[static_cast<std::size_t>(k)] = m;
    ref.side_d[static_cast<std::size_t>(k)] = m.dot(cap) + cylinder.radius_m;
  }
  ref.sides = kReferenceCapSides;
  ref.disk = true;
  ref.disk_centre = cap;
  ref.disk_axis = a;
  ref.disk_radius_m = cylinder.radius_m;
  ref.top_m = n_RI.dot(c) + cylinder.half_length_m * std::abs(an) +
              cylinder.radius_m * std::sqrt(std::max(0.0, 1.0 - an * an));
  return true;
}

// A cylinder's feature facing direction w (unit, toward the reference body).
void cylinder_incident(const ClipBody& cylinder, const Eigen::Isometry3d& X,
                       const Eigen::Vector3d& w, IncidentFeature& inc) {
  const Eigen::Matrix3d R = X.linear();
  const Eigen::Vector3d c = X.translation();
  const Eigen::Vector3d a = R.col(2);
  const double aw = a.dot(w);
  const Eigen::Vector3d w_side = w - aw * a;  // w across the axis
  const double w_side_norm = w_side.norm();
  const double r = cylinder.radius_m;
  if (std::abs(aw) >= kCapFacingCos) {
    // the cap: rim points fixed on the body (a level cup keeps the same ones), and the rim's
    // deepest point when tilted (between two rim points it is deeper than both)
    const double side = aw >= 0.0 ? 1.0 : -1.0;
    const Eigen::Vector3d cap = c + side * cylinder.half_length_m * a;
    const Eigen::Vector3d e1 = R.col(0), e2 = R.col(1);
    const auto& dirs = rim_directions();
    for (int k = 0; k < kRimVertices; ++k) {
      const Unit2& d = dirs[static_cast<std::size_t>(k)];
      inc.v[static_cast<std::size_t>(k)] = cap + r * (d.c * e1 + d.s * e2);
    }
    inc.count = kRimVertices;
    inc.segment = false;
    inc.has_extra = w_side_norm > 1e-12;
    if (inc.has_extra) inc.extra = cap + (r / w_side_norm) * w_side;
  } else {
    // the side: the line of the side nearest the reference, end to end (w_side_norm >= 0.7)
    const Eigen::Vector3d out = (r / w_side_norm) * w_side;
    inc.v[0] = c - cylinder.half_length_m * a + out;
    inc.v[1] = c + cylinder.half_length_m * a + out;
    inc.count = 2;
    inc.segment = true;
    inc.has_extra = false;
  }
}

// A capsule's feature facing w: the deepest points of its two end spheres.
void capsule_incident(const ClipBody& capsule, const Eigen::Isometry3d& X, const Eigen::Vector3d& w,
                      IncidentFeature& inc) {
  const Eigen::Vector3d a = X.linear().col(2);
  const Eigen::Vector3d c = X.translation();
  inc.v[0] = c - capsule.half_length_m * a + capsule.radius_m * w;
  inc.v[1] = c + capsule.half_length_m * a + capsule.radius_m * w;
  inc.count = 2;
  inc.segment = true;
  inc.has_extra = false;
}

// Sutherland-Hodgman: the convex polygon `in` clipped to m . p <= d, into `out`.
int clip_polygon(const Eigen::Vector3d* in, int count, const Eigen::Vector3d& m, double d,
                 Eigen::Vector3d* out) {
  int n_out = 0;
  for (int i = 0; i < count; ++i) {
    const Eigen::Vector3d& p = in[i];
    const Eigen::Vector3d& q = in[i + 1 < count ? i + 1 : 0];
    const double fp = m.dot(p) - d;
    const double fq = m.dot(q) - d;
    if (fp <= 0.0 && n_out < kMaxPolygon) out[n_out++] = p;
    if (((fp < 0.0 && fq > 0.0) || (fp > 0.0 && fq < 0.0)) && n_out < kMaxPolygon)
      out[n_out++] = p + (fp / (fp - fq)) * (q - p);
  }
  return n_out;
}

// The incident feature clipped to the reference face's extent: the surviving points with their
// depths (> 0) in `cand`, in a fixed order.
int clip_to_reference(const ReferenceFace& ref, IncidentFeature& inc, const Eigen::Vector3d& n_RI,
                      std::array<Eigen::Vector3d, kMaxPolygon>& scratch,
                      std::array<Candidate, kMaxCandidates>& cand) {
  int count = inc.count;
  if (inc.segment) {
    // the segment v0 + t (v1 - v0), t in [t0, t1]
    double t0 = 0.0, t1 = 1.0;
    for (int k = 0; k < ref.sides && t0 <= t1; ++k) {
      const Eigen::Vector3d& m = ref.side_n[static_cast<std::size_t>(k)];
      const double d = ref.side_d[static_cast<std::size_t>(k)];
      const double f0 = m.dot(inc.v[0]) - d;
      const double f1 = m.dot(inc.v[1]) - d;
      if (f0 > 0.0 && f1 > 0.0) {
        t0 = 1.0;
        t1 = 0.0;
      } else if (f0 > 0.0) {
        t0 = std::max(t0, f0 / (f0 - f1));
      } else if (f1 > 0.0) {
        t1 = std::min(t1, f0 / (f0 - f1));
      }
    }
    if (t0 > t1) {
      count = 0;
    } else {
      const Eigen::Vector3d v0 = inc.v[0], dv = inc.v[1] - inc.v[0];
      inc.v[0] = v0 + t0 * dv;
      inc.v[1] = v0 + t1 * dv;
    }
  } else {
    bool all_over_disk = ref.disk;
    for (int i = 0; i < count && all_over_disk; ++i)
      all_over_disk = ref.over_disk(inc.v[static_cast<std::size_t>(i)]);
    Eigen::Vector3d* from = inc.v.data();
    Eigen::Vector3d* to = scratch.data();
    for (int k = 0; k < ref.sides && count > 0 && !all_over_disk; ++k) {
      const Eigen::Vector3d& m = ref.side_n[static_cast<std::size_t>(k)];
      const double d = ref.side_d[static_cast<std::size_t>(k)];
      bool all_inside = true;
      for (int i = 0; i < count && all_inside; ++i) all_inside = m.dot(from[i]) <= d;
      if (all_inside) continue;  // nothing to cut: skip the copy
      count = clip_polygon(from, count, m, d, to);
      std::swap(from, to);
    }
    if (from != inc.v.data())
      std::copy(from, from + count, inc.v.data());
  }

  int n = 0;
  for (int i = 0; i < count; ++i) {
    const Eigen::Vector3d& q = inc.v[static_cast<std::size_t>(i)];
    const double depth_m = ref.top_m - n_RI.dot(q);
    if (depth_m > 0.0) cand[static_cast<std::size_t>(n++)] = {q, depth_m};
  }
  if (inc.has_extra) {
    bool inside = true;
    for (int k = 0; k < ref.sides && inside; ++k)
      inside = ref.side_n[static_cast<std::size_t>(k)].dot(inc.extra) <=
               ref.side_d[static_cast<std::size_t>(k)];
    const double depth_m = ref.top_m - n_RI.dot(inc.extra);
    if (inside && depth_m > 0.0) cand[static_cast<std::size_t>(n++)] = {inc.extra, depth_m};
  }
  return n;
}

// Picks the reference face for normal n_ab (from body a to body b): a box face, else a
// cylinder cap (the larger's first). Sets which body it is (a or b); false for none.
bool choose_reference(const ClipBody& a, const ClipBody& b, const Eigen::Vector3d& n_ab,
                      ReferenceFace& ref, bool& reference_is_lo) {
  const Eigen::Isometry3d& X_a = a.X_GB;
  const Eigen::Isometry3d& X_b = b.X_GB;
  const Eigen::Vector3d n_ba = -n_ab;
  if (a.shape == ShapeKind::kBox && box_reference(a, X_a, n_ab, ref)) {
    reference_is_lo = true;
    return true;
  }
  if (b.shape == ShapeKind::kBox && box_reference(b, X_b, n_ba, ref)) {
    reference_is_lo = false;
    return true;
  }
  const bool a_cap = a.shape == ShapeKind::kCylinder;
  const bool b_cap = b.shape == ShapeKind::kCylinder;
  const bool b_first = b_cap && (!a_cap || b.radius_m > a.radius_m);
  for (int attempt = 0; attempt < 2; ++attempt) {
    const bool try_b = (attempt == 0) == b_first;
    const bool found = try_b ? b_cap && cap_reference(b, X_b, n_ba, ref)
                             : a_cap && cap_reference(a, X_a, n_ab, ref);
    if (found) {
      reference_is_lo = !try_b;
      return true;
    }
  }
  return false;
}

}  // namespace

bool wants_manifold(ShapeKind a, ShapeKind b) {
  const auto round = [](ShapeKind k) {
    return k == ShapeKind::kCylinder || k == ShapeKind::kCapsule;
  };
  if (a == ShapeKind::kBox || b == ShapeKind::kBox) return round(a) || round(b);
  return (a == ShapeKind::kCylinder && round(b)) || (b == ShapeKind::kCylinder && round(a));
}

int reduce_manifold(const std::array<Candidate, kMaxCandidates>& cand, int n,
                    const Eigen::Vector3d& normal, int max_out,
                    std::array<int, kMaxManifold>& pick) {
  if (n <= 0 || max_out <= 0) return 0;
  double deepest_m = 0.0;
  for (int i = 0; i < n; ++i)
    deepest_m = std::max(deepest_m, cand[static_cast<std::size_t>(i)].depth_m);
  const double tie_m = std::min(kDepthTieRel * deepest_m, kDepthTieMax_m);
  int p0 = 0;
  while (cand[static_cast<std::size_t>(p0)].depth_m < deepest_m - tie_m) ++p0;
  pick[0] = p0;
  if (max_out < 2) return 1;
  const auto q = [&](int i) -> const Eigen::Vector3d& {
    return cand[static_cast<std::size_t>(i)].q;
  };

  int p1 = -1;
  double best = kMinSpread_m * kMinSpread_m;
  for (int i = 0; i < n; ++i) {
    const double d2 = (q(i) - q(p0)).squaredNorm();
    if (d2 > best * (1.0 + kTieRel)) {
      best = d2;
      p1 = i;
    }
  }
  if (p1 < 0) return 1;
  pick[1] = p1;
  if (max_out < 3) return 2;

  // twice the signed area of (x, y, z) seen along the normal
  const auto area2 = [&](int x, int y, int z) {
    return normal.dot((q(y) - q(x)).cross(q(z) - q(x)));
  };
  const double min_area2 = std::sqrt(best) * kMinSpread_m;
  int p2 = -1;
  best = min_area2;
  for (int i = 0; i < n; ++i) {
    const double a = std::abs(area2(p0, p1, i));
    if (a > best * (1.0 + kTieRel)) {
      best = a;
      p2 = i;
    }
  }
  if (p2 < 0) return 2;
  pick[2] = p2;
  if (max_out < 4) return 3;

  const double sense = area2(p0, p1, p2) > 0.0 ? 1.0 : -1.0;  // the triangle's orientation
  int p3 = -1;
  best = min_area2;
  for (int i = 0; i < n; ++i) {
    // the area the point adds beyond the triangle's edges (outside one: a negative area)
    const double a = -std::min({sense * area2(p0, p1, i), sense * area2(p1, p2, i),
                                sense * area2(p2, p0, i)});
    if (a > best * (1.0 + kTieRel)) {
      best = a;
      p3 = i;
    }
  }
  if (p3 < 0) return 3;
  pick[3] = p3;
  return 4;
}

ManifoldClipper::ManifoldClipper(int max_points)
    : max_points_(std::clamp(max_points, 1, kMaxManifold)) {}

int ManifoldClipper::clip(const ClipBody& a, const ClipBody& b, const Eigen::Vector3d& n_ab,
                          std::array<ManifoldPoint, kMaxManifold>& out) {
  bool reference_is_lo = true;
  if (!choose_reference(a, b, n_ab, reference_, reference_is_lo)) return 0;
  const ClipBody& body = reference_is_lo ? b : a;
  const Eigen::Isometry3d& X = body.X_GB;
  const Eigen::Vector3d n_RI = reference_is_lo ? n_ab : Eigen::Vector3d(-n_ab);
  const Eigen::Vector3d toward_reference = -n_RI;
  if (body.shape == ShapeKind::kCylinder) {
    cylinder_incident(body, X, toward_reference, incident_);
  } else if (body.shape == ShapeKind::kCapsule) {
    capsule_incident(body, X, toward_reference, incident_);
  } else {
    return 0;  // a box's edge or corner on a cap: the narrowphase's point
  }
  const int n = clip_to_reference(reference_, incident_, n_RI, clip_scratch_, candidates_);
  const int kept = reduce_manifold(candidates_, n, n_RI, max_points_, picked_);
  for (int i = 0; i < kept; ++i) {
    const int index = picked_[static_cast<std::size_t>(i)];
    const Candidate& c = candidates_[static_cast<std::size_t>(index)];
    out[static_cast<std::size_t>(i)] = {c.q + (0.5 * c.depth_m) * n_RI, c.depth_m};
  }
  return kept;
}

}  // namespace vcockpit::physics

namespace vcockpit::physics {

int ManifoldClipper::clip_on_face(const FlatFace& face, const ClipBody& round, double max_depth_m,
                                  std::array<ManifoldPoint, kMaxManifold>& out) {
  const Eigen::Vector3d& n = face.n_G;
  if (round.shape == ShapeKind::kCylinder) {
    cylinder_incident(round, round.X_GB, -n, incident_);
  } else if (round.shape == ShapeKind::kCapsule) {
    capsule_incident(round, round.X_GB, -n, incident_);
  } else {
    return 0;
  }
  // the face's sides: each edge's outward normal in its plane (corners counter-clockwise about n)
  reference_.sides = 0;
  reference_.disk = false;
  reference_.top_m = n.dot(face.corners_G[0]);
  for (int k = 0; k < face.corner_count; ++k) {
    const Eigen::Vector3d& c0 = face.corners_G[static_cast<std::size_t>(k)];
    const Eigen::Vector3d& c1 = face.corners_G[static_cast<std::size_t>((k + 1) % face.corner_count)];
    const Eigen::Vector3d m = (c1 - c0).cross(n);
    const double length = m.norm();
    if (!(length > 1e-12)) return 0;  // a degenerate face
    reference_.side_n[static_cast<std::size_t>(reference_.sides)] = m / length;
    reference_.side_d[static_cast<std::size_t>(reference_.sides++)] = (m / length).dot(c0);
  }
  int count = clip_to_reference(reference_, incident_, n, clip_scratch_, candidates_);
  int kept_deep = 0;  // those no deeper than max_depth_m, in order
  for (int i = 0; i < count; ++i)
    if (candidates_[static_cast<std::size_t>(i)].depth_m <= max_depth_m)
      candidates_[static_cast<std::size_t>(kept_deep++)] = candidates_[static_cast<std::size_t>(i)];
  count = kept_deep;
  const int kept = reduce_manifold(candidates_, count, n, max_points_, picked_);
  for (int i = 0; i < kept; ++i) {
    const Candidate& c = candidates_[static_cast<std::size_t>(picked_[static_cast<std::size_t>(i)])];
    out[static_cast<std::size_t>(i)] = {c.q + (0.5 * c.depth_m) * n, c.depth_m};
  }
  return kept;
}

}  // namespace vcockpit::physics
