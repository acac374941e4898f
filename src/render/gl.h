// The GL header of the render layer (glad, generated at build time for OpenGL 3.3 core), and error checks.
#pragma once

#include <glad/gl.h>

namespace render {
// Throws core::RuntimeFault naming `where` if GL reports an error.
void check_gl(const char* where);
}  // namespace render
