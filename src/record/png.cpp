#include "record/png.h"

#include <zlib.h>

#include <cstdlib>

#include "core/error.h"
#include "io/output.h"

namespace {
// stb's PNG writer calls this instead of its own (slow) deflate.
unsigned char* zlib_compress(unsigned char* data, int data_len, int* out_len, int /*quality*/) {
  uLongf bound = compressBound(static_cast<uLong>(data_len));
  auto* out = static_cast<unsigned char*>(std::malloc(bound));
  if (!out) return nullptr;
  if (compress2(out, &bound, data, static_cast<uLong>(data_len), 1) != Z_OK) {
    std::free(out);
    return nullptr;
  }
  *out_len = static_cast<int>(bound);
  return out;
}
}  // namespace

#define STBIW_ZLIB_COMPRESS zlib_compress
#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_WRITE_STATIC
#include <stb_image_write.h>

namespace record {

std::string encode_png(const core::Image& img) {
  if (img.width <= 0 || img.height <= 0 || img.rgba.size() != static_cast<size_t>(img.width) * img.height * 4)
    throw core::RuntimeFault("encode_png: the image is empty or inconsistent");
  std::string out;
  stbi_write_force_png_filter = 0;  // no per-row filter search: half the time, slightly larger files
  int len = 0;
  unsigned char* png = stbi_write_png_to_mem(img.rgba.data(), img.width * 4, img.width, img.height, 4, &len);
  if (!png) throw core::RuntimeFault("PNG encoding failed");
  out.assign(reinterpret_cast<char*>(png), static_cast<size_t>(len));
  STBIW_FREE(png);
  return out;
}

void write_png(const std::filesystem::path& path, const core::Image& img, bool sync) {
  io::write_file_atomic(path, encode_png(img), sync);
}

}  // namespace record
