#include "image_generator/render/outside_view.hpp"

#include "image_generator/render/gl_program.hpp"

namespace vcockpit::render {
namespace {

// one triangle that covers the viewport, clip (-1,-1), (3,-1), (-1,3), at the far plane (depth
// 1, the cleared depth): drawn after the opaque cockpit, it shades only what nothing covers
constexpr const char* kVertexSource = R"glsl(#version 450 core
void main() {
  vec2 corner = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);
  gl_Position = vec4(corner * 2.0 - 1.0, 1.0, 1.0);
}
)glsl";

// The eye's ray through the pixel, from the inverse view-projection. Above the horizon the sky,
// from haze at the horizon to a deeper blue overhead; below it the ground plane where the ray
// meets it: fields of a few greens and browns 150 m across (a hash of the field's index), fading
// to their mean colour as they shrink to a pixel and to the haze with distance (aerial
// perspective), so the horizon is one soft line at any height.
constexpr const char* kFragmentSource = R"glsl(#version 450 core
uniform mat4 u_G_from_clip;
uniform vec3 u_eye_position_G;
uniform vec4 u_viewport;
uniform float u_ground_z;
out vec4 frag_rgba;

const vec3 kZenith = vec3(0.22, 0.42, 0.78);
const vec3 kHaze = vec3(0.72, 0.79, 0.86);
const vec3 kFields[4] = vec3[](vec3(0.30, 0.42, 0.18), vec3(0.40, 0.48, 0.22),
                               vec3(0.46, 0.40, 0.26), vec3(0.24, 0.36, 0.16));
const vec3 kFieldMean = vec3(0.35, 0.415, 0.205);
const float kFieldSize_m = 150.0;
const float kHazeDistance_m = 9000.0;

float hash(vec2 cell) {
  return fract(sin(dot(cell, vec2(127.1, 311.7))) * 43758.5453);
}

void main() {
  vec2 ndc = (gl_FragCoord.xy - u_viewport.xy) / u_viewport.zw * 2.0 - 1.0;
  vec4 far_G = u_G_from_clip * vec4(ndc, 1.0, 1.0);
  vec3 ray = normalize(far_G.xyz / far_G.w - u_eye_position_G);
  vec3 rgb;
  // (the ground point for every pixel, so that its derivatives are defined everywhere)
  float distance_m = (u_eye_position_G.z - u_ground_z) / max(-ray.z, 1e-4);
  vec2 p = u_eye_position_G.xy + ray.xy * distance_m;
  // a field seen smaller than a few pixels: its mean (no shimmer at the horizon)
  float pixels_per_field = kFieldSize_m / max(length(fwidth(p)), 1e-6);
  if (ray.z >= 0.0) {
    rgb = mix(kHaze, kZenith, pow(ray.z, 0.45));
  } else {
    vec3 field = kFields[int(hash(floor(p / kFieldSize_m)) * 3.999)];
    field = mix(kFieldMean, field, smoothstep(3.0, 12.0, pixels_per_field));
    rgb = mix(field, kHaze, 1.0 - exp(-distance_m / kHazeDistance_m));
  }
  frag_rgba = vec4(rgb, 1.0);
}
)glsl";

}  // namespace

OutsideViewProgram::OutsideViewProgram() {
  program_ = build_program(kVertexSource, kFragmentSource);
  G_from_clip_ = uniform_location(program_, "u_G_from_clip");
  eye_position_G_ = uniform_location(program_, "u_eye_position_G");
  viewport_ = uniform_location(program_, "u_viewport");
  ground_z_ = uniform_location(program_, "u_ground_z");
  glGenVertexArrays(1, &empty_vertex_array_);
}

OutsideViewProgram::~OutsideViewProgram() {
  glDeleteVertexArrays(1, &empty_vertex_array_);
  glDeleteProgram(program_);
}

void OutsideViewProgram::draw(const OutsideView& view, const Eigen::Matrix4f& G_from_clip,
                              const Eigen::Vector3f& p_GE, const Eigen::Vector4i& viewport_px) const {
  glUseProgram(program_);
  glUniformMatrix4fv(G_from_clip_, 1, GL_FALSE, G_from_clip.data());
  glUniform3fv(eye_position_G_, 1, p_GE.data());
  const Eigen::Vector4f viewport = viewport_px.cast<float>();
  glUniform4fv(viewport_, 1, viewport.data());
  glUniform1f(ground_z_, static_cast<float>(-view.ground_depth_m));
  // where the depth is still the cleared 1: nothing drawn there (the renderer's depth test is
  // GL_LESS, which would reject the far plane itself)
  glDepthFunc(GL_LEQUAL);
  glDepthMask(GL_FALSE);
  glDisable(GL_CULL_FACE);  // (the renderer's front faces wind clockwise; this one does not)
  glBindVertexArray(empty_vertex_array_);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
  glEnable(GL_CULL_FACE);
  glDepthMask(GL_TRUE);
  glDepthFunc(GL_LESS);
}

}  // namespace vcockpit::render
