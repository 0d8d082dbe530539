#pragma once
// Contacts of a polyhedral body's vertices against a flat face (a mesh's triangle, a box's face):
// the manifold FCL does not give for a mesh pair (one point per triangle, so a box lying on a
// mesh would rest on one point and rock). Each vertex of the incident body that is under the
// face's plane and over the face itself is a contact, at the vertex backed off half its depth
// along the face's normal (midway between the surfaces, as FCL's closed-form pairs place it).

#include <Eigen/Geometry>
#include <array>
#include <vector>

namespace vcockpit::physics {

struct FlatFace {
  Eigen::Vector3d n_G = Eigen::Vector3d::UnitZ();  // out of the face's body, unit
  std::array<Eigen::Vector3d, 4> corners_G{};      // a convex polygon in the face's plane, in
  int corner_count = 3;                            // counter-clockwise order about n_G
};

struct FaceContact {
  Eigen::Vector3d p_G = Eigen::Vector3d::Zero();
  Eigen::Vector3d n_G = Eigen::Vector3d::UnitZ();  // out of the face's body
  double depth_m = 0.0;
};

// Appends a contact for each of `vertices_G` whose depth under the face's plane is in
// (0, max_depth_m] and whose projection lies on the face (within slack_m of its edges).
void face_vertex_contacts(const FlatFace& face, const std::vector<Eigen::Vector3d>& vertices_G,
                          double max_depth_m, double slack_m, std::vector<FaceContact>& out);

// Keeps at most `keep` of `contacts`: the deepest, then each time the one farthest from those
// kept (the support polygon's corners before its inner points). Merges first any two closer
// than merge_m with normals within a degree (the same point found through two triangles of one
// plane), keeping the deeper.
void reduce_face_contacts(std::vector<FaceContact>& contacts, int keep, double merge_m);

}  // namespace vcockpit::physics
