#include "model/convex_hull.hpp"

extern "C" {
#include <libqhull_r/qhull_ra.h>
}

#include <cstdio>
#include <memory>
#include <unordered_map>
#include <vector>

namespace vcockpit::model {
namespace {

// qhull writes its diagnostics to a FILE; they go nowhere (the exit code says what failed)
struct NullFile {
  std::FILE* f = std::fopen("/dev/null", "w");
  ~NullFile() {
    if (f != nullptr) std::fclose(f);
  }
};

}  // namespace

TriangleMesh convex_hull(const TriangleMesh& mesh) {
  TriangleMesh hull;
  hull.source = mesh.source + " (hull)";
  if (mesh.vertices_m.size() < 4) throw MeshError(hull.source + ": fewer than 4 vertices");
  std::vector<coordT> points;
  points.reserve(3 * mesh.vertices_m.size());
  for (const Eigen::Vector3d& v : mesh.vertices_m)
    points.insert(points.end(), {v.x(), v.y(), v.z()});
  NullFile null;
  qhT qh_storage;
  qhT* qh = &qh_storage;
  std::FILE* errors = null.f != nullptr ? null.f : stderr;
  qh_zero(qh, errors);
  char options[] = "qhull Qt";  // triangulated facets
  const int exit_code = qh_new_qhull(qh, 3, static_cast<int>(mesh.vertices_m.size()), points.data(),
                                     False, options, nullptr, errors);
  if (exit_code == 0) {
    std::unordered_map<int, uint32_t> index;  // qhull point id -> hull vertex
    const auto vertex_of = [&](vertexT* v) {
      const int id = qh_pointid(qh, v->point);
      auto [it, added] = index.emplace(id, static_cast<uint32_t>(hull.vertices_m.size()));
      if (added) hull.vertices_m.push_back(mesh.vertices_m[static_cast<std::size_t>(id)]);
      return it->second;
    };
    facetT* facet;
    FORALLfacets {
      if (facet->upperdelaunay) continue;
      std::array<uint32_t, 3> tri{};
      int n = 0;
      vertexT* vertex;
      vertexT** vertexp;
      FOREACHvertex_(facet->vertices) {
        if (n < 3) tri[static_cast<std::size_t>(n)] = vertex_of(vertex);
        ++n;
      }
      if (n != 3) continue;
      const Eigen::Vector3d normal(facet->normal[0], facet->normal[1], facet->normal[2]);
      const Eigen::Vector3d& a = hull.vertices_m[tri[0]];
      if ((hull.vertices_m[tri[1]] - a).cross(hull.vertices_m[tri[2]] - a).dot(normal) < 0.0)
        std::swap(tri[1], tri[2]);
      hull.triangles.push_back(tri);
    }
  }
  qh_freeqhull(qh, !qh_ALL);
  int curlong = 0, totlong = 0;
  qh_memfreeshort(qh, &curlong, &totlong);
  if (exit_code != 0 || hull.triangles.size() < 4)
    throw MeshError(hull.source + ": the vertices span no volume (qhull exit " +
                    std::to_string(exit_code) + "); a flat part needs a thickness in the model");
  return hull;
}

}  // namespace vcockpit::model
