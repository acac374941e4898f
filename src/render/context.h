// An off-screen OpenGL 3.3 core context, current on the creating thread. The only implementation today is
// OSMesa (llvmpipe, no GPU, no display); it lives in context_osmesa.cpp, the only file that includes
// GL/osmesa.h, so an EGL surfaceless context can replace it without touching the renderer.
#pragma once

#include <memory>
#include <string>

namespace render {

using ProcLoader = void* (*)(const char* name);

class OffscreenContext {
 public:
  // Creates the context, makes it current and loads the GL entry points. Throws core::RuntimeFault.
  OffscreenContext();
  ~OffscreenContext();
  OffscreenContext(const OffscreenContext&) = delete;
  OffscreenContext& operator=(const OffscreenContext&) = delete;
  // GL_RENDERER and GL_VERSION, e.g. "llvmpipe (LLVM 15.0.6, 256 bits), 4.5 (Core Profile) Mesa 22.3.6".
  const std::string& description() const { return description_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::string description_;
};

// Loads GL entry points through `loader` (any window system's GetProcAddress) and returns GL_RENDERER and
// GL_VERSION. Throws core::RuntimeFault if the context is not 3.3 core or better.
std::string load_gl(ProcLoader loader);

}  // namespace render
