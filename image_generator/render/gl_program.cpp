#include "image_generator/render/gl_program.hpp"

#include <string>

#include "image_generator/render/render_error.hpp"

namespace vcockpit::render {
namespace {

GLuint compile(GLenum stage, const char* source, const char* name) {
  const GLuint shader = glCreateShader(stage);
  glShaderSource(shader, 1, &source, nullptr);
  glCompileShader(shader);
  GLint ok = GL_FALSE;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (ok == GL_TRUE) return shader;
  GLint length = 0;
  glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
  std::string log(static_cast<size_t>(length > 0 ? length : 1), '\0');
  glGetShaderInfoLog(shader, length, nullptr, log.data());
  glDeleteShader(shader);
  throw RenderError(std::string("GL: ") + name + " shader does not compile: " + log.c_str());
}

GLuint link(GLuint vertex, GLuint fragment) {
  const GLuint program = glCreateProgram();
  glAttachShader(program, vertex);
  glAttachShader(program, fragment);
  glLinkProgram(program);
  glDeleteShader(vertex);  // flagged; freed with the program
  glDeleteShader(fragment);
  GLint ok = GL_FALSE;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (ok == GL_TRUE) return program;
  GLint length = 0;
  glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
  std::string log(static_cast<size_t>(length > 0 ? length : 1), '\0');
  glGetProgramInfoLog(program, length, nullptr, log.data());
  glDeleteProgram(program);
  throw RenderError(std::string("GL: shader program does not link: ") + log.c_str());
}

}  // namespace

GLuint build_program(const char* vertex_source, const char* fragment_source) {
  const GLuint vertex = compile(GL_VERTEX_SHADER, vertex_source, "vertex");
  GLuint fragment = 0;
  try {
    fragment = compile(GL_FRAGMENT_SHADER, fragment_source, "fragment");
  } catch (...) {
    glDeleteShader(vertex);
    throw;
  }
  return link(vertex, fragment);
}

GLint uniform_location(GLuint program, const char* name) {
  const GLint location = glGetUniformLocation(program, name);
  if (location < 0) {
    glDeleteProgram(program);
    throw RenderError(std::string("GL: shader program has no uniform ") + name);
  }
  return location;
}

}  // namespace vcockpit::render
