#pragma once
// The convex hull of a mesh's vertices (Debian's qhull, libqhull_r): what a moving part or a
// loose object made from a model collides with (FCL's Convex), and whose solid gives its mass.

#include "model/triangle_mesh.hpp"

namespace vcockpit::model {

// The hull as a closed mesh of outward, counter-clockwise triangles over the hull's vertices
// only; source names it "(hull)". Throws MeshError for fewer than 4 points or points that span
// no volume (a flat panel: give it a thickness in the model).
TriangleMesh convex_hull(const TriangleMesh& mesh);

}  // namespace vcockpit::model
