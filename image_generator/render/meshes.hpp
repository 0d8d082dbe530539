#pragma once
// Unit meshes on the CPU, scaled per instance in the vertex shader. Triangles wind
// counter-clockwise seen from outside, normals point outwards.
//   box: [-0.5, 0.5]^3, flat faces
//   sphere: radius 1, centred
//   cylinder: radius 1, z in [-0.5, 0.5], with flat end caps
//   frustum, rounded box: below
// llvmpipe's front end (vertex shading, clipping, binning) is single-threaded and costs about
// 0.25 us per triangle here whatever the batching, so the defaults are coarse: 224 triangles a
// sphere, 64 a cylinder. Sphere and cylinder share 16 slices so capsule caps meet the tube's rim.

#include <array>
#include <cstdint>
#include <vector>

#include "model/triangle_mesh.hpp"

namespace vcockpit::render {

struct Vertex {
  std::array<float, 3> position;
  std::array<float, 3> normal;
  std::array<float, 3> rgb{1.0f, 1.0f, 1.0f};  // times the instance's colour
  // where the vertex samples its texture: s right, t down from the image's top row (the rows
  // are uploaded top first); an untextured vertex samples a white texel
  std::array<float, 2> st{0.0f, 0.0f};
};

// Triangles that sample one texture: indices [first_index, first_index + index_count).
struct MeshGroup {
  uint32_t first_index = 0;
  uint32_t index_count = 0;
  int32_t texture = -1;  // in MeshData::textures; -1 none
};

struct MeshData {
  std::vector<Vertex> vertices;
  std::vector<uint32_t> indices;  // triangles
  // a model's: its triangles by texture, and the images (empty: one untextured group)
  std::vector<MeshGroup> groups;
  std::vector<model::TextureImage> textures;
};

MeshData unit_box();
MeshData unit_sphere(int slices = 16, int stacks = 8);
MeshData unit_cylinder(int slices = 16);
// The +z half of a unit sphere, open at z = 0 (a capsule's end cap).
MeshData unit_hemisphere(int slices = 12, int stacks = 3);
// The side of a cone's frustum along z in [-0.5, 0.5], radius 1 at -z narrowing to
// kFrustumTaper at +z, open at both ends (a tapered capsule's body, closed by its caps).
constexpr float kFrustumTaper = 0.8f;
MeshData unit_frustum(int slices = 12);
// A box in [-0.5, 0.5]^3 with its edges and corners rounded: the superellipsoid
// |x|^4 + |y|^4 + |z|^4 = 0.5^4 (a hand's palm).
MeshData unit_rounded_box(int slices = 24, int stacks = 12);

// A model's mesh to draw in its own frame (scale 1): its normals and colours per vertex where it
// has them, else flat faces (each triangle its own three vertices and normal) in white; its
// triangles grouped by the texture they sample.
MeshData model_mesh_data(model::TriangleMesh mesh);  // (its images are moved, not copied)

}  // namespace vcockpit::render
