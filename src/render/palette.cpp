#include "render/palette.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace render {

Palette parse_palette(const std::string& s) {
  if (s == "paper") return Palette::Paper;
  if (s == "colorblind") return Palette::ColorBlind;
  throw core::InputError("--palette " + s + ": expected paper or colorblind");
}

ColorMode parse_color_mode(const std::string& s) {
  if (s == "species") return ColorMode::Species;
  if (s == "speed") return ColorMode::Speed;
  if (s == "force") return ColorMode::Force;
  throw core::InputError("--color " + s + ": expected species, speed or force");
}

Rgba species_color(Palette p, core::Species s) {
  // Beyond the first two: Okabe-Ito bluish green, orange, reddish purple, sky blue, yellow, then grey.
  static const Rgba more[] = {{0.0f, 0.62f, 0.451f, 1},
                              {0.902f, 0.624f, 0.0f, 1},
                              {0.8f, 0.475f, 0.655f, 1},
                              {0.337f, 0.706f, 0.914f, 1},
                              {0.941f, 0.894f, 0.259f, 1}};
  const int k = core::species_index(s);
  if (k >= 2) return k - 2 < 5 ? more[k - 2] : Rgba{0.55f, 0.55f, 0.55f, 1};
  const bool original = k == 0;
  if (p == Palette::ColorBlind)
    return original ? Rgba{0.835f, 0.369f, 0.0f, 1} : Rgba{0.0f, 0.447f, 0.698f, 1};
  return original ? Rgba{0.85f, 0.16f, 0.14f, 1} : Rgba{0.16f, 0.38f, 0.85f, 1};
}

Rgba species_color(const Style& style, core::Species s) {
  const size_t k = static_cast<size_t>(core::species_index(s));
  if (k < style.species_colors.size() && style.species_colors[k].a > 0) return style.species_colors[k];
  return species_color(style.palette, s);
}

Rgba background_color(const Style& s) {
  if (s.transparent) return {0, 0, 0, 0};
  if (s.dark) return {0.07f, 0.07f, 0.09f, 1};
  return {1, 1, 1, 1};
}

Rgba wall_color(const Style& s) {
  return s.dark ? Rgba{0.82f, 0.82f, 0.85f, 1} : wall_color(s.palette);
}

Rgba wall_color(Palette) {
  return {0.18f, 0.18f, 0.2f, 1};
}

Rgba tracked_color(const Style& s) {
  return s.dark ? Rgba{0.3f, 1.0f, 0.4f, 1}
                : Rgba{0.0f, 0.62f, 0.2f, 1};  // green: apart from red, blue, gold
}

Rgba arch_color(Palette p) {
  if (p == Palette::ColorBlind) return {0.0f, 0.0f, 0.0f, 1};
  return {1.0f, 0.76f, 0.0f, 1};  // gold
}

Rgba colormap(double t) {
  t = std::clamp(t, 0.0, 1.0);
  // Viridis, 6th-order polynomial fit per channel.
  const double c0[3] = {0.2777273272234177, 0.005407344544966578, 0.3340998053353061};
  const double c1[3] = {0.1050930431085774, 1.404613529898575, 1.384590162594685};
  const double c2[3] = {-0.3308618287255563, 0.214847559468213, 0.09509516302823659};
  const double c3[3] = {-4.634230498983486, -5.799100973351585, -19.33244095627987};
  const double c4[3] = {6.228269936347081, 14.17993336680509, 56.69055260068105};
  const double c5[3] = {4.776384997670288, -13.74514537774601, -65.35303263337234};
  const double c6[3] = {-5.435455855934631, 4.645852612178535, 26.3124352495832};
  float out[3];
  for (int k = 0; k < 3; ++k)
    out[k] = static_cast<float>(std::clamp(
        c0[k] + t * (c1[k] + t * (c2[k] + t * (c3[k] + t * (c4[k] + t * (c5[k] + t * c6[k]))))), 0.0, 1.0));
  return {out[0], out[1], out[2], 1};
}

Rgba particle_color(const Style& s, const core::Particle& p) {
  switch (s.color) {
    case ColorMode::Speed:
      return colormap(std::hypot(p.vx, p.vy) / s.speed_max);
    case ColorMode::Force:
      return colormap(p.force / s.force_max);
    case ColorMode::Species:
      break;
  }
  return species_color(s, p.species);
}

}  // namespace render
