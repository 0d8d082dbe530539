#include "image_generator/render/mesh_buffers.hpp"

#include <algorithm>
#include <cstdint>

#include "image_generator/render/meshes.hpp"
#include "image_generator/render/shaders.hpp"

namespace vcockpit::render {
namespace {

const void* offset(size_t bytes) {
  return reinterpret_cast<const void*>(bytes);
}

// per-instance attributes from the instance buffer, bound to the current vertex array
void bind_instance_attributes(GLuint instance_buffer) {
  glBindBuffer(GL_ARRAY_BUFFER, instance_buffer);
  constexpr GLsizei kStride = sizeof(InstanceRecord);
  for (GLuint column = 0; column < 4; ++column) {
    const GLuint location = attrib::kX_GO + column;
    glEnableVertexAttribArray(location);
    glVertexAttribPointer(location, 4, GL_FLOAT, GL_FALSE, kStride,
                          offset(offsetof(InstanceRecord, X_GO) + column * 4 * sizeof(float)));
    glVertexAttribDivisor(location, 1);
  }
  glEnableVertexAttribArray(attrib::kScaleHighlight);
  glVertexAttribPointer(attrib::kScaleHighlight, 4, GL_FLOAT, GL_FALSE, kStride,
                        offset(offsetof(InstanceRecord, scale_highlight)));
  glVertexAttribDivisor(attrib::kScaleHighlight, 1);
  glEnableVertexAttribArray(attrib::kRgba);
  glVertexAttribPointer(attrib::kRgba, 4, GL_FLOAT, GL_FALSE, kStride,
                        offset(offsetof(InstanceRecord, rgba)));
  glVertexAttribDivisor(attrib::kRgba, 1);
}

void bind_vertex_attributes(GLuint vertex_buffer) {
  glBindBuffer(GL_ARRAY_BUFFER, vertex_buffer);
  constexpr GLsizei kStride = sizeof(Vertex);
  glEnableVertexAttribArray(attrib::kPosition);
  glVertexAttribPointer(attrib::kPosition, 3, GL_FLOAT, GL_FALSE, kStride,
                        offset(offsetof(Vertex, position)));
  glEnableVertexAttribArray(attrib::kNormal);
  glVertexAttribPointer(attrib::kNormal, 3, GL_FLOAT, GL_FALSE, kStride,
                        offset(offsetof(Vertex, normal)));
  glEnableVertexAttribArray(attrib::kVertexRgb);
  glVertexAttribPointer(attrib::kVertexRgb, 3, GL_FLOAT, GL_FALSE, kStride,
                        offset(offsetof(Vertex, rgb)));
  glEnableVertexAttribArray(attrib::kVertexSt);
  glVertexAttribPointer(attrib::kVertexSt, 2, GL_FLOAT, GL_FALSE, kStride,
                        offset(offsetof(Vertex, st)));
}

GLint gl_wrap(model::TextureWrap wrap) {
  switch (wrap) {
    case model::TextureWrap::kClampToEdge:
      return GL_CLAMP_TO_EDGE;
    case model::TextureWrap::kMirroredRepeat:
      return GL_MIRRORED_REPEAT;
    default:
      return GL_REPEAT;
  }
}

// An image on the GPU, mipmapped (a label read from across the cockpit stays legible, not
// aliased), sampled as its model says (by default glTF's: repeated past [0, 1], trilinear).
GLuint make_texture(uint32_t width, uint32_t height, const uint8_t* rgba,
                    const model::TextureSampler& sampler = {}) {
  GLuint texture = 0;
  glGenTextures(1, &texture);
  glBindTexture(GL_TEXTURE_2D, texture);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, static_cast<GLsizei>(width),
               static_cast<GLsizei>(height), 0, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
  glGenerateMipmap(GL_TEXTURE_2D);
  const bool nearest_min = sampler.minify == model::TextureFilter::kNearest;
  const bool nearest_mag = sampler.magnify == model::TextureFilter::kNearest;
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER,
                  nearest_min ? GL_NEAREST_MIPMAP_NEAREST : GL_LINEAR_MIPMAP_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, nearest_mag ? GL_NEAREST : GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, gl_wrap(sampler.wrap_u));
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, gl_wrap(sampler.wrap_v));
  glBindTexture(GL_TEXTURE_2D, 0);
  return texture;
}

}  // namespace

MeshBuffers::MeshBuffers() {
  glGenBuffers(1, &instance_buffer_);
  const uint8_t white[4] = {255, 255, 255, 255};
  white_texture_ = make_texture(1, 1, white);
  const std::array<MeshData, kUnitMeshCount> data{unit_box(),       unit_sphere(),
                                                  unit_cylinder(),  unit_hemisphere(),
                                                  unit_frustum(),   unit_rounded_box()};
  for (int m = 0; m < kUnitMeshCount; ++m)
    make_gpu_mesh(data[m], meshes_[m]);
}

void MeshBuffers::make_gpu_mesh(const MeshData& data, GpuMesh& mesh) const {
  glGenVertexArrays(1, &mesh.vertex_array);
  glBindVertexArray(mesh.vertex_array);
  glGenBuffers(1, &mesh.vertex_buffer);
  glBindBuffer(GL_ARRAY_BUFFER, mesh.vertex_buffer);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(data.vertices.size() * sizeof(Vertex)),
               data.vertices.data(), GL_STATIC_DRAW);
  glGenBuffers(1, &mesh.index_buffer);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, mesh.index_buffer);  // recorded in the vertex array
  glBufferData(GL_ELEMENT_ARRAY_BUFFER,
               static_cast<GLsizeiptr>(data.indices.size() * sizeof(uint32_t)), data.indices.data(),
               GL_STATIC_DRAW);
  mesh.index_count = static_cast<GLsizei>(data.indices.size());
  bind_vertex_attributes(mesh.vertex_buffer);
  bind_instance_attributes(instance_buffer_);
  glBindVertexArray(0);
  mesh.groups = data.groups;
  for (const model::TextureImage& image : data.textures)
    mesh.textures.push_back(make_texture(image.width, image.height, image.rgba.data(), image.sampler));
}

void MeshBuffers::delete_gpu_mesh(GpuMesh& mesh) {
  glDeleteVertexArrays(1, &mesh.vertex_array);
  glDeleteBuffers(1, &mesh.vertex_buffer);
  glDeleteBuffers(1, &mesh.index_buffer);
  if (!mesh.textures.empty())
    glDeleteTextures(static_cast<GLsizei>(mesh.textures.size()), mesh.textures.data());
}

MeshBuffers::~MeshBuffers() {
  for (GpuMesh& mesh : meshes_)
    delete_gpu_mesh(mesh);
  for (auto& [data, mesh] : model_meshes_)
    delete_gpu_mesh(mesh);
  glDeleteBuffers(1, &instance_buffer_);
  glDeleteTextures(1, &white_texture_);
}

void MeshBuffers::upload(const PackedInstances& packed) {
  for (auto it = model_meshes_.begin(); it != model_meshes_.end();) {
    if (!it->second.owner.expired()) {
      ++it;
      continue;
    }
    delete_gpu_mesh(it->second);
    it = model_meshes_.erase(it);
  }
  for (std::size_t k = 0; k < packed.model_meshes.size(); ++k) {
    const MeshData* data = packed.model_meshes[k];
    if (model_meshes_.count(data) != 0) continue;
    GpuMesh& mesh = model_meshes_[data];
    make_gpu_mesh(*data, mesh);
    mesh.owner = packed.model_owners[k];
  }
  const size_t count = packed.records.size();
  if (count == 0) return;
  glBindBuffer(GL_ARRAY_BUFFER, instance_buffer_);
  if (count > instance_capacity_) {
    // grow with headroom so a slowly growing scene reallocates rarely
    instance_capacity_ = std::max<size_t>({count, 2 * instance_capacity_, 64});
    glBufferData(GL_ARRAY_BUFFER,
                 static_cast<GLsizeiptr>(instance_capacity_ * sizeof(InstanceRecord)), nullptr,
                 GL_DYNAMIC_DRAW);
  }
  glBufferSubData(GL_ARRAY_BUFFER, 0, static_cast<GLsizeiptr>(count * sizeof(InstanceRecord)),
                  packed.records.data());
}

void MeshBuffers::draw(UnitMesh mesh, const MeshRange& range) const {
  draw(meshes_[static_cast<int>(mesh)], range);
}

void MeshBuffers::draw(const MeshData* mesh, const MeshRange& range) const {
  const auto it = model_meshes_.find(mesh);
  if (it != model_meshes_.end()) draw(it->second, range);
}

void MeshBuffers::draw(const GpuMesh& gpu, const MeshRange& range) const {
  if (range.count == 0) return;
  glBindVertexArray(gpu.vertex_array);
  glActiveTexture(GL_TEXTURE0);
  if (gpu.groups.empty()) {
    glBindTexture(GL_TEXTURE_2D, white_texture_);
    glDrawElementsInstancedBaseInstance(GL_TRIANGLES, gpu.index_count, GL_UNSIGNED_INT, nullptr,
                                        range.count, static_cast<GLuint>(range.first));
    return;
  }
  for (const MeshGroup& group : gpu.groups) {
    const bool textured = group.texture >= 0 &&
                          static_cast<std::size_t>(group.texture) < gpu.textures.size();
    glBindTexture(GL_TEXTURE_2D, textured ? gpu.textures[static_cast<std::size_t>(group.texture)]
                                          : white_texture_);
    glDrawElementsInstancedBaseInstance(GL_TRIANGLES, static_cast<GLsizei>(group.index_count),
                                        GL_UNSIGNED_INT, offset(group.first_index * sizeof(uint32_t)),
                                        range.count, static_cast<GLuint>(range.first));
  }
}

}  // namespace vcockpit::render
