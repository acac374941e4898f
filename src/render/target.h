// An off-screen framebuffer of any size, and its read-back into a core::Image (rows from the top).
#pragma once

#include <cstdint>
#include <vector>

#include "core/image.h"

namespace render {

// Read w x h pixels of framebuffer `fbo` (0: the window's back buffer) into `out`, rows from the top. The one
// read-back of the project: Target::read and the window's screenshot both use it. With pack_invert (pass
// has_pack_invert() of the current context, asked once per context: it walks GL's extension list) GL writes
// the rows from the top itself; without, they are read into `scratch` and flipped.
void read_framebuffer(unsigned fbo, int w, int h, core::Image& out, std::vector<std::uint8_t>& scratch,
                      bool pack_invert);
// The current context offers GL_MESA_pack_invert (Mesa: OSMesa, Xvfb).
bool has_pack_invert();

class Target {
 public:
  // Throws core::InputError if the size is not positive or exceeds what GL allows here.
  Target(int width, int height);
  ~Target();
  Target(const Target&) = delete;
  Target& operator=(const Target&) = delete;
  void bind() const;
  int width() const { return w_; }
  unsigned framebuffer() const { return fbo_; }
  int height() const { return h_; }
  // Read the pixels into `out` (resized), flipping GL's bottom-up rows. The renderer blends with
  // premultiplied alpha; straight_alpha converts back (needed only for transparent backgrounds).
  void read(core::Image& out, bool straight_alpha = false) const;

 private:
  int w_, h_;
  unsigned fbo_ = 0, color_ = 0;
  bool pack_invert_ = false;  // has_pack_invert() of the context the target was made in
  mutable std::vector<std::uint8_t> scratch_;
};

}  // namespace render
