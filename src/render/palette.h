// Colours and styles of a rendered frame. Pure data, no GL.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/frame.h"

namespace render {

struct Rgba {
  float r, g, b, a;
};

enum class Palette { Paper, ColorBlind };
// What sets a grain's colour: its species (the legend), a per-grain quantity on a colour map (speed, the
// summed contact force, the displacement since a reference time, the coordination number, the pressure of
// its Love-Weber stress), or its id (distinct colours, to tell grains apart).
enum class ColorMode { Species, Speed, Force, Displacement, Coordination, Stress, Id };
// Perceptually uniform colour maps (matplotlib's; cividis also reads for red-green colour blindness).
enum class Colormap { Viridis, Magma, Inferno, Cividis };

struct Style {
  Palette palette = Palette::Paper;
  ColorMode color = ColorMode::Species;
  double speed_max = 0.5;   // m/s at the top of the colour scale
  double force_max = 20.0;  // N at the top of the colour scale (~99th percentile of the default scene)
  Colormap colormap = Colormap::Viridis;
  // The bottom of the scale (speed, force, displacement, coordination) and the tops of the displacement (m;
  // 0: each frame's largest) and coordination scales.
  double color_min = 0;
  double displacement_max = 0;
  double coordination_max = 6;
  double stress_max = 60;        // N/m: about the 99th percentile of the paper's silo at rest
  double displacement_from = 0;  // s: displacement is measured from the first frame at or after this time
  bool transparent = false;      // transparent background (PNG)
  bool dark = false;             // a dark background (projectors, dark slides): light walls, dark panels
  bool show_arch = true;
  // Arrows of the forces the shown arch takes from outside it (the grains above, the walls), at their contact
  // points, from the frame's contacts (version 2: with points); the largest as long as an arch member's
  // diameter.
  bool arch_forces = false;
  // Force chains: a segment between the centres of each pair of grains in contact whose normal force is at
  // least chain_min, its width and colour (the colour map) growing with the force up to chain_max.
  bool chains = false;
  double chain_min = 2.0;   // N
  double chain_max = 20.0;  // N
  // The chains' own colour map; unset: the grains' map, or (grains coloured on a scale by viridis) magma, so
  // that chains stand out on force-coloured grains (chain_colormap()).
  std::optional<Colormap> chain_colormap;
  // Tracked grains (by id): a ring of their own colour and a trail of their last trail_s seconds.
  std::vector<int> tracked;
  double trail_s = 2.0;
  bool clear = true;  // clear the image first (false: draw another panel into the same image)
  // A scene's own species colours by species index (alpha 0: the palette's colour for that index); set per
  // panel from its OverlayData.
  std::vector<Rgba> species_colors;
};

// Parse "paper"/"colorblind", "species"/"speed"/"force"/"displacement"/"coordination"/"stress"/"id" and
// "viridis"/"magma"/"inferno"/"cividis"; throw core::InputError naming the option and what is allowed.
Palette parse_palette(const std::string& s);
ColorMode parse_color_mode(const std::string& s);
Colormap parse_colormap(const std::string& s);
const char* color_mode_name(ColorMode m);
// Set the colour scale's range of the style's mode from "MAX", "MIN:MAX" or (displacement) "auto": each
// frame's largest; throws core::InputError naming what is allowed.
void set_color_range(Style& style, const std::string& text);
// Switch force chains on from "MIN" or "MIN:MAX" (N); throws core::InputError naming `option` and the form.
void set_chains(Style& style, const std::string& text, const std::string& option);
const char* colormap_name(Colormap m);
// The colour scale's quantity and unit for the colour bar, e.g. "speed [m/s]"; "" for species and id.
std::string color_scale_label(const Style& s);
// The top of the colour scale the style uses for its mode (0 for species and id), and where it is kept
// (null for species and id).
double color_scale_max(const Style& s);
double* color_scale_top(Style& s);

// The palette's colour of a species by its index: the paper's original disks red and added disks blue, then
// Okabe-Ito green, orange, purple, sky blue, yellow, grey; the colour-blind-safe palette starts with
// Okabe-Ito vermillion and blue. A style's own species_colors win where set.
Rgba species_color(Palette p, core::Species s);
Rgba species_color(const Style& style, core::Species s);
// "#rrggbb" of a colour (alpha left out; channels clamped to 0..1): SVG, matplotlib.
std::string hex_rgb(Rgba c);
Rgba background_color(const Style& s);
Rgba wall_color(Palette p);
Rgba wall_color(const Style& s);  // light on a dark background
Rgba arch_color(Palette p);       // halo and bonds of arch members
// On the style's background: the colour-blind palette's black arch is white on a dark background (black had
// 1.1:1 contrast there).
Rgba arch_color(const Style& s);
// The dark edge outside halos on a light background (alpha 0 on a dark or transparent one).
Rgba halo_edge_color(const Style& s);
Rgba tracked_color(const Style& s);  // ring and trail of tracked grains
// A perceptually uniform map (viridis, polynomial fit) of t in [0, 1].
Rgba colormap(double t);
// The style's colour map of t in [0, 1] (viridis: the polynomial above; the others: matplotlib's map sampled
// at 17 points, linearly interpolated).
Rgba colormap(const Style& s, double t);
// The force chains' map (Style::chain_colormap) and their colour at t in [0, 1].
Colormap chain_colormap(const Style& s);
Rgba chain_color(const Style& s, double t);
// The colour of a value on the style's scale [color_min, top]; NaN (no value: a grain re-injected since the
// reference time) is a neutral grey.
Rgba value_color(const Style& s, double value, double top);
// Distinct colours by id: hues a golden angle apart at three lightness levels, so that neighbours differ.
Rgba id_color(int id);
// The fill colour of a grain under a style (species, speed, force and id; the other modes need the grain's
// value: value_color).
Rgba particle_color(const Style& s, const core::Particle& p, int id = 0);

}  // namespace render
