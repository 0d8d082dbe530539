#include "image_generator/render/gl_context.hpp"

#include <GL/osmesa.h>

#include <string>

#include "image_generator/render/render_error.hpp"

namespace vcockpit::render {
namespace {

std::string gl_string(GLenum name) {
  const auto* text = reinterpret_cast<const char*>(glGetString(name));
  return text ? text : "";
}

size_t buffer_bytes(int width_px, int height_px) {
  if (width_px <= 0 || height_px <= 0) {
    throw RenderError("OSMesa: bad buffer size " + std::to_string(width_px) + "x" +
                      std::to_string(height_px));
  }
  return static_cast<size_t>(width_px) * static_cast<size_t>(height_px) * 4;
}

}  // namespace

GlContext::GlContext(int width_px, int height_px)
    : width_px_(width_px), height_px_(height_px), buffer_(buffer_bytes(width_px, height_px), 0) {
  // 4.6 is refused by Mesa 22.3; 4.5 core is what llvmpipe offers
  // clang-format off
  const int attribs[] = {OSMESA_FORMAT, OSMESA_RGBA,
                         OSMESA_DEPTH_BITS, 24,
                         OSMESA_STENCIL_BITS, 0,
                         OSMESA_ACCUM_BITS, 0,
                         OSMESA_PROFILE, OSMESA_CORE_PROFILE,
                         OSMESA_CONTEXT_MAJOR_VERSION, 4,
                         OSMESA_CONTEXT_MINOR_VERSION, 5,
                         0};
  // clang-format on
  context_ = OSMesaCreateContextAttribs(attribs, nullptr);
  if (!context_) throw RenderError("OSMesa: could not create a 4.5 core-profile context");
  if (!OSMesaMakeCurrent(context_, buffer_.data(), GL_UNSIGNED_BYTE, width_px, height_px)) {
    OSMesaDestroyContext(context_);
    throw RenderError("OSMesa: could not bind a " + std::to_string(width_px) + "x" +
                      std::to_string(height_px) + " RGBA buffer");
  }
  OSMesaPixelStore(OSMESA_Y_UP, 0);  // row 0 at the top
  renderer_ = gl_string(GL_RENDERER);
  version_ = gl_string(GL_VERSION);
  if (version_.rfind("4.5", 0) != 0 && version_.rfind("4.6", 0) != 0) {
    OSMesaMakeCurrent(nullptr, nullptr, 0, 0, 0);
    OSMesaDestroyContext(context_);
    throw RenderError("OSMesa: wanted OpenGL 4.5 core, got '" + version_ + "'");
  }
}

GlContext::~GlContext() {
  // unbind first so the thread never holds a dangling current context
  if (OSMesaGetCurrentContext() == context_) OSMesaMakeCurrent(nullptr, nullptr, 0, 0, 0);
  OSMesaDestroyContext(context_);
}

void GlContext::make_current() {
  if (OSMesaGetCurrentContext() == context_) return;
  OSMesaMakeCurrent(context_, buffer_.data(), GL_UNSIGNED_BYTE, width_px_, height_px_);
  OSMesaPixelStore(OSMESA_Y_UP, 0);
}

}  // namespace vcockpit::render
