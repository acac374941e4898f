#include "render/target.h"

#include <algorithm>
#include <cstring>
#include <string>

#include "core/error.h"
#include "render/gl.h"

namespace render {

Target::Target(int width, int height) : w_(width), h_(height) {
  GLint max_size = 0;
  glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &max_size);
  if (w_ <= 0 || h_ <= 0 || w_ > max_size || h_ > max_size)
    throw core::InputError("image size " + std::to_string(w_) + "x" + std::to_string(h_) +
                           " is not allowed; each side must be from 1 to " + std::to_string(max_size) +
                           " pixels");
  glGenFramebuffers(1, &fbo_);
  glGenRenderbuffers(1, &color_);
  glBindRenderbuffer(GL_RENDERBUFFER, color_);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, w_, h_);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, color_);
  GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE)
    throw core::RuntimeFault("off-screen framebuffer " + std::to_string(w_) + "x" + std::to_string(h_) +
                             " is incomplete (status " + std::to_string(status) + ")");
  pack_invert_ = has_pack_invert();
  check_gl("Target");
}

Target::~Target() {
  glDeleteFramebuffers(1, &fbo_);
  glDeleteRenderbuffers(1, &color_);
}

void Target::bind() const {
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
}

#ifndef GL_PACK_INVERT_MESA
#define GL_PACK_INVERT_MESA 0x8758  // GL_MESA_pack_invert; glad is generated for the core profile only
#endif

// Mesa (llvmpipe under OSMesa and under Xvfb) can return rows from the top itself, in the copy it makes
// anyway; other drivers get the flip in read_framebuffer.
bool has_pack_invert() {
  GLint n = 0;
  glGetIntegerv(GL_NUM_EXTENSIONS, &n);
  for (GLint i = 0; i < n; ++i) {
    const char* e = reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, static_cast<GLuint>(i)));
    if (e && std::strcmp(e, "GL_MESA_pack_invert") == 0) return true;
  }
  return false;
}

void read_framebuffer(unsigned fbo, int w, int h, core::Image& out, std::vector<std::uint8_t>& scratch,
                      bool pack_invert) {
  const size_t row = static_cast<size_t>(w) * 4;
  glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
  if (fbo == 0) glReadBuffer(GL_BACK);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  out.width = w;
  out.height = h;
  out.rgba.resize(row * h);
  if (pack_invert) {
    glPixelStorei(GL_PACK_INVERT_MESA, GL_TRUE);
    glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, out.rgba.data());
    glPixelStorei(GL_PACK_INVERT_MESA, GL_FALSE);
    check_gl("glReadPixels");
    return;
  }
  scratch.resize(row * h);
  glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, scratch.data());
  check_gl("glReadPixels");
  for (int y = 0; y < h; ++y) std::memcpy(&out.rgba[row * y], &scratch[row * (h - 1 - y)], row);
}

void Target::read(core::Image& out, bool straight_alpha) const {
  read_framebuffer(fbo_, w_, h_, out, scratch_, pack_invert_);
  if (!straight_alpha) return;
  for (size_t i = 0; i < out.rgba.size(); i += 4) {
    const unsigned a = out.rgba[i + 3];
    if (a == 0 || a == 255) continue;
    for (int k = 0; k < 3; ++k)
      out.rgba[i + k] = static_cast<std::uint8_t>(std::min(255u, (out.rgba[i + k] * 255u + a / 2) / a));
  }
}

}  // namespace render
