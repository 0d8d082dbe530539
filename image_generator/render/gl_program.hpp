#pragma once
// Building a GL shader program from its two stages' sources, and finding its uniforms: what the
// renderer's programs (the lit instances, the outside view) share. Needs a current context.

#include "image_generator/render/gl.hpp"

namespace vcockpit::render {

// Compiles both stages and links them; throws RenderError with the compiler's or linker's log.
GLuint build_program(const char* vertex_source, const char* fragment_source);
// The uniform's location; throws RenderError (and deletes the program) if it has none.
GLint uniform_location(GLuint program, const char* name);

}  // namespace vcockpit::render
