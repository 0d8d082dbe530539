#pragma once
// Signed distances between the hand's collision shapes and an object (metres; negative when they
// overlap), for placing an object in a recorded grip (grip_fit.hpp). Object shapes as in the
// scene (physics::Shape): box full extents, sphere, and cylinder and capsule along the object's z.
//
// sd(link, object) is the distance between the two when apart and minus the depth of the overlap
// when they overlap:
// - A capsule link (a segment swept by a radius): the least signed distance of the object over
//   the link's segment, minus the radius. The object's signed distance is convex, and so is its
//   restriction to a segment: closed forms for a sphere (point-segment) and a capsule
//   (segment-segment), a golden-section search for a box or a cylinder (as the simulator's
//   segment_contact does). Exact while the segment stays outside the object, i.e. for every
//   overlap shallower than the link's radius (6-10 mm): all a placement accepts.
// - The palm box: exact for a sphere (its centre against the box) and a capsule (its segment
//   against the box); against a box or a cylinder FCL's, the simulator's own narrowphase: the GJK
//   distance when apart, libccd MPR's depth when overlapping (exact for a face on a face or on a
//   cylinder's side, an over-estimate if anything for deep overlaps).

#include <Eigen/Geometry>

#include "physics_node/physics/scene.hpp"

namespace vcockpit::fit {

// Signed distance of a point (object frame O) from the shape's surface; negative inside.
double point_signed_distance(const physics::Shape& shape, const Eigen::Vector3d& p_O);

// The capsule link from a_G to b_G (its segment) with radius_m against the shape at X_GO.
struct LinkContact {
  double distance_m = 0.0;                        // signed, as above
  Eigen::Vector3d p_G = Eigen::Vector3d::Zero();  // the segment's point nearest the object
  // the object's outward normal there (its signed distance's gradient, by central differences
  // of 1 um): the direction the object's surface faces the link. Zero where it is undefined (the
  // point on the object's centre or axis).
  Eigen::Vector3d n_G = Eigen::Vector3d::Zero();
};
LinkContact capsule_contact(const physics::Shape& shape, const Eigen::Isometry3d& X_GO,
                            const Eigen::Vector3d& a_G, const Eigen::Vector3d& b_G,
                            double radius_m);
double capsule_signed_distance(const physics::Shape& shape, const Eigen::Isometry3d& X_GO,
                               const Eigen::Vector3d& a_G, const Eigen::Vector3d& b_G,
                               double radius_m);

// A box of full extents size_m at X_GB (the palm) against the shape at X_GO.
double box_signed_distance(const physics::Shape& shape, const Eigen::Isometry3d& X_GO,
                           const Eigen::Vector3d& size_m, const Eigen::Isometry3d& X_GB);

// Distance between two segments (closest points, Ericson's "Real-Time Collision Detection" 5.1.9).
double segment_segment_distance(const Eigen::Vector3d& p1, const Eigen::Vector3d& q1,
                                const Eigen::Vector3d& p2, const Eigen::Vector3d& q2);

// A cheap bound for signed distances (the placement search and the hand's approach leave out
// links and hands that cannot be the nearest): the shape lies within radius_m of the segment
// a_G..b_G (a point for a ball or a box: its centre; a capsule's or a cylinder's axis).
struct ShapeCore {
  Eigen::Vector3d a_G = Eigen::Vector3d::Zero();
  Eigen::Vector3d b_G = Eigen::Vector3d::Zero();
  double radius_m = 0.0;
};
ShapeCore shape_core(const physics::Shape& shape, const Eigen::Isometry3d& X_GO);
// At most capsule_signed_distance of the capsule link a_G..b_G (radius_m) from the shape.
double capsule_distance_lower_bound(const ShapeCore& core, const Eigen::Vector3d& a_G,
                                    const Eigen::Vector3d& b_G, double radius_m);

// How far the shape reaches from its centroid along the unit direction u_O (its support
// function; every scene shape is symmetric about its centroid, so also along -u_O).
double support_half_extent(const physics::Shape& shape, const Eigen::Vector3d& u_O);

}  // namespace vcockpit::fit
