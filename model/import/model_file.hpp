#pragma once
// Meshes from model files through Debian's Open Asset Import Library (assimp 5.2): glTF 2.0
// (.gltf, .glb), Wavefront OBJ (.obj) and AC3D (.ac, the format of FlightGear's cockpits).
// One node (or the whole file) becomes one TriangleMesh in the project's units and axes.

#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "model/import/isolated_reader.hpp"
#include "model/triangle_mesh.hpp"

namespace vcockpit::model {

enum class UpAxis { kY, kZ };

struct ModelRequest {
  std::string path;  // the model file
  // a node's name: its meshes and its children's, in that node's own frame (the node's own
  // placement in the file is left out: the scene's pose places it). Empty: every mesh of the
  // file, in the file's frame.
  std::string node;
  double scale = 1.0;  // file units to metres (glTF is in metres; OBJ and AC3D have no unit)
  // The file's up axis: +y for glTF (its specification), and by default for OBJ and AC3D
  // (Blender's exports, FlightGear's models); turned to the project's +z up by a quarter turn
  // about x: (x, y, z) -> (x, -z, y).
  UpAxis up = UpAxis::kY;
  // Decode the parts' texture images (the image generator's need; the physics never reads them).
  bool textures = false;
};

// Throws MeshError naming the file (and node): missing, unsupported, unreadable, no such node
// (with the file's node names), no triangles, a non-finite vertex, every triangle degenerate, or
// the reader crashed or hung on it (it runs in a child process: isolated_reader.hpp). Triangles
// with no area among good ones are left out and counted (TriangleMesh::degenerate_dropped), as
// are texture images that are not found or cannot be decoded (TriangleMesh::textures_left_out):
// their triangles keep their colour.
TriangleMesh load_model_mesh(const ModelRequest& request);

// Several parts of one file (every request's path the same: std::invalid_argument otherwise),
// read in one go: the file parsed once, in one child process, where load_model_mesh per part
// parses it once each (a flight simulator's cockpit is one file of many nodes). Each request's
// mesh, or its MeshError's message, comes back in its place; a file that cannot be read at all
// (missing, unsupported, unreadable, the reader crashed) throws, as load_model_mesh does.
std::vector<ModelPart> load_model_parts(const std::vector<ModelRequest>& requests);

// While one lives, the parts `requests` name are read beforehand, each file's in one go
// (load_model_parts), and load_model_mesh hands them out for the same requests (path, node,
// scale, up axis, textures) without reading the file again. A scene's loader holds one over
// its objects, the image generator over a batch of objects' infos: a cockpit of many parts in
// one file is parsed once, not once per part. A file that cannot be read at all gives each of
// its parts the error reading it alone would (not read again). Several may live at once
// (threads loading scenes); thread-safe.
class ModelPrefetch {
 public:
  explicit ModelPrefetch(const std::vector<ModelRequest>& requests);
  ~ModelPrefetch();
  ModelPrefetch(const ModelPrefetch&) = delete;
  ModelPrefetch& operator=(const ModelPrefetch&) = delete;

 private:
  std::unique_ptr<const std::map<std::string, ModelPart>> parts_;
};

// How many model files this process has parsed (each load_model_mesh one, each
// load_model_parts one): what tests count to see a file read once.
uint64_t model_file_reads();

// The same from the bytes of a file in memory, of the format its `extension` names ("gltf",
// "glb", "obj", "ac"); request.path only names it in messages (files it refers to are not read:
// only embedded textures are).
TriangleMesh load_model_mesh_from_memory(std::string_view bytes, const std::string& extension,
                                         const ModelRequest& request);

}  // namespace vcockpit::model
