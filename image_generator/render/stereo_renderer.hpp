#pragma once
// Renders a list of instances for both eyes into one side-by-side RGBA8 image (left eye in the
// left half, top-down rows) with OSMesa. Constant config in, one call per frame, no allocation
// and no throw after the first frames: instance buffers are reused and grow only with the
// instance count, and each unit mesh is one instanced draw call per eye.
//
// Two layers, as VR compositors do: the fixed instances (Instance::fixed: the cockpit's shell,
// most of the pixels) are drawn into an offscreen colour and depth image (both eyes) only when
// they or the head pose change; every frame starts from a copy of it and draws only the moving
// instances on top. The result equals a full redraw (the same depth test, the same shading).
// A frame can also be made in three calls, so the moving instances are taken as late as
// possible: begin_frame() restores the background, draw_moving() draws what moves (built from
// the newest state just before), end_frame() waits for the pixels (llvmpipe rasterises lazily,
// at the flush, so the moving data is used within a few ms of being taken).
//
// The OSMesa context is bound to the thread that calls the constructor and render(); a renderer
// used from another thread rebinds it there (one thread at a time).

#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <memory>

#include "image_generator/render/frame_buffer_pool.hpp"
#include <span>
#include <string>
#include <vector>

#include "image_generator/render/hmd_config.hpp"
#include "image_generator/render/instance.hpp"
#include "image_generator/render/instance_packing.hpp"

namespace vcockpit::render {

class GlContext;
class LitProgram;
class MeshBuffers;
class OutsideViewProgram;

// A dim cockpit interior: what shows where nothing is drawn, without an outside view (linear
// RGB 0..1).
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

  // The frame in three steps (render() is the three). `fixed` are the fixed instances (their
  // `fixed` flag is not looked at); the background is redrawn if they or the head differ from
  // the last frame's, or when the cache is off.
  void begin_frame(std::span<const Instance> fixed, const Eigen::Isometry3d& X_GHead);
  void draw_moving(std::span<const Instance> moving);
  void end_frame();

  // Off: every frame draws everything (the fixed layer too), for comparison.
  void set_background_cache(bool on) { cache_on_ = on; }
  bool background_cache() const { return cache_on_; }

  // What the last frame cost, by part (ns of wall time): restoring (or redrawing) the background,
  // submitting the moving instances, and waiting for the rasteriser at the end.
  struct FrameCost {
    int64_t background_ns = 0;
    int64_t moving_ns = 0;
    int64_t finish_ns = 0;
    bool background_redrawn = false;
    // the scene's triangles for one eye: the fixed layer's (the cockpit, whether redrawn or
    // restored) and the moving layer's
    uint64_t fixed_triangles = 0;
    uint64_t moving_triangles = 0;
  };
  const FrameCost& last_cost() const { return cost_; }
  uint64_t background_redraws() const { return background_redraws_; }

  // The last frame: 2 * width_px() by height_px(), RGBA8, row 0 at the top. Valid until the
  // next render() or the renderer's destruction.
  const uint8_t* pixels() const;
  // The same frame as a buffer a consumer may keep (a video encoder's queue): the renderer reads
  // later frames into other buffers while one is held (a small pool, grown only when every
  // buffer is held).
  std::shared_ptr<const std::vector<uint8_t>> shared_pixels() { return frames_.share_current(); }
  int width_px() const { return config_.width_px; }  // per eye
  int height_px() const { return config_.height_px; }
  const HmdConfig& config() const { return config_; }

  std::string gl_renderer() const;  // e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
  std::string gl_version() const;   // e.g. "4.5 (Core Profile) Mesa 22.3.6"
  // GL errors seen after frames (counted, not thrown: the frame loop never throws).
  uint64_t gl_error_count() const { return gl_error_count_; }
  // Draw calls issued by the last render(): per eye, one per unit mesh and model mesh drawn,
  // in each layer's opaque and translucent part, and one for the outside view.
  int last_draw_calls() const { return last_draw_calls_; }

 private:
  // One layer's instances, packed in two parts: the opaque, then the translucent (rgba alpha
  // below 1: glazing), blended over them without writing depth. Translucent instances are not
  // sorted among themselves: panes that do not overlap from the eye (a cockpit's windows) need
  // no order. The fixed layer's glazing is in the cached background, so a moving instance
  // behind it is drawn over it, untinted (nothing moves outside a cockpit's windows); a full
  // redraw draws in the same order.
  struct Layer {
    PackedInstances opaque, translucent;
    std::unique_ptr<MeshBuffers> opaque_meshes, translucent_meshes;
    std::vector<Instance> opaque_scratch, translucent_scratch;  // (kept for their capacity)
  };
  void pack_layer(std::span<const Instance> instances, Layer& layer);
  uint64_t triangles_in(const Layer& layer) const;
  // with_outside: the outside view between the opaque and the translucent part (the fixed
  // layer's)
  void draw_layer(Layer& layer, bool with_outside);
  // the viewport and the programs' view for one eye
  void set_eye(Eye eye, const Eigen::Isometry3d& X_GHead);
  void draw_packed(const MeshBuffers& meshes, const PackedInstances& packed);
  void draw_outside(const Eigen::Isometry3d& X_GHead);  // both eyes
  void redraw_background(const Eigen::Isometry3d& X_GHead);
  bool background_changed(const Eigen::Isometry3d& X_GHead) const;

  HmdConfig config_;
  std::array<Eigen::Matrix4f, 2> projection_;  // per eye, constant
  std::unique_ptr<GlContext> context_;         // declared first: destroyed last
  std::unique_ptr<LitProgram> program_;
  std::unique_ptr<OutsideViewProgram> outside_program_;  // with config_.outside only
  std::array<int, kUnitMeshCount> unit_mesh_triangles_{};
  Layer moving_;
  Layer background_;
  std::vector<Instance> split_;  // render(): the moving instances
  std::vector<Instance> split_fixed_;
  FrameBufferPool frames_;  // read-back buffers
  unsigned frame_framebuffer_ = 0;  // the frame being drawn: colour and depth of both eyes
  unsigned frame_colour_ = 0;
  unsigned frame_depth_ = 0;
  // the cached background: colour and depth of both eyes, and what it shows
  unsigned background_framebuffer_ = 0;
  unsigned background_colour_ = 0;
  unsigned background_depth_ = 0;
  bool background_valid_ = false;
  std::vector<InstanceRecord> background_records_;  // opaque, then translucent
  std::vector<const MeshData*> background_model_meshes_;
  std::size_t background_translucent_count_ = 0;
  // (and which unit mesh or model each of those records drew: a box turned rounded box with the
  // same pose and size has the same record)
  std::array<MeshRange, kUnitMeshCount> background_opaque_ranges_{}, background_translucent_ranges_{};
  std::vector<MeshRange> background_model_ranges_;
  Eigen::Isometry3d background_X_GHead_ = Eigen::Isometry3d::Identity();
  bool cache_on_ = true;
  Eigen::Isometry3d X_GHead_ = Eigen::Isometry3d::Identity();  // this frame's
  FrameCost cost_;
  int64_t frame_start_ns_ = 0;
  uint64_t background_redraws_ = 0;
  uint64_t gl_error_count_ = 0;
  int last_draw_calls_ = 0;
};

}  // namespace vcockpit::render
