// A model file (model/import: glTF, OBJ or AC3D through assimp; the first byte picks the format,
// the rest is the file): any bytes are either a mesh or a MeshError naming the file, whatever
// assimp does with them (it reads in a child process: a crash or a hang there is such an error;
// so this target checks the project's side, the child's answer and its decoding, not assimp's
// coverage, which libFuzzer does not see across the fork). A mesh has
// finite vertices, indices in range and no degenerate triangle (check_mesh's promise); its hull
// is either a closed solid of positive volume or a MeshError, and its mass properties are finite.

#include <cmath>
#include <string>

#include "fuzz/fuzz_support.hpp"
#include "model/convex_hull.hpp"
#include "model/import/model_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  using namespace vcockpit;
  if (size == 0) return 0;
  static const char* const kFormats[] = {"gltf", "obj", "ac", "glb"};
  const std::string format = kFormats[data[0] % 4];
  const std::string_view bytes = fuzz::as_text(data + 1, size - 1);
  model::TriangleMesh mesh;
  try {
    // with textures: an embedded image is decoded in the reader's child as the image generator's is
    mesh = model::load_model_mesh_from_memory(bytes, format,
                                              {"fuzz." + format, "", 1.0, model::UpAxis::kY, true});
  } catch (const model::MeshError& e) {
    fuzz::require(std::string(e.what()).rfind("fuzz." + format + ":", 0) == 0,
                  "a model error names the file first");
    return 0;
  }
  model::check_mesh(mesh);  // throws (and so aborts: uncaught) if the loader let one through
  fuzz::require(mesh.colors_rgba.empty() || mesh.colors_rgba.size() == mesh.vertices_m.size(),
                "a colour per vertex or none");
  try {
    const model::TriangleMesh hull = model::convex_hull(mesh);
    const model::MassProperties m = model::mass_properties(hull);
    fuzz::require(std::isfinite(m.volume_m3) && m.volume_m3 > 0.0, "a hull has a volume");
    fuzz::require(m.centroid_m.allFinite() && m.unit_density_inertia.allFinite(),
                  "a hull's mass properties are finite");
  } catch (const model::MeshError&) {
    // flat, or fewer than 4 vertices: named, refused
  }
  return 0;
}
