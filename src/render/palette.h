// Colours and styles of a rendered frame. Pure data, no GL.
#pragma once

#include <string>
#include <vector>

#include "core/frame.h"

namespace render {

struct Rgba {
  float r, g, b, a;
};

enum class Palette { Paper, ColorBlind };
enum class ColorMode { Species, Speed, Force };

struct Style {
  Palette palette = Palette::Paper;
  ColorMode color = ColorMode::Species;
  double speed_max = 0.5;    // m/s at the top of the colour scale
  double force_max = 20.0;   // N at the top of the colour scale (~99th percentile of the default scene)
  bool transparent = false;  // transparent background (PNG)
  bool dark = false;         // a dark background (projectors, dark slides): light walls, dark panels
  bool show_arch = true;
  // Force chains: a segment between the centres of each pair of grains in contact whose normal force is at
  // least chain_min, its width and colour (the colour map) growing with the force up to chain_max.
  bool chains = false;
  double chain_min = 2.0;   // N
  double chain_max = 20.0;  // N
  // Tracked grains (by id): a ring of their own colour and a trail of their last trail_s seconds.
  std::vector<int> tracked;
  double trail_s = 2.0;
  bool clear = true;  // clear the image first (false: draw another panel into the same image)
  // A scene's own species colours by species index (alpha 0: the palette's colour for that index); set per
  // panel from its OverlayData.
  std::vector<Rgba> species_colors;
};

// Parse "paper"/"colorblind" and "species"/"speed"/"force"; throw core::InputError naming the option.
Palette parse_palette(const std::string& s);
ColorMode parse_color_mode(const std::string& s);

// The palette's colour of a species by its index: the paper's original disks red and added disks blue, then
// Okabe-Ito green, orange, purple, sky blue, yellow, grey; the colour-blind-safe palette starts with
// Okabe-Ito vermillion and blue. A style's own species_colors win where set.
Rgba species_color(Palette p, core::Species s);
Rgba species_color(const Style& style, core::Species s);
Rgba background_color(const Style& s);
Rgba wall_color(Palette p);
Rgba wall_color(const Style& s);     // light on a dark background
Rgba arch_color(Palette p);          // halo and bonds of arch members
Rgba tracked_color(const Style& s);  // ring and trail of tracked grains
// A perceptually uniform map (viridis, polynomial fit) of t in [0, 1].
Rgba colormap(double t);
// The fill colour of a disk under a style.
Rgba particle_color(const Style& s, const core::Particle& p);

}  // namespace render
