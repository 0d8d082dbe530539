#pragma once
// Renders a list of instances for both eyes into one side-by-side RGBA8 image (left eye in the
// left half, top-down rows) with OSMesa. Constant config in, one call per frame, no allocation
// and no throw after the first frames: instance buffers are reused and grow only with the
// instance count, and each unit mesh is one instanced draw call per eye.
//
// The OSMesa context is bound to the thread that calls the constructor and render(); a renderer
// used from another thread rebinds it there (one thread at a time).

#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "image_generator/render/hmd_config.hpp"
#include "image_generator/render/instance.hpp"
#include "image_generator/render/instance_packing.hpp"

namespace vcockpit::render {

class GlContext;
class LitProgram;
class MeshBuffers;

// A dim cockpit interior: what shows where nothing is drawn (linear RGB 0..1).
constexpr std::array<float, 3> kBackgroundRgb{0.11f, 0.12f, 0.14f};

class StereoRenderer {
 public:
  // Validates the config (std::invalid_argument), then creates the context, shaders and meshes
  // (RenderError on any OSMesa or GL failure).
  explicit StereoRenderer(const HmdConfig& config);
  ~StereoRenderer();
  StereoRenderer(const StereoRenderer&) = delete;
  StereoRenderer& operator=(const StereoRenderer&) = delete;

  void render(const std::vector<Instance>& instances, const Eigen::Isometry3d& X_GHead);

  // The last frame: 2 * width_px() by height_px(), RGBA8, row 0 at the top. Valid until the
  // next render() or the renderer's destruction.
  const uint8_t* pixels() const;
  int width_px() const { return config_.width_px; }  // per eye
  int height_px() const { return config_.height_px; }
  const HmdConfig& config() const { return config_; }

  std::string gl_renderer() const;  // e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
  std::string gl_version() const;   // e.g. "4.5 (Core Profile) Mesa 22.3.6"
  // GL errors seen after frames (counted, not thrown: the frame loop never throws).
  uint64_t gl_error_count() const { return gl_error_count_; }
  // Draw calls issued by the last render() (at most 3 per eye).
  int last_draw_calls() const { return last_draw_calls_; }

 private:
  void draw_eye(Eye eye, const Eigen::Isometry3d& X_GHead);

  HmdConfig config_;
  std::array<Eigen::Matrix4f, 2> projection_;  // per eye, constant
  std::unique_ptr<GlContext> context_;         // declared first: destroyed last
  std::unique_ptr<LitProgram> program_;
  std::unique_ptr<MeshBuffers> meshes_;
  PackedInstances packed_;
  uint64_t gl_error_count_ = 0;
  int last_draw_calls_ = 0;
};

}  // namespace vcockpit::render
