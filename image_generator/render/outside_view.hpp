#pragma once
// What the pilot sees beyond the cockpit's glazing: a sky that pales to a haze at the horizon,
// and flat ground below, a patchwork of fields fading into the haze with distance. Drawn per
// pixel from the eye's ray (a full-screen triangle at the far plane, no geometry), so the
// horizon is at any distance. It is drawn after the opaque cockpit, where the depth is still
// the cleared far plane: only the pixels nothing covers are shaded. Glazing drawn translucent
// after it lets it show through.

#include <Eigen/Core>

#include "image_generator/render/gl.hpp"
#include "image_generator/render/hmd_config.hpp"

namespace vcockpit::render {

class OutsideViewProgram {
 public:
  // Compiles and links (RenderError on failure); needs a current context.
  OutsideViewProgram();
  ~OutsideViewProgram();
  OutsideViewProgram(const OutsideViewProgram&) = delete;
  OutsideViewProgram& operator=(const OutsideViewProgram&) = delete;

  // Fills the current viewport's pixels whose depth is the cleared 1 (nothing drawn there) with
  // the view from p_GE through the inverse of its view-projection (clip -> G), writing no
  // depth. Leaves the depth test GL_LESS, as the renderer draws.
  void draw(const OutsideView& view, const Eigen::Matrix4f& G_from_clip, const Eigen::Vector3f& p_GE,
            const Eigen::Vector4i& viewport_px) const;

 private:
  GLuint program_ = 0;
  GLuint empty_vertex_array_ = 0;  // a core context draws only with one bound
  GLint G_from_clip_ = -1;
  GLint eye_position_G_ = -1;
  GLint viewport_ = -1;
  GLint ground_z_ = -1;
};

}  // namespace vcockpit::render
