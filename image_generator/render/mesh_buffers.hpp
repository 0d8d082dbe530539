#pragma once
// The unit meshes on the GPU (one vertex array each), the models' meshes and textures as they
// come, and the one instance buffer they all read their per-instance attributes from. The instance buffer grows when the count grows, never
// shrinks, and is otherwise updated in place.

#include <array>
#include <cstddef>
#include <memory>
#include <unordered_map>
#include <vector>

#include "image_generator/render/gl.hpp"
#include "image_generator/render/instance_packing.hpp"
#include "image_generator/render/meshes.hpp"

namespace vcockpit::render {

class MeshBuffers {
 public:
  // Uploads the unit box, sphere and cylinder; needs a current context.
  MeshBuffers();
  ~MeshBuffers();
  MeshBuffers(const MeshBuffers&) = delete;
  MeshBuffers& operator=(const MeshBuffers&) = delete;

  // The records, and any model mesh among them not yet on the GPU.
  void upload(const PackedInstances& packed);
  // One instanced draw of `mesh` for the records in `range`; nothing if the range is empty.
  void draw(UnitMesh mesh, const MeshRange& range) const;
  // The same for a model mesh uploaded by upload().
  void draw(const MeshData* mesh, const MeshRange& range) const;

  int triangle_count(UnitMesh mesh) const {
    return meshes_[static_cast<int>(mesh)].index_count / 3;
  }

 private:
  struct GpuMesh {
    GLuint vertex_array = 0;
    GLuint vertex_buffer = 0;
    GLuint index_buffer = 0;
    GLsizei index_count = 0;
    std::vector<MeshGroup> groups;  // a model's; empty: one draw of every index
    std::vector<GLuint> textures;   // its images, as MeshGroup::texture numbers them
    std::weak_ptr<const MeshData> owner;  // a model's data; expired: its copy here is stale
  };

  void make_gpu_mesh(const MeshData& data, GpuMesh& mesh) const;
  static void delete_gpu_mesh(GpuMesh& mesh);
  void draw(const GpuMesh& gpu, const MeshRange& range) const;

  GLuint instance_buffer_ = 0;
  GLuint white_texture_ = 0;  // what the untextured sample
  size_t instance_capacity_ = 0;  // records
  std::array<GpuMesh, kUnitMeshCount> meshes_{};
  // model meshes by address: an instance's shared_ptr keeps the data alive while it is drawn.
  // A copy whose data has gone is deleted at the next upload, so that a new mesh made at the
  // same address is not drawn with the old one's triangles.
  std::unordered_map<const MeshData*, GpuMesh> model_meshes_;
};

}  // namespace vcockpit::render
