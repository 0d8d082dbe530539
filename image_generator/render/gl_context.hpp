#pragma once
// An OSMesa OpenGL 4.5 core-profile context rendering straight into its own RGBA8 buffer
// (top-down rows, PNG order), with a 24-bit depth buffer. The buffer is the default framebuffer.

#include <cstdint>
#include <string>
#include <vector>

struct osmesa_context;  // OSMesaContext, kept out of this header (osmesa.h pulls in GL/gl.h)

namespace vcockpit::render {

class GlContext {
 public:
  // Creates the context and makes it current on this thread; throws RenderError on failure.
  GlContext(int width_px, int height_px);
  ~GlContext();
  GlContext(const GlContext&) = delete;
  GlContext& operator=(const GlContext&) = delete;

  // Binds the context to the calling thread unless it already is.
  void make_current();

  const uint8_t* pixels() const { return buffer_.data(); }
  int width_px() const { return width_px_; }
  int height_px() const { return height_px_; }
  const std::string& renderer() const { return renderer_; }  // GL_RENDERER
  const std::string& version() const { return version_; }    // GL_VERSION

 private:
  int width_px_;
  int height_px_;
  std::vector<uint8_t> buffer_;
  osmesa_context* context_ = nullptr;
  std::string renderer_;
  std::string version_;
};

}  // namespace vcockpit::render
