#include "physics_node/physics/segment_contact.hpp"

#include <algorithm>
#include <cmath>

namespace vcockpit::physics {
namespace {

// Golden-section search stops when the bracket is this short (m along the segment): far below
// any contact depth that matters, and the distance is flat to second order at its least value.
constexpr double kBracket_m = 1e-9;
constexpr int kMaxIterations = 80;

}  // namespace

double signed_distance(const RoundBody& body, const Eigen::Vector3d& p_G, Eigen::Vector3d& grad_G) {
  const Eigen::Vector3d p = body.X_GB.inverse() * p_G;
  const Eigen::Matrix3d& R = body.X_GB.linear();
  if (body.kind == RoundBody::Kind::kCapsule) {
    const double z = std::clamp(p.z(), -body.half_length_m, body.half_length_m);
    const Eigen::Vector3d d = p - Eigen::Vector3d(0.0, 0.0, z);
    const double norm = d.norm();
    grad_G = norm > 0.0 ? Eigen::Vector3d(R * (d / norm)) : Eigen::Vector3d(R.col(0));
    return norm - body.radius_m;
  }
  const double rho = std::hypot(p.x(), p.y());
  const Eigen::Vector3d radial =
      rho > 0.0 ? Eigen::Vector3d(p.x() / rho, p.y() / rho, 0.0) : Eigen::Vector3d::UnitX();
  const Eigen::Vector3d axial(0.0, 0.0, p.z() >= 0.0 ? 1.0 : -1.0);
  const double dr = rho - body.radius_m;
  const double dh = std::abs(p.z()) - body.half_length_m;
  if (dr > 0.0 && dh > 0.0) {  // nearest the rim
    const double d = std::hypot(dr, dh);
    grad_G = R * ((dr / d) * radial + (dh / d) * axial);
    return d;
  }
  // beside the side, above a cap, or inside (the nearer face): the larger of the two
  grad_G = R * (dr >= dh ? radial : axial);
  return std::max(dr, dh);
}

SegmentContact segment_contact(const Eigen::Vector3d& a_G, const Eigen::Vector3d& b_G,
                               double radius_m, const RoundBody& body) {
  SegmentContact out;
  const Eigen::Vector3d ab = b_G - a_G;
  const double length_m = ab.norm();
  Eigen::Vector3d grad;
  const auto distance_at = [&](double t) { return signed_distance(body, a_G + t * ab, grad); };
  // golden-section search for the least signed distance over t in [0, 1] (a convex function)
  constexpr double kInvPhi = 0.6180339887498949;
  double lo = 0.0;
  double hi = 1.0;
  double t1 = hi - kInvPhi * (hi - lo);
  double t2 = lo + kInvPhi * (hi - lo);
  double d1 = distance_at(t1);
  double d2 = distance_at(t2);
  for (int i = 0; i < kMaxIterations && (hi - lo) * length_m > kBracket_m; ++i) {
    if (d1 <= d2) {
      hi = t2;
      t2 = t1;
      d2 = d1;
      t1 = hi - kInvPhi * (hi - lo);
      d1 = distance_at(t1);
    } else {
      lo = t1;
      t1 = t2;
      d1 = d2;
      t2 = lo + kInvPhi * (hi - lo);
      d2 = distance_at(t2);
    }
  }
  // the ends too: a flat minimum at an end is found by the search only to within the bracket
  double best_t = 0.5 * (lo + hi);
  double best = distance_at(best_t);
  for (double t : {0.0, 1.0}) {
    const double d = distance_at(t);
    if (d < best) {
      best = d;
      best_t = t;
    }
  }
  if (best <= 0.0) return out;  // the segment reaches into the body
  const Eigen::Vector3d p_G = a_G + best_t * ab;
  signed_distance(body, p_G, grad);
  out.resolved = true;
  out.depth_m = radius_m - best;
  out.n_G = grad;
  // the capsule's deepest point is p - r n, the body's surface p - best n: midway between them
  out.p_G = p_G - (0.5 * (radius_m + best)) * grad;
  return out;
}

}  // namespace vcockpit::physics
