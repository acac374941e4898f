// RGBA (8 bits, rows from the top) to planar YUV 4:2:0, BT.709, limited range: the movie's pixel format,
// converted in one pass with the chroma of each 2x2 block from its mean colour. Written by hand because
// swscale's generic path cost 12-17 ms per 1080p frame here, more than the encoder (see docs/filming.md).
#pragma once

#include <cstdint>

namespace record {

// width and height even. Strides in bytes.
void rgba_to_yuv420p(const std::uint8_t* rgba, int width, int height, std::uint8_t* y, int y_stride,
                     std::uint8_t* u, int u_stride, std::uint8_t* v, int v_stride);

}  // namespace record
