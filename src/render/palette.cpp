#include "render/palette.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/error.h"

namespace render {

Palette parse_palette(const std::string& s) {
  if (s == "paper") return Palette::Paper;
  if (s == "colorblind") return Palette::ColorBlind;
  throw core::InputError("palette '" + s + "': expected paper or colorblind");
}

ColorMode parse_color_mode(const std::string& s) {
  for (ColorMode m : {ColorMode::Species, ColorMode::Speed, ColorMode::Force, ColorMode::Displacement,
                      ColorMode::Coordination, ColorMode::Stress, ColorMode::Id})
    if (s == color_mode_name(m)) return m;
  throw core::InputError("color '" + s + "'" +
                         ": expected species, speed, force, displacement, coordination, stress or id");
}

Colormap parse_colormap(const std::string& s) {
  for (Colormap m : {Colormap::Viridis, Colormap::Magma, Colormap::Inferno, Colormap::Cividis})
    if (s == colormap_name(m)) return m;
  throw core::InputError("colormap '" + s + "': expected viridis, magma, inferno or cividis");
}

const char* color_mode_name(ColorMode m) {
  switch (m) {
    case ColorMode::Speed:
      return "speed";
    case ColorMode::Force:
      return "force";
    case ColorMode::Displacement:
      return "displacement";
    case ColorMode::Coordination:
      return "coordination";
    case ColorMode::Stress:
      return "stress";
    case ColorMode::Id:
      return "id";
    case ColorMode::Species:
      break;
  }
  return "species";
}

const char* colormap_name(Colormap m) {
  switch (m) {
    case Colormap::Magma:
      return "magma";
    case Colormap::Inferno:
      return "inferno";
    case Colormap::Cividis:
      return "cividis";
    case Colormap::Viridis:
      break;
  }
  return "viridis";
}

std::string color_scale_label(const Style& s) {
  switch (s.color) {
    case ColorMode::Speed:
      return "speed [m/s]";
    case ColorMode::Force:
      return "contact force [N]";
    case ColorMode::Displacement: {
      char buf[64];
      std::snprintf(buf, sizeof buf, "displacement since %g s [m]", s.displacement_from);
      return buf;
    }
    case ColorMode::Coordination:
      return "contacts per grain";
    case ColorMode::Stress:
      return "pressure (Love-Weber stress) [N/m]";
    default:
      return "";
  }
}

double* color_scale_top(Style& s) {
  switch (s.color) {
    case ColorMode::Speed:
      return &s.speed_max;
    case ColorMode::Force:
      return &s.force_max;
    case ColorMode::Displacement:
      return &s.displacement_max;
    case ColorMode::Coordination:
      return &s.coordination_max;
    case ColorMode::Stress:
      return &s.stress_max;
    default:
      return nullptr;
  }
}

double color_scale_max(const Style& s) {
  const double* top = color_scale_top(const_cast<Style&>(s));
  return top ? *top : 0;
}

namespace {
// "A" or "A:B", finite numbers, nothing else: the number of values read (1 or 2), 0 if malformed.
int read_range(const std::string& text, double& a, double& b) {
  const size_t colon = text.find(':');
  auto number = [](const std::string& t, double& v) {
    char* end = nullptr;
    v = std::strtod(t.c_str(), &end);
    return !t.empty() && *end == '\0' && std::isfinite(v);
  };
  if (colon == std::string::npos) return number(text, a) ? 1 : 0;
  return number(text.substr(0, colon), a) && number(text.substr(colon + 1), b) ? 2 : 0;
}
}  // namespace

void set_color_range(Style& style, const std::string& text) {
  if (style.color == ColorMode::Species || style.color == ColorMode::Id)
    throw core::InputError(
        "a colour range applies to speed, force, displacement, coordination and stress, not " +
        std::string(color_mode_name(style.color)));
  double lo = 0, hi = 0;
  if (text == "auto") {
    if (style.color != ColorMode::Displacement)
      throw core::InputError("auto: each frame's own range is for displacement; give MAX or MIN:MAX");
  } else {
    // MAX, or MIN:MAX.
    double a = 0, b = 0;
    const int n = read_range(text, a, b);
    lo = n == 2 ? a : 0;
    hi = n == 2 ? b : a;
    if (n == 0 || !(hi > lo) || lo < 0)
      throw core::InputError("colour range " + text +
                             ": expected MAX or MIN:MAX with 0 <= MIN < MAX, or auto");
  }
  style.color_min = lo;
  *color_scale_top(style) = hi;  // displacement's 0: each frame's largest
}

void set_chains(Style& style, const std::string& text, const std::string& option) {
  // MIN[:MAX] (N): contacts at least MIN drawn, width and colour growing up to MAX.
  double lo = 0, hi = Style{}.chain_max;
  const int n = read_range(text, lo, hi);
  if (n == 0 || lo < 0 || !(hi > lo)) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", Style{}.chain_max);
    throw core::InputError(
        option + " " + text +
        ": expected MIN or MIN:MAX in N with 0 <= MIN < MAX (e.g. 2 or 2:30; MAX default " + buf + ")");
  }
  style.chains = true;
  style.chain_min = lo;
  style.chain_max = hi;
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

std::string hex_rgb(Rgba c) {
  char b[8];
  auto byte = [](float v) { return static_cast<int>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255)); };
  std::snprintf(b, sizeof b, "#%02x%02x%02x", byte(c.r), byte(c.g), byte(c.b));
  return b;
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

Rgba arch_color(const Style& s) {
  if (s.palette == Palette::ColorBlind && s.dark) return {1.0f, 1.0f, 1.0f, 1};
  return arch_color(s.palette);
}

Rgba halo_edge_color(const Style& s) {
  if (s.dark || s.transparent) return {0, 0, 0, 0};
  return {0.12f, 0.12f, 0.12f, 0.9f};
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

Rgba colormap(const Style& s, double t) {
  // matplotlib's maps at t = k/16.
  static const float table[3][17][3] = {{{0.0015f, 0.0005f, 0.0139f},
                                         {0.0396f, 0.0311f, 0.1335f},
                                         {0.1131f, 0.0655f, 0.2768f},
                                         {0.2117f, 0.0620f, 0.4186f},
                                         {0.3167f, 0.0717f, 0.4854f},
                                         {0.4147f, 0.1104f, 0.5047f},
                                         {0.5128f, 0.1482f, 0.5076f},
                                         {0.6136f, 0.1818f, 0.4985f},
                                         {0.7164f, 0.2150f, 0.4753f},
                                         {0.8169f, 0.2559f, 0.4365f},
                                         {0.9043f, 0.3196f, 0.3881f},
                                         {0.9609f, 0.4183f, 0.3596f},
                                         {0.9867f, 0.5356f, 0.3822f},
                                         {0.9961f, 0.6537f, 0.4462f},
                                         {0.9969f, 0.7696f, 0.5349f},
                                         {0.9924f, 0.8843f, 0.6401f},
                                         {0.9871f, 0.9914f, 0.7495f}},
                                        {{0.0015f, 0.0005f, 0.0139f},
                                         {0.0423f, 0.0281f, 0.1411f},
                                         {0.1293f, 0.0473f, 0.2908f},
                                         {0.2383f, 0.0366f, 0.3964f},
                                         {0.3415f, 0.0623f, 0.4294f},
                                         {0.4412f, 0.0993f, 0.4316f},
                                         {0.5409f, 0.1347f, 0.4151f},
                                         {0.6401f, 0.1714f, 0.3811f},
                                         {0.7357f, 0.2159f, 0.3302f},
                                         {0.8224f, 0.2752f, 0.2661f},
                                         {0.8943f, 0.3534f, 0.1936f},
                                         {0.9470f, 0.4492f, 0.1153f},
                                         {0.9784f, 0.5579f, 0.0349f},
                                         {0.9879f, 0.6753f, 0.0653f},
                                         {0.9746f, 0.7977f, 0.2063f},
                                         {0.9476f, 0.9174f, 0.4107f},
                                         {0.9884f, 0.9984f, 0.6449f}},
                                        {{0.0000f, 0.1351f, 0.3048f},
                                         {0.0000f, 0.1788f, 0.4148f},
                                         {0.1034f, 0.2204f, 0.4358f},
                                         {0.1951f, 0.2644f, 0.4259f},
                                         {0.2637f, 0.3078f, 0.4228f},
                                         {0.3242f, 0.3513f, 0.4263f},
                                         {0.3808f, 0.3952f, 0.4357f},
                                         {0.4352f, 0.4398f, 0.4511f},
                                         {0.4887f, 0.4853f, 0.4710f},
                                         {0.5478f, 0.5319f, 0.4717f},
                                         {0.6091f, 0.5798f, 0.4636f},
                                         {0.6720f, 0.6293f, 0.4480f},
                                         {0.7365f, 0.6806f, 0.4240f},
                                         {0.8027f, 0.7340f, 0.3902f},
                                         {0.8707f, 0.7896f, 0.3433f},
                                         {0.9411f, 0.8475f, 0.2758f},
                                         {0.9957f, 0.9093f, 0.2178f}}};
  if (s.colormap == Colormap::Viridis) return colormap(t);
  const auto& m = table[static_cast<int>(s.colormap) - 1];
  t = std::isfinite(t) ? std::clamp(t, 0.0, 1.0) : 0.0;
  const double x = 16 * t;
  const int k = std::min(15, static_cast<int>(x));
  const float u = static_cast<float>(x - k);
  return {m[k][0] + u * (m[k + 1][0] - m[k][0]), m[k][1] + u * (m[k + 1][1] - m[k][1]),
          m[k][2] + u * (m[k + 1][2] - m[k][2]), 1};
}

Colormap chain_colormap(const Style& s) {
  if (s.chain_colormap) return *s.chain_colormap;
  const bool scaled = s.color != ColorMode::Species && s.color != ColorMode::Id;
  return scaled && s.colormap == Colormap::Viridis ? Colormap::Magma : s.colormap;
}

Rgba chain_color(const Style& s, double t) {
  Style as = s;
  as.colormap = chain_colormap(s);
  return colormap(as, t);
}

Rgba value_color(const Style& s, double value, double top) {
  if (!std::isfinite(value)) return {0.62f, 0.62f, 0.62f, 1};
  const double span = top - s.color_min;
  return colormap(s, span > 0 ? (value - s.color_min) / span : 0.0);
}

Rgba id_color(int id) {
  // Hue a golden angle on from the previous id; lightness cycles through three levels.
  const double h = std::fmod(0.618033988749895 * id, 1.0) * 6.0;
  const double v = id % 3 == 0 ? 0.95 : id % 3 == 1 ? 0.75 : 0.55, sat = 0.75;
  const double c = v * sat, x = c * (1 - std::fabs(std::fmod(h, 2.0) - 1)), m = v - c;
  double r = 0, g = 0, b = 0;
  switch (static_cast<int>(h)) {
    case 0:
      r = c, g = x;
      break;
    case 1:
      r = x, g = c;
      break;
    case 2:
      g = c, b = x;
      break;
    case 3:
      g = x, b = c;
      break;
    case 4:
      r = x, b = c;
      break;
    default:
      r = c, b = x;
      break;
  }
  return {static_cast<float>(r + m), static_cast<float>(g + m), static_cast<float>(b + m), 1};
}

Rgba particle_color(const Style& s, const core::Particle& p, int id) {
  switch (s.color) {
    case ColorMode::Speed:
      return value_color(s, std::hypot(p.vx, p.vy), s.speed_max);
    case ColorMode::Force:
      return value_color(s, p.force, s.force_max);
    case ColorMode::Id:
      return id_color(id);
    default:
      break;
  }
  return species_color(s, p.species);
}

}  // namespace render
