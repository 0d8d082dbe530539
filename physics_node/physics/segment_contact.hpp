#pragma once
// The exact contact of a capsule (a segment swept by a radius) with a round convex body (a
// cylinder or another capsule), from closest points instead of libccd's MPR.
//
// MPR's normal is that of the Minkowski-difference face crossed by the ray between the two
// centres. For a fingertip on the side of a 16 cm flashlight the ray runs far from the contact,
// and the normal it gives swings between the true one and one along the barrel's axis or up
// through it from one step to the next (measured: a thumb's normal flipped from (0, 0.87, -0.49)
// to (0, 0.02, 1.00) at 0.6 mm depth), which throws grips. Here the segment's point nearest the
// body is found (the body's signed distance is convex, and so is its restriction to a segment:
// a golden-section search finds its least value), and while the segment itself stays outside
// the body that gives the penetration exactly: depth = radius - distance, along the distance's
// gradient. A segment that reaches inside the body (an overlap deeper than the capsule's radius)
// is left to MPR.

#include <Eigen/Geometry>

namespace vcockpit::physics {

// A round convex body in its pose: a cylinder (axis z of X_GB, radius, half length) or a
// capsule (a segment on z of X_GB of half length, swept by radius).
struct RoundBody {
  enum class Kind { kCylinder, kCapsule } kind = Kind::kCylinder;
  Eigen::Isometry3d X_GB = Eigen::Isometry3d::Identity();
  double radius_m = 0.0;
  double half_length_m = 0.0;
};

// Signed distance of p_G from the body's surface (negative inside), and its gradient (unit,
// pointing out of the body).
double signed_distance(const RoundBody& body, const Eigen::Vector3d& p_G, Eigen::Vector3d& grad_G);

struct SegmentContact {
  bool resolved = false;  // false: the segment reaches into the body (left to MPR)
  double depth_m = 0.0;   // > 0: overlapping
  Eigen::Vector3d n_G = Eigen::Vector3d::UnitZ();  // out of the body, toward the capsule
  Eigen::Vector3d p_G = Eigen::Vector3d::Zero();   // midway between the two surfaces
};

// The capsule from a_G to b_G of radius_m against `body`.
SegmentContact segment_contact(const Eigen::Vector3d& a_G, const Eigen::Vector3d& b_G,
                               double radius_m, const RoundBody& body);

}  // namespace vcockpit::physics
