// An RGBA image, 8 bits per channel, rows from the top, no padding: what the renderer hands to the recorder.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace core {

struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgba;  // width * height * 4 bytes
  double t = 0;                    // simulated time shown, s

  const std::uint8_t* pixel(int x, int y) const { return &rgba[(static_cast<size_t>(y) * width + x) * 4]; }
};

}  // namespace core
