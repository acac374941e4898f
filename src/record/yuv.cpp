#include "record/yuv.h"

namespace record {

namespace {
// BT.709 limited range in 16.16 fixed point:
//   Y  = 16  + 0.1826 R + 0.6142 G + 0.0620 B
//   Cb = 128 - 0.1006 R - 0.3386 G + 0.4392 B
//   Cr = 128 + 0.4392 R - 0.3989 G - 0.0403 B
constexpr int kYR = 11966, kYG = 40254, kYB = 4064;
constexpr int kUR = -6596, kUG = -22189, kUB = 28784;
constexpr int kVR = 28784, kVG = -26145, kVB = -2639;
constexpr int kHalf = 1 << 15;

inline std::uint8_t luma(const std::uint8_t* p) {
  return static_cast<std::uint8_t>(((16 << 16) + kYR * p[0] + kYG * p[1] + kYB * p[2] + kHalf) >> 16);
}
}  // namespace

void rgba_to_yuv420p(const std::uint8_t* rgba, int width, int height, std::uint8_t* y, int y_stride,
                     std::uint8_t* u, int u_stride, std::uint8_t* v, int v_stride) {
  const int row = 4 * width;
  for (int j = 0; j < height; j += 2) {
    const std::uint8_t* a = rgba + static_cast<long>(j) * row;
    const std::uint8_t* b = a + row;
    std::uint8_t* ya = y + static_cast<long>(j) * y_stride;
    std::uint8_t* yb = ya + y_stride;
    std::uint8_t* uu = u + static_cast<long>(j / 2) * u_stride;
    std::uint8_t* vv = v + static_cast<long>(j / 2) * v_stride;
    for (int i = 0; i < width; i += 2) {
      const std::uint8_t *p0 = a + 4 * i, *p1 = p0 + 4, *p2 = b + 4 * i, *p3 = p2 + 4;
      ya[i] = luma(p0);
      ya[i + 1] = luma(p1);
      yb[i] = luma(p2);
      yb[i + 1] = luma(p3);
      // Sums of the four pixels: the mean colour times 4, so the coefficients are divided by 4 (>> 18).
      const int r = p0[0] + p1[0] + p2[0] + p3[0], g = p0[1] + p1[1] + p2[1] + p3[1],
                bl = p0[2] + p1[2] + p2[2] + p3[2];
      uu[i / 2] = static_cast<std::uint8_t>(((128 << 18) + kUR * r + kUG * g + kUB * bl + (1 << 17)) >> 18);
      vv[i / 2] = static_cast<std::uint8_t>(((128 << 18) + kVR * r + kVG * g + kVB * bl + (1 << 17)) >> 18);
    }
  }
}

}  // namespace record
