#include "physics_node/physics/face_vertex_contacts.hpp"

#include <algorithm>
#include <limits>

namespace vcockpit::physics {
namespace {

constexpr double kSameNormal = 0.99985;  // cos(1 deg)

}  // namespace

void face_vertex_contacts(const FlatFace& face, const std::vector<Eigen::Vector3d>& vertices_G,
                          double max_depth_m, double slack_m, std::vector<FaceContact>& out) {
  const Eigen::Vector3d& n = face.n_G;
  const Eigen::Vector3d& origin = face.corners_G[0];
  for (const Eigen::Vector3d& v : vertices_G) {
    const double depth_m = (origin - v).dot(n);
    if (depth_m <= 0.0 || depth_m > max_depth_m) continue;
    const Eigen::Vector3d on_plane = v + depth_m * n;
    bool over = true;
    for (int i = 0; i < face.corner_count && over; ++i) {
      const Eigen::Vector3d& a = face.corners_G[static_cast<std::size_t>(i)];
      const Eigen::Vector3d& b =
          face.corners_G[static_cast<std::size_t>((i + 1) % face.corner_count)];
      // inward normal of edge ab within the plane (counter-clockwise about n)
      const Eigen::Vector3d inward = n.cross(b - a);
      const double length_m = inward.norm();
      if (length_m <= 0.0) continue;
      over = (on_plane - a).dot(inward) / length_m >= -slack_m;
    }
    if (over) out.push_back({v + (0.5 * depth_m) * n, n, depth_m});
  }
}

void reduce_face_contacts(std::vector<FaceContact>& contacts, int keep, double merge_m) {
  // merge near-duplicates (the deeper stays)
  std::vector<FaceContact> merged;
  merged.reserve(contacts.size());
  for (const FaceContact& c : contacts) {
    bool absorbed = false;
    for (FaceContact& m : merged) {
      if ((m.p_G - c.p_G).norm() > merge_m || m.n_G.dot(c.n_G) < kSameNormal) continue;
      if (c.depth_m > m.depth_m) m = c;
      absorbed = true;
      break;
    }
    if (!absorbed) merged.push_back(c);
  }
  if (static_cast<int>(merged.size()) <= keep) {
    contacts = std::move(merged);
    return;
  }
  std::vector<FaceContact> kept;
  kept.reserve(static_cast<std::size_t>(keep));
  auto deepest = std::max_element(
      merged.begin(), merged.end(),
      [](const FaceContact& a, const FaceContact& b) { return a.depth_m < b.depth_m; });
  kept.push_back(*deepest);
  merged.erase(deepest);
  while (static_cast<int>(kept.size()) < keep && !merged.empty()) {
    auto farthest = merged.begin();
    double best_m2 = -1.0;
    for (auto it = merged.begin(); it != merged.end(); ++it) {
      double nearest_m2 = std::numeric_limits<double>::infinity();
      for (const FaceContact& k : kept)
        nearest_m2 = std::min(nearest_m2, (k.p_G - it->p_G).squaredNorm());
      if (nearest_m2 > best_m2) {
        best_m2 = nearest_m2;
        farthest = it;
      }
    }
    kept.push_back(*farthest);
    merged.erase(farthest);
  }
  contacts = std::move(kept);
}

}  // namespace vcockpit::physics
