#include "image_generator/render/stereo_renderer.hpp"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <string>

#include "image_generator/render/camera.hpp"
#include "image_generator/render/gl.hpp"
#include "image_generator/render/gl_context.hpp"
#include "image_generator/render/mesh_buffers.hpp"
#include "image_generator/render/outside_view.hpp"
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

constexpr std::array<UnitMesh, kUnitMeshCount> kMeshes{UnitMesh::kBox,      UnitMesh::kSphere,
                                                       UnitMesh::kCylinder, UnitMesh::kCap,
                                                       UnitMesh::kFrustum,  UnitMesh::kRoundedBox};

int64_t now_ns() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return int64_t{ts.tv_sec} * 1'000'000'000 + ts.tv_nsec;
}

bool same_pose(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return std::memcmp(a.matrix().data(), b.matrix().data(), sizeof(double) * 16) == 0;
}

// A framebuffer with an RGBA8 colour and a 24-bit depth renderbuffer of the given size.
void make_framebuffer(GLsizei width, GLsizei height, unsigned& framebuffer, unsigned& colour,
                      unsigned& depth) {
  glGenFramebuffers(1, &framebuffer);
  glGenRenderbuffers(1, &colour);
  glGenRenderbuffers(1, &depth);
  glBindRenderbuffer(GL_RENDERBUFFER, colour);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
  glBindRenderbuffer(GL_RENDERBUFFER, depth);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, width, height);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colour);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw RenderError("GL: a framebuffer of renderbuffers is incomplete");
}

void delete_framebuffer(unsigned framebuffer, unsigned colour, unsigned depth) {
  glDeleteFramebuffers(1, &framebuffer);
  glDeleteRenderbuffers(1, &colour);
  glDeleteRenderbuffers(1, &depth);
}

}  // namespace

namespace {
HmdConfig validated(HmdConfig config) {
  config.validate();
  return config;
}
}  // namespace

StereoRenderer::StereoRenderer(const HmdConfig& config)
    : config_(validated(config)),
      frames_(static_cast<std::size_t>(2 * config_.width_px) * config_.height_px * 4) {
  // Frames are drawn upside down (y flipped in the projection), so that glReadPixels, which
  // returns the bottom row first, gives the image top row first with no flip afterwards.
  const Eigen::Matrix4f flip_y = Eigen::Vector4f(1, -1, 1, 1).asDiagonal();
  for (const Eye eye : {Eye::kLeft, Eye::kRight}) {
    projection_[eye_index(eye)] =
        flip_y * off_axis_projection(config_.eye_fov(eye), config_.near_m, config_.far_m);
  }
  // The frame is drawn into framebuffers of the renderer's own; OSMesa's buffer is only what
  // the context needs to be current.
  context_ = std::make_unique<GlContext>(1, 1);
  check_gl("context creation");
  program_ = std::make_unique<LitProgram>();
  if (config_.outside) outside_program_ = std::make_unique<OutsideViewProgram>();
  for (Layer* layer : {&moving_, &background_}) {
    layer->opaque_meshes = std::make_unique<MeshBuffers>();
    layer->translucent_meshes = std::make_unique<MeshBuffers>();
  }
  for (const UnitMesh mesh : kMeshes)
    unit_mesh_triangles_[static_cast<std::size_t>(mesh)] = moving_.opaque_meshes->triangle_count(mesh);
  // the frame and the background layer, both eyes side by side; the same formats, so the
  // background is restored by copying images (a memcpy in llvmpipe; a blit of the depth was
  // a shader pass costing 9 ms a frame here)
  make_framebuffer(2 * config_.width_px, config_.height_px, frame_framebuffer_, frame_colour_,
                   frame_depth_);
  make_framebuffer(2 * config_.width_px, config_.height_px, background_framebuffer_,
                   background_colour_, background_depth_);
  glBindFramebuffer(GL_FRAMEBUFFER, frame_framebuffer_);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glEnable(GL_CULL_FACE);  // closed meshes, counter-clockwise outside (clockwise once flipped)
  glCullFace(GL_BACK);
  glFrontFace(GL_CW);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  // the translucent pass: colour over what is behind; the frame's alpha stays 1
  glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO, GL_ONE);
  glClearColor(kBackgroundRgb[0], kBackgroundRgb[1], kBackgroundRgb[2], 1.0f);
  check_gl("renderer set-up");
}

StereoRenderer::~StereoRenderer() {
  context_->make_current();  // GL objects are deleted by the members below, in this context
  delete_framebuffer(background_framebuffer_, background_colour_, background_depth_);
  delete_framebuffer(frame_framebuffer_, frame_colour_, frame_depth_);
  for (Layer* layer : {&moving_, &background_}) {
    layer->opaque_meshes.reset();
    layer->translucent_meshes.reset();
  }
  outside_program_.reset();
  program_.reset();
}

void StereoRenderer::render(const std::vector<Instance>& instances,
                            const Eigen::Isometry3d& X_GHead) {
  split_fixed_.clear();
  split_.clear();
  for (const Instance& instance : instances) (instance.fixed ? split_fixed_ : split_).push_back(instance);
  begin_frame(split_fixed_, X_GHead);
  draw_moving(split_);
  end_frame();
}

void StereoRenderer::begin_frame(std::span<const Instance> fixed, const Eigen::Isometry3d& X_GHead) {
  frame_start_ns_ = now_ns();
  context_->make_current();
  cost_ = FrameCost{};
  last_draw_calls_ = 0;
  X_GHead_ = X_GHead;
  pack_layer(fixed, background_);
  cost_.fixed_triangles = triangles_in(background_);
  if (!cache_on_) {  // everything drawn every frame, straight into the frame
    background_valid_ = false;
    glBindFramebuffer(GL_FRAMEBUFFER, frame_framebuffer_);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);  // both halves at once
    draw_layer(background_, true);
    cost_.background_ns = now_ns() - frame_start_ns_;
    return;
  }
  if (background_changed(X_GHead)) redraw_background(X_GHead);
  // the frame starts as a copy of the background: colour and depth, both eyes
  const GLsizei w = 2 * config_.width_px, h = config_.height_px;
  glCopyImageSubData(background_colour_, GL_RENDERBUFFER, 0, 0, 0, 0, frame_colour_,
                     GL_RENDERBUFFER, 0, 0, 0, 0, w, h, 1);
  glCopyImageSubData(background_depth_, GL_RENDERBUFFER, 0, 0, 0, 0, frame_depth_,
                     GL_RENDERBUFFER, 0, 0, 0, 0, w, h, 1);
  glBindFramebuffer(GL_FRAMEBUFFER, frame_framebuffer_);
  cost_.background_ns = now_ns() - frame_start_ns_;
}

bool StereoRenderer::background_changed(const Eigen::Isometry3d& X_GHead) const {
  const PackedInstances& opaque = background_.opaque;
  const PackedInstances& translucent = background_.translucent;
  if (!background_valid_ || !same_pose(X_GHead, background_X_GHead_)) return true;
  if (translucent.records.size() != background_translucent_count_) return true;
  if (opaque.records.size() + translucent.records.size() != background_records_.size()) return true;
  const std::size_t record = sizeof(InstanceRecord);
  if (!opaque.records.empty() &&
      std::memcmp(opaque.records.data(), background_records_.data(), opaque.records.size() * record) != 0)
    return true;
  if (!translucent.records.empty() &&
      std::memcmp(translucent.records.data(), background_records_.data() + opaque.records.size(),
                  translucent.records.size() * record) != 0)
    return true;
  const auto same_ranges = [](const MeshRange* a, const MeshRange* b, std::size_t n) {
    for (std::size_t i = 0; i < n; ++i)
      if (a[i].first != b[i].first || a[i].count != b[i].count) return false;
    return true;
  };
  if (!same_ranges(opaque.ranges.data(), background_opaque_ranges_.data(), kUnitMeshCount) ||
      !same_ranges(translucent.ranges.data(), background_translucent_ranges_.data(), kUnitMeshCount))
    return true;
  const std::size_t models = opaque.model_meshes.size();
  if (models + translucent.model_meshes.size() != background_model_meshes_.size()) return true;
  if (!same_ranges(opaque.model_ranges.data(), background_model_ranges_.data(), models) ||
      !same_ranges(translucent.model_ranges.data(), background_model_ranges_.data() + models,
                   translucent.model_meshes.size()))
    return true;
  return !std::equal(opaque.model_meshes.begin(), opaque.model_meshes.end(), background_model_meshes_.begin()) ||
         !std::equal(translucent.model_meshes.begin(), translucent.model_meshes.end(),
                     background_model_meshes_.begin() + static_cast<std::ptrdiff_t>(models));
}

void StereoRenderer::redraw_background(const Eigen::Isometry3d& X_GHead) {
  glBindFramebuffer(GL_FRAMEBUFFER, background_framebuffer_);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  draw_layer(background_, true);
  glBindFramebuffer(GL_FRAMEBUFFER, frame_framebuffer_);
  // what it shows, to compare the next frames' with (assign: no allocation once grown)
  const PackedInstances& opaque = background_.opaque;
  const PackedInstances& translucent = background_.translucent;
  background_records_.assign(opaque.records.begin(), opaque.records.end());
  background_records_.insert(background_records_.end(), translucent.records.begin(), translucent.records.end());
  background_model_meshes_.assign(opaque.model_meshes.begin(), opaque.model_meshes.end());
  background_model_meshes_.insert(background_model_meshes_.end(), translucent.model_meshes.begin(),
                                  translucent.model_meshes.end());
  background_translucent_count_ = translucent.records.size();
  background_opaque_ranges_ = opaque.ranges;
  background_translucent_ranges_ = translucent.ranges;
  background_model_ranges_.assign(opaque.model_ranges.begin(), opaque.model_ranges.end());
  background_model_ranges_.insert(background_model_ranges_.end(), translucent.model_ranges.begin(),
                                  translucent.model_ranges.end());
  background_X_GHead_ = X_GHead;
  background_valid_ = true;
  cost_.background_redrawn = true;
  ++background_redraws_;
}

void StereoRenderer::draw_moving(std::span<const Instance> moving) {
  const int64_t start_ns = now_ns();
  pack_layer(moving, moving_);
  cost_.moving_triangles = triangles_in(moving_);
  draw_layer(moving_, false);
  cost_.moving_ns = now_ns() - start_ns;
}

void StereoRenderer::pack_layer(std::span<const Instance> instances, Layer& layer) {
  layer.opaque_scratch.clear();
  layer.translucent_scratch.clear();
  for (const Instance& instance : instances)
    (instance.rgba[3] < 1.0f ? layer.translucent_scratch : layer.opaque_scratch).push_back(instance);
  pack_instances(layer.opaque_scratch, layer.opaque);
  pack_instances(layer.translucent_scratch, layer.translucent);
}

uint64_t StereoRenderer::triangles_in(const Layer& layer) const {
  uint64_t triangles = 0;
  for (const PackedInstances* packed : {&layer.opaque, &layer.translucent}) {
    for (const UnitMesh mesh : kMeshes) {
      triangles += static_cast<uint64_t>(packed->range(mesh).count) *
                   static_cast<uint64_t>(unit_mesh_triangles_[static_cast<std::size_t>(mesh)]);
    }
    for (std::size_t k = 0; k < packed->model_meshes.size(); ++k) {
      triangles += static_cast<uint64_t>(packed->model_ranges[k].count) *
                   (packed->model_meshes[k]->indices.size() / 3);
    }
  }
  return triangles;
}

void StereoRenderer::draw_layer(Layer& layer, bool with_outside) {
  // (both uploaded every time: an upload also lets go of the copies of models that are gone)
  layer.opaque_meshes->upload(layer.opaque);
  layer.translucent_meshes->upload(layer.translucent);
  program_->use();
  for (const Eye eye : {Eye::kLeft, Eye::kRight}) {
    set_eye(eye, X_GHead_);
    draw_packed(*layer.opaque_meshes, layer.opaque);
  }
  // the outside view after the opaque cockpit, at the far plane: only the pixels nothing
  // covers are shaded (the depth test rejects the rest first), then the glazing over it
  if (with_outside && outside_program_) {
    draw_outside(X_GHead_);
    program_->use();
  }
  if (layer.translucent.records.empty()) return;
  glEnable(GL_BLEND);
  glDepthMask(GL_FALSE);
  for (const Eye eye : {Eye::kLeft, Eye::kRight}) {
    set_eye(eye, X_GHead_);
    draw_packed(*layer.translucent_meshes, layer.translucent);
  }
  glDepthMask(GL_TRUE);
  glDisable(GL_BLEND);
}

void StereoRenderer::draw_outside(const Eigen::Isometry3d& X_GHead) {
  if (!outside_program_) return;
  for (const Eye eye : {Eye::kLeft, Eye::kRight}) {
    const int i = eye_index(eye);
    const Eigen::Isometry3d X_GE = eye_pose(config_, eye, X_GHead);
    const Eigen::Matrix4f clip_from_G = projection_[i] * view_matrix(X_GE);
    glViewport(i * config_.width_px, 0, config_.width_px, config_.height_px);
    outside_program_->draw(*config_.outside, clip_from_G.inverse(), X_GE.translation().cast<float>(),
                           Eigen::Vector4i(i * config_.width_px, 0, config_.width_px, config_.height_px));
    ++last_draw_calls_;
  }
}

void StereoRenderer::end_frame() {
  const int64_t start_ns = now_ns();
  // llvmpipe renders lazily: reading the pixels flushes, then copies them (top row first, as
  // drawn upside down)
  // into a buffer nobody else holds (a frame kept by the video encoder stays whole)
  glReadPixels(0, 0, 2 * config_.width_px, config_.height_px, GL_RGBA, GL_UNSIGNED_BYTE,
               frames_.next().data());
  while (glGetError() != GL_NO_ERROR)
    ++gl_error_count_;
  cost_.finish_ns = now_ns() - start_ns;
}

void StereoRenderer::set_eye(Eye eye, const Eigen::Isometry3d& X_GHead) {
  const int i = eye_index(eye);
  glViewport(i * config_.width_px, 0, config_.width_px, config_.height_px);
  const Eigen::Isometry3d X_GE = eye_pose(config_, eye, X_GHead);
  program_->set_view_projection(projection_[i] * view_matrix(X_GE));
  program_->set_eye_position(X_GE.translation().cast<float>());
}

void StereoRenderer::draw_packed(const MeshBuffers& meshes, const PackedInstances& packed) {
  for (const UnitMesh mesh : kMeshes) {
    const MeshRange& range = packed.range(mesh);
    meshes.draw(mesh, range);
    if (range.count > 0) ++last_draw_calls_;
  }
  // a model's surfaces may be open or one-sided (a panel's face): both sides drawn
  if (!packed.model_meshes.empty()) glDisable(GL_CULL_FACE);
  for (std::size_t k = 0; k < packed.model_meshes.size(); ++k) {
    meshes.draw(packed.model_meshes[k], packed.model_ranges[k]);
    ++last_draw_calls_;
  }
  if (!packed.model_meshes.empty()) glEnable(GL_CULL_FACE);
}

const uint8_t* StereoRenderer::pixels() const { return frames_.current().data(); }

std::string StereoRenderer::gl_renderer() const {
  return context_->renderer();
}

std::string StereoRenderer::gl_version() const {
  return context_->version();
}

}  // namespace vcockpit::render
