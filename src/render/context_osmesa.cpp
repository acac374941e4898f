// The only file that includes GL/osmesa.h (see context.h).
#include <GL/osmesa.h>

#include <vector>

#include "core/error.h"
#include "render/context.h"

namespace render {

struct OffscreenContext::Impl {
  OSMesaContext ctx = nullptr;
  // OSMesaMakeCurrent needs a buffer; we draw into framebuffer objects, so a small one will do.
  std::vector<unsigned char> buffer = std::vector<unsigned char>(16 * 16 * 4);
};

namespace {
void* osmesa_proc(const char* name) {
  return reinterpret_cast<void*>(OSMesaGetProcAddress(name));
}
}  // namespace

OffscreenContext::OffscreenContext() : impl_(std::make_unique<Impl>()) {
  const int attribs[] = {OSMESA_FORMAT,
                         OSMESA_RGBA,
                         OSMESA_DEPTH_BITS,
                         0,
                         OSMESA_STENCIL_BITS,
                         0,
                         OSMESA_PROFILE,
                         OSMESA_CORE_PROFILE,
                         OSMESA_CONTEXT_MAJOR_VERSION,
                         3,
                         OSMESA_CONTEXT_MINOR_VERSION,
                         3,
                         0};
  impl_->ctx = OSMesaCreateContextAttribs(attribs, nullptr);
  if (!impl_->ctx) throw core::RuntimeFault("OSMesa: cannot create an OpenGL 3.3 core context");
  if (!OSMesaMakeCurrent(impl_->ctx, impl_->buffer.data(), GL_UNSIGNED_BYTE, 16, 16)) {
    OSMesaDestroyContext(impl_->ctx);
    throw core::RuntimeFault("OSMesa: cannot make the context current");
  }
  description_ = load_gl(&osmesa_proc);
}

OffscreenContext::~OffscreenContext() {
  if (impl_->ctx) OSMesaDestroyContext(impl_->ctx);
}

}  // namespace render
