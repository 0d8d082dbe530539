#pragma once
// A shape as FCL's collision geometry: the one place the physics' shapes become FCL's (the
// collision world, and the tools and tests that measure against the same geometry).

#include <fcl/narrowphase/collision_object.h>

#include <memory>

#include "physics_node/physics/scene.hpp"

namespace vcockpit::physics {

// `moving`: a mesh collides as its convex hull (a static one as its triangles, in a BVH).
// Throws std::invalid_argument for a shape with a non-positive size, or a mesh without its
// triangles (or, moving, its hull).
std::shared_ptr<fcl::CollisionGeometryd> fcl_geometry(const Shape& shape, bool moving);

}  // namespace vcockpit::physics
