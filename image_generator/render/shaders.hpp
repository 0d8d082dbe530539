#pragma once
// The one shader program: instanced, lit primitives. Per vertex: unit-mesh position and normal,
// colour and texture coordinate (a model's; the base colour texture on unit 0 multiplies the
// colour, a white texel for what has none). Per instance: pose X_GO, scale, highlight flag and
// colour. Lighting is in the world frame G:
// a key light from above, in front of the objects the pilot faces, plus ambient, Lambert with a
// little Blinn-Phong specular; highlighted instances glow.

#include <Eigen/Core>

#include "image_generator/render/gl.hpp"

namespace vcockpit::render {

// Vertex attribute locations shared by the shaders and the vertex arrays.
namespace attrib {
constexpr GLuint kPosition = 0;
constexpr GLuint kNormal = 1;
constexpr GLuint kX_GO = 2;  // mat4: locations 2..5, one column each
constexpr GLuint kScaleHighlight = 6;
constexpr GLuint kRgba = 7;
constexpr GLuint kVertexRgb = 8;  // per vertex: a model part's colour (white for the primitives)
constexpr GLuint kVertexSt = 9;   // per vertex: where a model part samples its texture
}  // namespace attrib

class LitProgram {
 public:
  // Compiles and links; throws RenderError with the compiler's log on failure.
  LitProgram();
  ~LitProgram();
  LitProgram(const LitProgram&) = delete;
  LitProgram& operator=(const LitProgram&) = delete;

  void use() const;
  void set_view_projection(const Eigen::Matrix4f& P_V) const;
  void set_eye_position(const Eigen::Vector3f& p_GE) const;

 private:
  GLuint program_ = 0;
  GLint view_projection_ = -1;
  GLint eye_position_G_ = -1;
};

}  // namespace vcockpit::render
