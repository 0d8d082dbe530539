#pragma once
// OpenGL 4.5 core declarations. libOSMesa exports every gl* entry point, so the prototypes are
// linked directly (no loader). Include this, never GL/gl.h, outside gl_context.cpp.

#ifndef GL_GLEXT_PROTOTYPES
#define GL_GLEXT_PROTOTYPES 1
#endif
#include <GL/glcorearb.h>
