#include "physics_node/fit/shape_distance.hpp"

#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "physics_node/physics/fcl_geometry.hpp"
#include "physics_node/physics/golden_section.hpp"

namespace vcockpit::fit {
namespace {

using physics::Shape;
using physics::ShapeKind;

// The golden-section search stops when its bracket is this short along the segment (m): far
// below a millimetre, and the distance is flat to second order at its least value.
constexpr double kBracket_m = 1e-10;
constexpr int kMaxIterations = 90;
// FCL's GJK and MPR tolerance: the simulator's (collision.cpp measures why 1e-9)
constexpr double kFclTolerance_m = 1e-9;

double box_point_signed_distance(const Eigen::Vector3d& half_m, const Eigen::Vector3d& p) {
  const Eigen::Vector3d q = p.cwiseAbs() - half_m;
  const double outside = q.cwiseMax(0.0).norm();
  const double inside = std::min(q.maxCoeff(), 0.0);
  return outside + inside;
}

double cylinder_point_signed_distance(double radius_m, double half_length_m,
                                      const Eigen::Vector3d& p) {
  // (sqrt, not hypot: these are lengths of a few cm, and hypot's care for overflow costs a third
  // of a placement search)
  const double dr = std::sqrt(p.x() * p.x() + p.y() * p.y()) - radius_m;
  const double dh = std::abs(p.z()) - half_length_m;
  if (dr > 0.0 && dh > 0.0) return std::sqrt(dr * dr + dh * dh);  // nearest the rim
  return std::max(dr, dh);  // beside the side, beyond a cap, or inside (the nearer face)
}

struct Minimum {
  double value;
  double t;
};

// The least value of a convex f over t in [0, 1] and where (segment length `length_m` sets the
// stop).
template <typename F>
Minimum convex_minimum(const F& f, double length_m) {
  const physics::GoldenBracket g = physics::golden_section(f, length_m, kBracket_m, kMaxIterations);
  // the search never evaluates the ends themselves, where a monotone f has its least value
  Minimum best = g.f1 <= g.f2 ? Minimum{g.f1, g.t1} : Minimum{g.f2, g.t2};
  for (double t : {0.0, 1.0}) {
    const double v = f(t);
    if (v < best.value) best = {v, t};
  }
  return best;
}

// Where on the segment a..b the point nearest p lies (0..1).
double nearest_on_segment(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                          const Eigen::Vector3d& b) {
  const Eigen::Vector3d ab = b - a;
  const double len2 = ab.squaredNorm();
  return len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
}

// The outward normal of the shape at p_O (its signed distance's gradient by central
// differences), unit, or zero where the gradient vanishes.
Eigen::Vector3d outward_normal(const Shape& shape, const Eigen::Vector3d& p_O) {
  constexpr double h = 1e-6;
  Eigen::Vector3d g;
  for (int i = 0; i < 3; ++i) {
    Eigen::Vector3d e = Eigen::Vector3d::Zero();
    e[i] = h;
    g[i] =
        (point_signed_distance(shape, p_O + e) - point_signed_distance(shape, p_O - e)) / (2.0 * h);
  }
  const double norm = g.norm();
  return norm > 1e-6 ? Eigen::Vector3d(g / norm) : Eigen::Vector3d::Zero();
}

// FCL's signed distance as the simulator measures it: the deepest contact when they overlap,
// the GJK distance when apart.
double fcl_signed_distance(const fcl::CollisionGeometryd& a, const Eigen::Isometry3d& X_GA,
                           const fcl::CollisionGeometryd& b, const Eigen::Isometry3d& X_GB) {
  fcl::CollisionRequestd request(4, /*enable_contact=*/true);
  request.gjk_tolerance = kFclTolerance_m;
  fcl::CollisionResultd result;
  fcl::collide(&a, X_GA, &b, X_GB, request, result);
  if (result.isCollision()) {
    double depth_m = 0.0;
    for (std::size_t i = 0; i < result.numContacts(); ++i)
      depth_m = std::max(depth_m, result.getContact(i).penetration_depth);
    return -depth_m;
  }
  fcl::DistanceRequestd distance_request;
  distance_request.distance_tolerance = kFclTolerance_m;
  fcl::DistanceResultd distance_result;
  fcl::distance(&a, X_GA, &b, X_GB, distance_request, distance_result);
  return std::max(distance_result.min_distance, 0.0);
}

}  // namespace

double point_signed_distance(const Shape& shape, const Eigen::Vector3d& p_O) {
  switch (shape.kind) {
    case ShapeKind::kBox:
      return box_point_signed_distance(0.5 * shape.box_size_m, p_O);
    case ShapeKind::kSphere:
      return p_O.norm() - shape.radius_m;
    case ShapeKind::kCapsule: {
      const double z = std::clamp(p_O.z(), -0.5 * shape.length_m, 0.5 * shape.length_m);
      return (p_O - Eigen::Vector3d(0.0, 0.0, z)).norm() - shape.radius_m;
    }
    case ShapeKind::kCylinder:
      return cylinder_point_signed_distance(shape.radius_m, 0.5 * shape.length_m, p_O);
    case ShapeKind::kMesh:  // grip_fit's objects are the primitives its command line names
      break;
  }
  return 0.0;
}

double segment_segment_distance(const Eigen::Vector3d& p1, const Eigen::Vector3d& q1,
                                const Eigen::Vector3d& p2, const Eigen::Vector3d& q2) {
  constexpr double kEps = 1e-18;  // m^2: a segment this short is a point
  const Eigen::Vector3d d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  double s = 0.0, t = 0.0;
  if (a <= kEps && e <= kEps) {
    return r.norm();
  } else if (a <= kEps) {
    t = std::clamp(f / e, 0.0, 1.0);
  } else {
    const double c = d1.dot(r);
    if (e <= kEps) {
      s = std::clamp(-c / a, 0.0, 1.0);
    } else {
      const double b = d1.dot(d2);
      const double denom = a * e - b * b;  // 0 for parallel segments: any s, take 0
      s = denom > 0.0 ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
      t = (b * s + f) / e;
      if (t < 0.0) {
        t = 0.0;
        s = std::clamp(-c / a, 0.0, 1.0);
      } else if (t > 1.0) {
        t = 1.0;
        s = std::clamp((b - c) / a, 0.0, 1.0);
      }
    }
  }
  return ((p1 + s * d1) - (p2 + t * d2)).norm();
}

LinkContact capsule_contact(const Shape& shape, const Eigen::Isometry3d& X_GO,
                            const Eigen::Vector3d& a_G, const Eigen::Vector3d& b_G,
                            double radius_m) {
  const Eigen::Isometry3d X_OG = X_GO.inverse();
  const Eigen::Vector3d a_O = X_OG * a_G, b_O = X_OG * b_G, ab_O = b_O - a_O;
  // where on the link's segment the object is nearest: a closed form for a sphere; else the least
  // of the object's point signed distance along the segment (exact for every shape, capsule too)
  double t = 0.0;
  if (shape.kind == ShapeKind::kSphere) {
    t = nearest_on_segment(Eigen::Vector3d::Zero(), a_O, b_O);
  } else {
    const auto at = [&](double u) { return point_signed_distance(shape, a_O + u * ab_O); };
    t = convex_minimum(at, ab_O.norm()).t;
  }
  const Eigen::Vector3d p_O = a_O + t * ab_O;
  LinkContact out;
  if (shape.kind == ShapeKind::kCapsule) {
    // the closed form for the distance itself (the search places the point)
    const Eigen::Vector3d half(0.0, 0.0, 0.5 * shape.length_m);
    out.distance_m = segment_segment_distance(a_O, b_O, -half, half) - shape.radius_m - radius_m;
  } else {
    out.distance_m = point_signed_distance(shape, p_O) - radius_m;
  }
  out.p_G = X_GO * p_O;
  out.n_G = X_GO.linear() * outward_normal(shape, p_O);
  return out;
}

double capsule_signed_distance(const Shape& shape, const Eigen::Isometry3d& X_GO,
                               const Eigen::Vector3d& a_G, const Eigen::Vector3d& b_G,
                               double radius_m) {
  return capsule_contact(shape, X_GO, a_G, b_G, radius_m).distance_m;
}

double box_signed_distance(const Shape& shape, const Eigen::Isometry3d& X_GO,
                           const Eigen::Vector3d& size_m, const Eigen::Isometry3d& X_GB) {
  const Eigen::Isometry3d X_BO = X_GB.inverse() * X_GO;
  const Eigen::Vector3d half_m = 0.5 * size_m;
  switch (shape.kind) {
    case ShapeKind::kSphere:
      return box_point_signed_distance(half_m, X_BO.translation()) - shape.radius_m;
    case ShapeKind::kCapsule: {
      const Eigen::Vector3d a_B = X_BO * Eigen::Vector3d(0.0, 0.0, -0.5 * shape.length_m);
      const Eigen::Vector3d ab_B = X_BO.linear() * Eigen::Vector3d(0.0, 0.0, shape.length_m);
      const auto at = [&](double t) { return box_point_signed_distance(half_m, a_B + t * ab_B); };
      return convex_minimum(at, shape.length_m).value - shape.radius_m;
    }
    case ShapeKind::kBox:
    case ShapeKind::kCylinder: {
      const fcl::Boxd box(size_m);
      return fcl_signed_distance(box, X_GB, *physics::fcl_geometry(shape, /*moving=*/true), X_GO);
    }
    case ShapeKind::kMesh:
      break;
  }
  return 0.0;
}

ShapeCore shape_core(const Shape& shape, const Eigen::Isometry3d& X_GO) {
  switch (shape.kind) {
    case ShapeKind::kSphere:
      return {X_GO.translation(), X_GO.translation(), shape.radius_m};
    case ShapeKind::kBox:
      return {X_GO.translation(), X_GO.translation(), 0.5 * shape.box_size_m.norm()};
    case ShapeKind::kCapsule:
    case ShapeKind::kCylinder: {
      const Eigen::Vector3d half_G = X_GO.linear().col(2) * (0.5 * shape.length_m);
      return {X_GO.translation() - half_G, X_GO.translation() + half_G, shape.radius_m};
    }
    case ShapeKind::kMesh:
      break;
  }
  return {X_GO.translation(), X_GO.translation(), INFINITY};
}

double capsule_distance_lower_bound(const ShapeCore& core, const Eigen::Vector3d& a_G,
                                    const Eigen::Vector3d& b_G, double radius_m) {
  return segment_segment_distance(a_G, b_G, core.a_G, core.b_G) - core.radius_m - radius_m;
}

double support_half_extent(const Shape& shape, const Eigen::Vector3d& u_O) {
  const double along_axis = std::abs(u_O.z());
  switch (shape.kind) {
    case ShapeKind::kBox:
      return 0.5 * shape.box_size_m.dot(u_O.cwiseAbs());
    case ShapeKind::kSphere:
      return shape.radius_m;
    case ShapeKind::kCapsule:
      return shape.radius_m + 0.5 * shape.length_m * along_axis;
    case ShapeKind::kCylinder:
      return shape.radius_m * std::sqrt(std::max(0.0, 1.0 - along_axis * along_axis)) +
             0.5 * shape.length_m * along_axis;
    case ShapeKind::kMesh:
      break;
  }
  return 0.0;
}

}  // namespace vcockpit::fit
