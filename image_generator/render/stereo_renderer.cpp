#include "image_generator/render/stereo_renderer.hpp"

#include <cstdio>
#include <string>

#include "image_generator/render/camera.hpp"
#include "image_generator/render/gl.hpp"
#include "image_generator/render/gl_context.hpp"
#include "image_generator/render/mesh_buffers.hpp"
#include "image_generator/render/render_error.hpp"
#include "image_generator/render/shaders.hpp"

namespace vcockpit::render {
namespace {

void check_gl(const char* stage) {
  const GLenum error = glGetError();
  if (error != GL_NO_ERROR) {
    char code[16];
    std::snprintf(code, sizeof(code), "0x%04x", error);
    throw RenderError(std::string("GL: error ") + code + " during " + stage);
  }
}

constexpr std::array<UnitMesh, kUnitMeshCount> kMeshes{UnitMesh::kBox, UnitMesh::kSphere,
                                                       UnitMesh::kCylinder};

}  // namespace

StereoRenderer::StereoRenderer(const HmdConfig& config) : config_(config) {
  config_.validate();
  for (const Eye eye : {Eye::kLeft, Eye::kRight}) {
    projection_[eye_index(eye)] =
        off_axis_projection(config_.eye_fov(eye), config_.near_m, config_.far_m);
  }
  context_ = std::make_unique<GlContext>(2 * config_.width_px, config_.height_px);
  check_gl("context creation");
  program_ = std::make_unique<LitProgram>();
  meshes_ = std::make_unique<MeshBuffers>();
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glEnable(GL_CULL_FACE);  // closed meshes, counter-clockwise outside
  glCullFace(GL_BACK);
  glFrontFace(GL_CCW);
  glClearColor(kBackgroundRgb[0], kBackgroundRgb[1], kBackgroundRgb[2], 1.0f);
  check_gl("renderer set-up");
}

StereoRenderer::~StereoRenderer() {
  context_->make_current();  // GL objects are deleted by the members below, in this context
  meshes_.reset();
  program_.reset();
}

void StereoRenderer::render(const std::vector<Instance>& instances,
                            const Eigen::Isometry3d& X_GHead) {
  context_->make_current();
  pack_instances(instances, packed_);
  meshes_->upload(packed_);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);  // both halves at once
  program_->use();
  last_draw_calls_ = 0;
  draw_eye(Eye::kLeft, X_GHead);
  draw_eye(Eye::kRight, X_GHead);
  glFinish();  // llvmpipe renders lazily: the buffer is complete only after this
  while (glGetError() != GL_NO_ERROR)
    ++gl_error_count_;
}

void StereoRenderer::draw_eye(Eye eye, const Eigen::Isometry3d& X_GHead) {
  const int i = eye_index(eye);
  glViewport(i * config_.width_px, 0, config_.width_px, config_.height_px);
  const Eigen::Isometry3d X_GE = eye_pose(config_, eye, X_GHead);
  program_->set_view_projection(projection_[i] * view_matrix(X_GE));
  program_->set_eye_position(X_GE.translation().cast<float>());
  for (const UnitMesh mesh : kMeshes) {
    const MeshRange& range = packed_.range(mesh);
    meshes_->draw(mesh, range);
    if (range.count > 0) ++last_draw_calls_;
  }
}

const uint8_t* StereoRenderer::pixels() const {
  return context_->pixels();
}

std::string StereoRenderer::gl_renderer() const {
  return context_->renderer();
}

std::string StereoRenderer::gl_version() const {
  return context_->version();
}

}  // namespace vcockpit::render
