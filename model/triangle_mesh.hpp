#pragma once
// A triangle mesh as the project uses it, in metres and in the project's axes (+z up), whatever
// file it came from (model/import): the geometry the physics collides (a static object's
// triangles, a moving part's convex hull) and the image generator draws. No file formats, no
// DDS, no YAML here.

#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace vcockpit::model {

// An image a mesh's triangles sample: 8-bit RGBA, rows from the top, decoded from its file
// (model/import/texture_image.hpp). `name` is what the model file calls it.
// How a texture is sampled (glTF's sampler; OBJ's "-clamp on"): past [0, 1] along u and v, and
// when magnified and minified. The defaults are glTF's when a file gives none.
enum class TextureWrap : uint8_t { kRepeat, kClampToEdge, kMirroredRepeat };
enum class TextureFilter : uint8_t { kLinear, kNearest };
struct TextureSampler {
  TextureWrap wrap_u = TextureWrap::kRepeat;
  TextureWrap wrap_v = TextureWrap::kRepeat;
  TextureFilter magnify = TextureFilter::kLinear;
  // minified: between the image's mipmap levels (kLinear: trilinear), or the nearest texel of
  // the nearest level (kNearest: a pixel-art or lookup-table image stays crisp)
  TextureFilter minify = TextureFilter::kLinear;
  bool operator==(const TextureSampler&) const = default;
};

struct TextureImage {
  std::string name;
  uint32_t width = 0;
  uint32_t height = 0;
  std::vector<uint8_t> rgba;  // width * height * 4
  TextureSampler sampler;
};

struct TriangleMesh {
  std::vector<Eigen::Vector3d> vertices_m;
  std::vector<std::array<uint32_t, 3>> triangles;  // counter-clockwise seen from outside
  // what to draw (optional): a normal per vertex (empty: flat faces), a colour per vertex (its
  // part's material; empty: the object's colour alone)
  std::vector<Eigen::Vector3f> normals;
  std::vector<std::array<float, 4>> colors_rgba;
  // textures (optional): a coordinate per vertex (u right, v up from the image's bottom row), the
  // images, and per triangle the image it samples or -1 (empty: none does). A textured
  // triangle's colour is its vertices' colour times the image (glTF's base colour factor times
  // its base colour texture).
  std::vector<Eigen::Vector2f> uv;
  std::vector<TextureImage> textures;
  std::vector<int32_t> triangle_texture;
  // Textures the file names that were not found or could not be decoded: drawn without them,
  // reported, the first one named with why ("'panel.dds': not a PNG or JPEG image").
  uint64_t textures_left_out = 0;
  std::string first_texture_left_out;
  std::string source;  // "FILE node 'NAME'": what errors and logs name
  // Triangles of the file left out for having no area (model/import), and the first one's
  // index in the file's order: reported, not refused (CAD and simulator models have some).
  uint64_t degenerate_dropped = 0;
  uint64_t first_degenerate = 0;
};

// The triangles with no area (below min_area_m2, or a vertex used twice) taken out, counted in
// degenerate_dropped; a MeshError naming mesh.source if none is left.
void drop_degenerate_triangles(TriangleMesh& mesh, double min_area_m2 = 1e-14);

// A mesh that cannot be used, with what and where: "cockpit.glb node 'panel': triangle 12 has no
// area".
class MeshError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Refuses an empty mesh, a non-finite vertex, an index past the vertices and a triangle with no
// area (below min_area_m2), naming mesh.source and the first offending vertex or triangle; and
// texture data that does not fit together (coordinates not one per vertex or not finite, a
// triangle's image that is not there, an image whose pixels are not width x height).
void check_mesh(const TriangleMesh& mesh, double min_area_m2 = 1e-14);

// Volume, centroid and inertia of the solid a closed, outward-oriented mesh bounds, at unit
// density (divergence theorem over signed tetrahedra from the origin; Eberly, "Polyhedral Mass
// Properties", 2002). Inertia about the centroid, in the mesh's frame.
struct MassProperties {
  double volume_m3 = 0.0;
  Eigen::Vector3d centroid_m = Eigen::Vector3d::Zero();
  Eigen::Matrix3d unit_density_inertia = Eigen::Matrix3d::Zero();
};
MassProperties mass_properties(const TriangleMesh& mesh);

// Axis-aligned bounds of the vertices.
struct Bounds {
  Eigen::Vector3d min_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d max_m = Eigen::Vector3d::Zero();
};
Bounds bounds(const TriangleMesh& mesh);

// The mesh moved by `shift_m` (every vertex plus shift_m).
void translate(TriangleMesh& mesh, const Eigen::Vector3d& shift_m);

}  // namespace vcockpit::model
