// One look for every picture: how grains, walls, text and marks are drawn (palette, species colours, the
// colouring and its scale, background, text size, overlay elements and where they go, notes, the arch's
// halo, force chains). One set of options, parsed and checked here, taken by every command that draws:
// record, frame, filmstrip, gallery, timeline, inspect and live. A recording keeps its look in its
// metadata's [look] table, and a picture made from it (frame, filmstrip, gallery, timeline, inspect) uses
// that look for every option the command line does not give.
//
// Following grains (--track and its kin) is record's alone: it simulates ahead (TrackOptions).
#pragma once

#include <CLI/CLI.hpp>

#include <string>
#include <utility>
#include <vector>

#include <toml++/toml.h>

#include "core/model.h"
#include "core/scene.h"
#include "io/metadata.h"
#include "render/overlay.h"
#include "render/palette.h"

namespace app {

// A look resolved for one scene: what the renderer, the overlay and the figure scripts take.
struct Look {
  render::Style style;
  render::OverlayOptions overlay;
  std::vector<render::TimedNote> notes;
  // Each species' colour by index (alpha 0: the palette's), for the overlay's legend and the figures.
  std::vector<render::Rgba> species_colors;
  // --color-max auto on speed or force: the scale comes from simulating ahead (record), or, for a picture of
  // a recording, from the scale the recording used.
  bool color_scale_from_data = false;
  // "#rrggbb" of each species in this look, comma-separated (figure scripts).
  std::string species_hex(const core::Model& model) const;
  // What the figure scripts take of it (src/figures/look.py): "background=dark;font_scale=2", and with a
  // journal width (points, FigureWidth) ";width_pt=241".
  std::string figure_spec(double width_pt = 0) const;
};

// A figure's width on the page, for a journal (--width of filmstrip, gallery and timeline): the figure is
// laid out at that width with text of 7 to 9 pt there (src/figures/look.py), whatever the look's text size.
struct FigureWidth {
  std::string given;  // "": the figure's own size

  void add_to(CLI::App& cmd);
  // Points (1/72 in); 0 when not given. "85mm", "8.5cm", "3.35in", "241pt", or a journal's column: single
  // (86 mm, 3.375 in) or double (178 mm, 7 in). Throws core::InputError naming the value and what is allowed.
  double points() const;
};

struct LookOptions {
  std::string palette = "paper", color = "species", colormap = "viridis", overlay = "all";
  std::string color_max;  // "": each colouring's fixed scale; MAX, MIN:MAX, or auto
  double displacement_from = 0;
  std::string background = "white";  // white | dark
  double font_scale = 1.0;
  std::string overlay_at = "auto";         // auto, a corner, or ELEMENT=CORNER,... (render::parse_placement)
  std::string chains;                      // "": off; "MIN" or "MIN:MAX" in N
  std::string chain_colormap;              // "": render::chain_colormap's choice
  std::string arch_halo = "on";            // on | off
  std::string arch_forces = "off";         // on | off
  bool transparent = false;                // PNG frames without a background
  std::vector<std::string> annotate;       // "T0:T1:X,Y:TEXT"
  std::vector<std::string> species_color;  // "NAME=#rrggbb"

  // Registers every look option on `cmd`, the same way for every command.
  void add_to(CLI::App& cmd);
  // The options not given on the command line take the values of a recording's [look] table (`metadata`:
  // its metadata.toml; a metadata without one, written before looks were kept, leaves the defaults).
  void inherit(const toml::table& metadata);
  // Checked (throws core::InputError naming the option, the value and what is allowed) and resolved for a
  // scene.
  Look resolve(const core::Model& model) const;
  // The [look] table a recording keeps: the options as they take effect (a scale from the data as the
  // numbers it used).
  io::Facts facts(const Look& look) const;

 private:
  std::vector<std::pair<std::string, CLI::Option*>> options_;  // key in [look], the option
  bool given(const std::string& key) const;
};

// record's grains to follow: a ring and a trail.
struct TrackOptions {
  std::vector<std::string> track;  // grain ids
  std::string track_region;        // "X0,Y0,X1,Y1@T": the grains whose centres are in this box at T s
  int track_arch = 0;              // K >= 1: the members of the K-th long-lasting arch (the rule removed)
  int track_clog = 0;              // K >= 1: the members of the arch standing as the K-th clog forms
  double trail_s = 2.0;

  void add_to(CLI::App& cmd);
  // The ids and the trail, checked against a scene of n_grains grains; throws core::InputError naming the
  // option.
  void apply(int n_grains, render::Style& style) const;
  io::Facts facts(const render::Style& style) const;
  // Grains tagged by region or by role, found by simulating the scene ahead from the same seed (a run is
  // repeatable, so the recording shows these grains doing what the look-ahead saw); added to style.tracked.
  void resolve_tags(const core::Model& model, render::Style& style, bool quiet) const;
};

}  // namespace app
