#include "image_generator/render/shaders.hpp"

#include <string>

#include "image_generator/render/gl_program.hpp"

namespace vcockpit::render {
namespace {

constexpr const char* kVertexSource = R"glsl(#version 450 core
layout(location = 0) in vec3 a_position_O;
layout(location = 1) in vec3 a_normal_O;
layout(location = 2) in mat4 a_X_GO;
layout(location = 6) in vec4 a_scale_highlight;
layout(location = 7) in vec4 a_rgba;
layout(location = 8) in vec3 a_vertex_rgb;
layout(location = 9) in vec2 a_st;

uniform mat4 u_view_projection;

out vec3 v_position_G;
out vec3 v_normal_G;
out vec3 v_rgb;
out vec2 v_st;
out float v_highlight;
out float v_alpha;

void main() {
  vec3 scale = max(a_scale_highlight.xyz, vec3(1e-6));
  vec4 p_G = a_X_GO * vec4(a_position_O * scale, 1.0);
  // inverse transpose of R * S is R * S^-1: normals stay normal under non-uniform scale
  v_normal_G = mat3(a_X_GO) * (a_normal_O / scale);
  v_position_G = p_G.xyz;
  v_rgb = a_rgba.rgb * a_vertex_rgb;
  v_st = a_st;
  v_highlight = a_scale_highlight.w;
  v_alpha = a_rgba.a;
  gl_Position = u_view_projection * p_G;
}
)glsl";

constexpr const char* kFragmentSource = R"glsl(#version 450 core
in vec3 v_position_G;
in vec3 v_normal_G;
in vec3 v_rgb;
in vec2 v_st;
in float v_highlight;
in float v_alpha;

uniform vec3 u_eye_position_G;
uniform sampler2D u_base_texture;

out vec4 frag_rgba;

// towards the key light: mostly overhead, somewhat from the pilot's side and left
const vec3 kToLight_G = normalize(vec3(-0.5, 0.3, 1.0));
const float kAmbient = 0.35;
const float kKey = 0.75;
const float kSpecular = 0.2;
const float kShininess = 32.0;

void main() {
  // a back face (a model's one-sided surface seen from behind) lit as its front
  vec3 n = gl_FrontFacing ? normalize(v_normal_G) : -normalize(v_normal_G);
  vec3 base = v_rgb * texture(u_base_texture, v_st).rgb;
  vec3 to_eye = normalize(u_eye_position_G - v_position_G);
  float lambert = max(dot(n, kToLight_G), 0.0);
  float blinn = lambert > 0.0 ? pow(max(dot(n, normalize(kToLight_G + to_eye)), 0.0), kShininess)
                              : 0.0;
  vec3 rgb = base * (kAmbient + kKey * lambert) + vec3(kSpecular * blinn);
  // highlighted: brighter and self-lit, so it reads even in shadow
  rgb = mix(rgb, rgb * 1.3 + base * 0.4 + vec3(0.08), v_highlight);
  frag_rgba = vec4(clamp(rgb, 0.0, 1.0), v_alpha);  // (blended only in the translucent pass)
}
)glsl";

}  // namespace

LitProgram::LitProgram() {
  program_ = build_program(kVertexSource, kFragmentSource);
  view_projection_ = uniform_location(program_, "u_view_projection");
  eye_position_G_ = uniform_location(program_, "u_eye_position_G");
  const GLint base_texture = uniform_location(program_, "u_base_texture");
  glUseProgram(program_);
  glUniform1i(base_texture, 0);  // texture unit 0 (MeshBuffers binds there)
  glUseProgram(0);
}

LitProgram::~LitProgram() {
  glDeleteProgram(program_);
}

void LitProgram::use() const {
  glUseProgram(program_);
}

void LitProgram::set_view_projection(const Eigen::Matrix4f& P_V) const {
  glUniformMatrix4fv(view_projection_, 1, GL_FALSE, P_V.data());  // column-major, as Eigen
}

void LitProgram::set_eye_position(const Eigen::Vector3f& p_GE) const {
  glUniform3fv(eye_position_G_, 1, p_GE.data());
}

}  // namespace vcockpit::render
