#include "render/gl.h"

#include <string>

#include "core/error.h"
#include "render/context.h"

namespace render {

void check_gl(const char* where) {
  GLenum err = glGetError();
  if (err == GL_NO_ERROR) return;
  char code[16];
  std::snprintf(code, sizeof code, "0x%04x", err);
  throw core::RuntimeFault(std::string("OpenGL error ") + code + " in " + where);
}

std::string load_gl(ProcLoader loader) {
  int version = gladLoadGL(reinterpret_cast<GLADloadfunc>(loader));
  if (version == 0) throw core::RuntimeFault("cannot load OpenGL entry points");
  if (GLAD_VERSION_MAJOR(version) * 10 + GLAD_VERSION_MINOR(version) < 33)
    throw core::RuntimeFault("OpenGL 3.3 core is required, the context offers " +
                             std::to_string(GLAD_VERSION_MAJOR(version)) + "." +
                             std::to_string(GLAD_VERSION_MINOR(version)));
  const char* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  const char* ver = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  return std::string(renderer ? renderer : "?") + ", " + (ver ? ver : "?");
}

}  // namespace render
