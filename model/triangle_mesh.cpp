#include "model/triangle_mesh.hpp"

#include <cmath>
#include <string>

namespace vcockpit::model {

namespace {

void check_textures(const TriangleMesh& mesh) {
  if (mesh.triangle_texture.empty() && mesh.uv.empty()) return;
  if (mesh.uv.size() != mesh.vertices_m.size())
    throw MeshError(mesh.source + ": " + std::to_string(mesh.uv.size()) +
                    " texture coordinates for " + std::to_string(mesh.vertices_m.size()) + " vertices");
  if (mesh.triangle_texture.size() != mesh.triangles.size())
    throw MeshError(mesh.source + ": a texture for " + std::to_string(mesh.triangle_texture.size()) +
                    " of its " + std::to_string(mesh.triangles.size()) + " triangles");
  for (std::size_t v = 0; v < mesh.uv.size(); ++v)
    if (!mesh.uv[v].allFinite())
      throw MeshError(mesh.source + ": vertex " + std::to_string(v) +
                      "'s texture coordinate is not a finite number");
  for (std::size_t t = 0; t < mesh.triangle_texture.size(); ++t) {
    const int32_t k = mesh.triangle_texture[t];
    if (k < -1 || k >= static_cast<int64_t>(mesh.textures.size()))
      throw MeshError(mesh.source + ": triangle " + std::to_string(t) + " samples texture " +
                      std::to_string(k) + " of " + std::to_string(mesh.textures.size()));
  }
  for (const TextureImage& image : mesh.textures)
    if (image.width == 0 || image.height == 0 ||
        image.rgba.size() != uint64_t{image.width} * image.height * 4)
      throw MeshError(mesh.source + ": texture '" + image.name + "' has " +
                      std::to_string(image.rgba.size()) + " bytes for " +
                      std::to_string(image.width) + " x " + std::to_string(image.height) + " pixels");
}

}  // namespace

void check_mesh(const TriangleMesh& mesh, double min_area_m2) {
  if (mesh.triangles.empty() || mesh.vertices_m.empty())
    throw MeshError(mesh.source + ": no triangles");
  for (std::size_t v = 0; v < mesh.vertices_m.size(); ++v)
    if (!mesh.vertices_m[v].allFinite())
      throw MeshError(mesh.source + ": vertex " + std::to_string(v) + " is not a finite number");
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tri = mesh.triangles[t];
    for (uint32_t i : tri)
      if (i >= mesh.vertices_m.size())
        throw MeshError(mesh.source + ": triangle " + std::to_string(t) + " refers to vertex " +
                        std::to_string(i) + " of " + std::to_string(mesh.vertices_m.size()));
    const Eigen::Vector3d& a = mesh.vertices_m[tri[0]];
    const double area_m2 =
        0.5 * (mesh.vertices_m[tri[1]] - a).cross(mesh.vertices_m[tri[2]] - a).norm();
    if (!(area_m2 >= min_area_m2))
      throw MeshError(mesh.source + ": triangle " + std::to_string(t) + " is degenerate (area " +
                      std::to_string(area_m2) + " m^2)");
  }
  check_textures(mesh);
}

void drop_degenerate_triangles(TriangleMesh& mesh, double min_area_m2) {
  // (a texture list that does not match the triangles is left as it is, for check_mesh to name)
  const bool textured = mesh.triangle_texture.size() == mesh.triangles.size();
  std::size_t kept = 0;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tri = mesh.triangles[t];
    const bool indices_ok = tri[0] < mesh.vertices_m.size() && tri[1] < mesh.vertices_m.size() &&
                            tri[2] < mesh.vertices_m.size();
    double area_m2 = 0.0;
    if (indices_ok) {
      const Eigen::Vector3d& a = mesh.vertices_m[tri[0]];
      area_m2 = 0.5 * (mesh.vertices_m[tri[1]] - a).cross(mesh.vertices_m[tri[2]] - a).norm();
    }
    // (a bad index or a non-finite vertex stays, for check_mesh to name)
    if (indices_ok && std::isfinite(area_m2) && area_m2 < min_area_m2) {
      if (mesh.degenerate_dropped++ == 0) mesh.first_degenerate = t;
      continue;
    }
    if (textured) mesh.triangle_texture[kept] = mesh.triangle_texture[t];
    mesh.triangles[kept++] = tri;
  }
  mesh.triangles.resize(kept);
  if (textured) mesh.triangle_texture.resize(kept);
  if (kept == 0 && mesh.degenerate_dropped > 0)
    throw MeshError(mesh.source + ": every one of its " + std::to_string(mesh.degenerate_dropped) +
                    " triangles is degenerate (no area)");
}

MassProperties mass_properties(const TriangleMesh& mesh) {
  // Integrals of 1, x, y, z, x^2, y^2, z^2, xy, yz, zx over the solid, summed over the signed
  // tetrahedra (origin, a, b, c). For a tetrahedron with vertices 0, a, b, c and volume V:
  // int x = V (a+b+c)_x / 4, int x_i x_j = V/20 (sum_k a_i a_j ... + (sum a)_i (sum a)_j).
  double V = 0.0;
  Eigen::Vector3d first = Eigen::Vector3d::Zero();
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();  // int x x^T
  for (const auto& tri : mesh.triangles) {
    const Eigen::Vector3d& a = mesh.vertices_m[tri[0]];
    const Eigen::Vector3d& b = mesh.vertices_m[tri[1]];
    const Eigen::Vector3d& c = mesh.vertices_m[tri[2]];
    const double v = a.dot(b.cross(c)) / 6.0;
    const Eigen::Vector3d s = a + b + c;
    V += v;
    first += v * s / 4.0;
    second +=
        v / 20.0 * (a * a.transpose() + b * b.transpose() + c * c.transpose() + s * s.transpose());
  }
  MassProperties m;
  m.volume_m3 = V;
  if (!(std::abs(V) > 0.0)) return m;
  m.centroid_m = first / V;
  // about the centroid: int (x-c)(x-c)^T = second - V c c^T; inertia = tr(S) I - S
  const Eigen::Matrix3d S = second - V * m.centroid_m * m.centroid_m.transpose();
  m.unit_density_inertia = S.trace() * Eigen::Matrix3d::Identity() - S;
  return m;
}

Bounds bounds(const TriangleMesh& mesh) {
  Bounds b;
  if (mesh.vertices_m.empty()) return b;
  b.min_m = b.max_m = mesh.vertices_m.front();
  for (const Eigen::Vector3d& v : mesh.vertices_m) {
    b.min_m = b.min_m.cwiseMin(v);
    b.max_m = b.max_m.cwiseMax(v);
  }
  return b;
}

void translate(TriangleMesh& mesh, const Eigen::Vector3d& shift_m) {
  for (Eigen::Vector3d& v : mesh.vertices_m)
    v += shift_m;
}

}  // namespace vcockpit::model
