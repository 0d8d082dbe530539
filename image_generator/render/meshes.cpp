#include "image_generator/render/meshes.hpp"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <numbers>

namespace vcockpit::render {
namespace {

constexpr float kTwoPi = 2.0f * std::numbers::pi_v<float>;

uint32_t index_of(const MeshData& mesh) {
  return static_cast<uint32_t>(mesh.vertices.size());
}

void add_triangle(MeshData& mesh, uint32_t a, uint32_t b, uint32_t c) {
  mesh.indices.insert(mesh.indices.end(), {a, b, c});
}

// one face of the box: normal n, in-plane axes u, v with u x v = n
void add_box_face(MeshData& mesh, const std::array<float, 3>& n, const std::array<float, 3>& u,
                  const std::array<float, 3>& v) {
  const uint32_t first = index_of(mesh);
  constexpr float kSigns[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
  for (const auto& s : kSigns) {
    Vertex vertex{{}, n};
    for (int i = 0; i < 3; ++i)
      vertex.position[i] = 0.5f * (n[i] + s[0] * u[i] + s[1] * v[i]);
    mesh.vertices.push_back(vertex);
  }
  add_triangle(mesh, first, first + 1, first + 2);
  add_triangle(mesh, first, first + 2, first + 3);
}

// a flat disc at height z facing +z (up) or -z
void add_cap(MeshData& mesh, int slices, float z, bool up) {
  const std::array<float, 3> n{0.0f, 0.0f, up ? 1.0f : -1.0f};
  const uint32_t centre = index_of(mesh);
  mesh.vertices.push_back({{0.0f, 0.0f, z}, n});
  for (int j = 0; j <= slices; ++j) {
    const float phi = kTwoPi * static_cast<float>(j) / static_cast<float>(slices);
    mesh.vertices.push_back({{std::cos(phi), std::sin(phi), z}, n});
  }
  for (uint32_t j = 0; j < static_cast<uint32_t>(slices); ++j) {
    const uint32_t a = centre + 1 + j, b = a + 1;
    if (up) {
      add_triangle(mesh, centre, a, b);
    } else {
      add_triangle(mesh, centre, b, a);
    }
  }
}

}  // namespace

MeshData unit_box() {
  MeshData mesh;
  add_box_face(mesh, {1, 0, 0}, {0, 1, 0}, {0, 0, 1});
  add_box_face(mesh, {-1, 0, 0}, {0, 0, 1}, {0, 1, 0});
  add_box_face(mesh, {0, 1, 0}, {0, 0, 1}, {1, 0, 0});
  add_box_face(mesh, {0, -1, 0}, {1, 0, 0}, {0, 0, 1});
  add_box_face(mesh, {0, 0, 1}, {1, 0, 0}, {0, 1, 0});
  add_box_face(mesh, {0, 0, -1}, {0, 1, 0}, {1, 0, 0});
  return mesh;
}

MeshData unit_sphere(int slices, int stacks) {
  MeshData mesh;
  // latitude theta from the north pole (+z) down, longitude phi counter-clockwise from +x
  for (int i = 0; i <= stacks; ++i) {
    const float theta =
        std::numbers::pi_v<float> * static_cast<float>(i) / static_cast<float>(stacks);
    for (int j = 0; j <= slices; ++j) {
      const float phi = kTwoPi * static_cast<float>(j) / static_cast<float>(slices);
      const std::array<float, 3> p{std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                                   std::cos(theta)};
      mesh.vertices.push_back({p, p});
    }
  }
  const auto row = static_cast<uint32_t>(slices + 1);
  for (uint32_t i = 0; i < static_cast<uint32_t>(stacks); ++i) {
    for (uint32_t j = 0; j < static_cast<uint32_t>(slices); ++j) {
      const uint32_t a = i * row + j, b = a + row, c = b + 1, d = a + 1;
      // skip the triangles that collapse at the poles
      if (i + 1 < static_cast<uint32_t>(stacks)) add_triangle(mesh, a, b, c);
      if (i > 0) add_triangle(mesh, a, c, d);
    }
  }
  return mesh;
}

MeshData unit_hemisphere(int slices, int stacks) {
  MeshData mesh;
  // latitude theta from the pole (+z) down to the equator
  for (int i = 0; i <= stacks; ++i) {
    const float theta =
        0.5f * std::numbers::pi_v<float> * static_cast<float>(i) / static_cast<float>(stacks);
    for (int j = 0; j <= slices; ++j) {
      const float phi = kTwoPi * static_cast<float>(j) / static_cast<float>(slices);
      const std::array<float, 3> p{std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                                   std::cos(theta)};
      mesh.vertices.push_back({p, p});
    }
  }
  const auto row = static_cast<uint32_t>(slices + 1);
  for (uint32_t i = 0; i < static_cast<uint32_t>(stacks); ++i) {
    for (uint32_t j = 0; j < static_cast<uint32_t>(slices); ++j) {
      const uint32_t a = i * row + j, b = a + row, c = b + 1, d = a + 1;
      add_triangle(mesh, a, b, c);
      if (i > 0) add_triangle(mesh, a, c, d);  // the pole's collapse
    }
  }
  return mesh;
}

MeshData unit_frustum(int slices) {
  MeshData mesh;
  // the side's outward normal tilts up by the slope of the taper (radius 1 -> kFrustumTaper
  // over a length of 1)
  const float slope = 1.0f - kFrustumTaper;
  const float n_scale = 1.0f / std::sqrt(1.0f + slope * slope);
  for (int j = 0; j <= slices; ++j) {
    const float phi = kTwoPi * static_cast<float>(j) / static_cast<float>(slices);
    const float x = std::cos(phi), y = std::sin(phi);
    const std::array<float, 3> n{x * n_scale, y * n_scale, slope * n_scale};
    mesh.vertices.push_back({{x, y, -0.5f}, n});
    mesh.vertices.push_back({{kFrustumTaper * x, kFrustumTaper * y, 0.5f}, n});
  }
  for (uint32_t j = 0; j < static_cast<uint32_t>(slices); ++j) {
    const uint32_t a = 2 * j, b = a + 2, c = b + 1, d = a + 1;  // bottom j, bottom j+1, tops
    add_triangle(mesh, a, b, c);
    add_triangle(mesh, a, c, d);
  }
  return mesh;
}

MeshData unit_rounded_box(int slices, int stacks) {
  // |x|^n + |y|^n + |z|^n = 0.5^n: the sphere's directions carried out to that surface, normals
  // from its gradient
  constexpr float kN = 4.0f;
  MeshData mesh = unit_sphere(slices, stacks);
  for (Vertex& v : mesh.vertices) {
    const Eigen::Vector3f d(v.position.data());
    const float k = std::pow(std::pow(std::abs(d.x()), kN) + std::pow(std::abs(d.y()), kN) +
                                 std::pow(std::abs(d.z()), kN),
                             -1.0f / kN);
    const Eigen::Vector3f p = 0.5f * k * d;
    Eigen::Vector3f n;
    for (int i = 0; i < 3; ++i) n[i] = std::copysign(std::pow(std::abs(p[i]), kN - 1.0f), p[i]);
    n.normalize();
    v.position = {p.x(), p.y(), p.z()};
    v.normal = {n.x(), n.y(), n.z()};
  }
  return mesh;
}

MeshData unit_cylinder(int slices) {
  MeshData mesh;
  for (int j = 0; j <= slices; ++j) {
    const float phi = kTwoPi * static_cast<float>(j) / static_cast<float>(slices);
    const float x = std::cos(phi), y = std::sin(phi);
    mesh.vertices.push_back({{x, y, -0.5f}, {x, y, 0.0f}});
    mesh.vertices.push_back({{x, y, 0.5f}, {x, y, 0.0f}});
  }
  for (uint32_t j = 0; j < static_cast<uint32_t>(slices); ++j) {
    const uint32_t a = 2 * j, b = a + 2, c = b + 1, d = a + 1;  // bottom j, bottom j+1, tops
    add_triangle(mesh, a, b, c);
    add_triangle(mesh, a, c, d);
  }
  add_cap(mesh, slices, 0.5f, true);
  add_cap(mesh, slices, -0.5f, false);
  return mesh;
}

MeshData model_mesh_data(model::TriangleMesh mesh) {
  MeshData out;
  const auto f3 = [](const auto& v) {
    return std::array<float, 3>{static_cast<float>(v.x()), static_cast<float>(v.y()),
                                static_cast<float>(v.z())};
  };
  const auto rgb_of = [&](uint32_t v) {
    return mesh.colors_rgba.empty()
               ? std::array<float, 3>{1.0f, 1.0f, 1.0f}
               : std::array<float, 3>{mesh.colors_rgba[v][0], mesh.colors_rgba[v][1],
                                      mesh.colors_rgba[v][2]};
  };
  const auto st_of = [&](uint32_t v) {
    return mesh.uv.empty() ? std::array<float, 2>{0.0f, 0.0f}
                           : std::array<float, 2>{mesh.uv[v].x(), 1.0f - mesh.uv[v].y()};
  };
  const auto texture_of = [&](std::size_t t) {
    return mesh.triangle_texture.empty() ? -1 : mesh.triangle_texture[t];
  };
  // the triangles in texture order (each group one draw), the file's order within a group
  std::vector<std::size_t> order(mesh.triangles.size());
  for (std::size_t t = 0; t < order.size(); ++t) order[t] = t;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return texture_of(a) < texture_of(b); });
  const bool smooth = !mesh.normals.empty();
  if (smooth) {
    out.vertices.reserve(mesh.vertices_m.size());
    for (std::size_t v = 0; v < mesh.vertices_m.size(); ++v) {
      const auto u = static_cast<uint32_t>(v);
      out.vertices.push_back({f3(mesh.vertices_m[v]), f3(mesh.normals[v]), rgb_of(u), st_of(u)});
    }
  } else {
    out.vertices.reserve(3 * mesh.triangles.size());
  }
  for (std::size_t t : order) {
    const auto& tri = mesh.triangles[t];
    if (out.groups.empty() || out.groups.back().texture != texture_of(t))
      out.groups.push_back({static_cast<uint32_t>(out.indices.size()), 0, texture_of(t)});
    out.groups.back().index_count += 3;
    if (smooth) {
      out.indices.insert(out.indices.end(), {tri[0], tri[1], tri[2]});
      continue;
    }
    const Eigen::Vector3d& a = mesh.vertices_m[tri[0]];
    const Eigen::Vector3d n =
        (mesh.vertices_m[tri[1]] - a).cross(mesh.vertices_m[tri[2]] - a).normalized();
    for (uint32_t v : tri) {
      out.indices.push_back(index_of(out));
      out.vertices.push_back({f3(mesh.vertices_m[v]), f3(n), rgb_of(v), st_of(v)});
    }
  }
  out.textures = std::move(mesh.textures);
  return out;
}

}  // namespace vcockpit::render
