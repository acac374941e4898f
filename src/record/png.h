// PNG files from images, with stb_image_write and zlib (level 1, filter 0: ~20 ms per 1080p frame instead of
// ~170 ms with stb's defaults). Written under a temporary name and renamed when complete.
#pragma once

#include <filesystem>
#include <string>

#include "core/image.h"

namespace record {

// Encode `img` as PNG bytes. Throws core::RuntimeFault.
std::string encode_png(const core::Image& img);
// Encode and write atomically; sync = fsync before the rename (off for frame sequences).
void write_png(const std::filesystem::path& path, const core::Image& img, bool sync = false);

}  // namespace record
