#include "physics_node/physics/segment_contact.hpp"

#include <algorithm>
#include <cmath>

#include "physics_node/physics/golden_section.hpp"

namespace vcockpit::physics {
namespace {

// Golden-section search stops when the bracket is this short (m along the segment): far below
// any contact depth that matters, and the distance is flat to second order at its least value.
constexpr double kBracket_m = 1e-9;
constexpr int kMaxIterations = 80;

// The signed distance of p_B (body frame) and, if asked, its gradient in the body frame.
double local_distance(const RoundBody& body, const Eigen::Vector3d& p, Eigen::Vector3d* grad) {
  if (body.kind == RoundBody::Kind::kCapsule) {
    const double z = std::clamp(p.z(), -body.half_length_m, body.half_length_m);
    const Eigen::Vector3d d = p - Eigen::Vector3d(0.0, 0.0, z);
    const double norm = d.norm();
    if (grad) *grad = norm > 0.0 ? Eigen::Vector3d(d / norm) : Eigen::Vector3d::UnitX();
    return norm - body.radius_m;
  }
  const double rho = std::sqrt(p.x() * p.x() + p.y() * p.y());
  const double dr = rho - body.radius_m;
  const double dh = std::abs(p.z()) - body.half_length_m;
  if (grad) {
    const Eigen::Vector3d radial =
        rho > 0.0 ? Eigen::Vector3d(p.x() / rho, p.y() / rho, 0.0) : Eigen::Vector3d::UnitX();
    const Eigen::Vector3d axial(0.0, 0.0, p.z() >= 0.0 ? 1.0 : -1.0);
    if (dr > 0.0 && dh > 0.0) {
      const double d = std::sqrt(dr * dr + dh * dh);
      *grad = (dr / d) * radial + (dh / d) * axial;
    } else {
      *grad = dr >= dh ? radial : axial;
    }
  }
  if (dr > 0.0 && dh > 0.0) return std::sqrt(dr * dr + dh * dh);  // nearest the rim
  // beside the side, above a cap, or inside (the nearer face): the larger of the two
  return std::max(dr, dh);
}

}  // namespace

double signed_distance(const RoundBody& body, const Eigen::Vector3d& p_G, Eigen::Vector3d& grad_G) {
  Eigen::Vector3d grad_B;
  const double d = local_distance(body, body.X_GB.inverse() * p_G, &grad_B);
  grad_G = body.X_GB.linear() * grad_B;
  return d;
}

SegmentContact segment_contact(const Eigen::Vector3d& a_G, const Eigen::Vector3d& b_G,
                               double radius_m, const RoundBody& body) {
  SegmentContact out;
  // in the body's frame: one transform, not one per evaluation
  const Eigen::Isometry3d X_BG = body.X_GB.inverse();
  const Eigen::Vector3d a_B = X_BG * a_G;
  const Eigen::Vector3d ab_B = X_BG.linear() * (b_G - a_G);
  const double length_m = ab_B.norm();
  const auto distance_at = [&](double t) { return local_distance(body, a_B + t * ab_B, nullptr); };
  // The least signed distance over t in [0, 1]: a convex function, so least at an end when its
  // slope there points inward (the gradient is a subgradient where the distance has a kink, and
  // its slope bounds the one-sided one), which is three calls in four on the bundled grasp log;
  // otherwise searched for inside.
  Eigen::Vector3d grad0_B, grad1_B;
  const double f0 = local_distance(body, a_B, &grad0_B);
  const double f1 = local_distance(body, a_B + ab_B, &grad1_B);
  double best_t = 0.0;
  double best = f0;
  if (grad0_B.dot(ab_B) >= 0.0) {
    // rising from the start
  } else if (grad1_B.dot(ab_B) <= 0.0) {
    best_t = 1.0;  // falling to the end
    best = f1;
  } else {
    const GoldenBracket g = golden_section(distance_at, length_m, kBracket_m, kMaxIterations);
    best_t = 0.5 * (g.lo + g.hi);
    best = distance_at(best_t);
    // the ends too (a flat least value reaching an end)
    if (f0 < best) {
      best = f0;
      best_t = 0.0;
    }
    if (f1 < best) {
      best = f1;
      best_t = 1.0;
    }
  }
  if (best <= 0.0) return out;  // the segment reaches into the body
  const Eigen::Vector3d p_G = a_G + best_t * (b_G - a_G);
  Eigen::Vector3d grad;
  signed_distance(body, p_G, grad);
  out.resolved = true;
  out.depth_m = radius_m - best;
  out.n_G = grad;
  // the capsule's deepest point is p - r n, the body's surface p - best n: midway between them
  out.p_G = p_G - (0.5 * (radius_m + best)) * grad;
  return out;
}

}  // namespace vcockpit::physics
