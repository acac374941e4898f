// How a recording looks, beyond palette and colouring: the background, the text size, force chains and
// tracked grains. Their command-line options, parsed and checked once, applied to the renderer's style and
// the overlay's options (record; anything else that records pictures can take the same options).
#pragma once

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

#include "core/model.h"
#include "core/scene.h"
#include "io/metadata.h"
#include "render/overlay.h"
#include "render/palette.h"

namespace app {

struct LookOptions {
  std::string background = "white";  // white | dark
  std::string overlay_at = "auto";   // where the boxes go: auto, a corner, or ELEMENT=CORNER,... (render)
  double font_scale = 1.0;
  std::string chains;              // "": off; "MIN" or "MIN:MAX" in N
  std::string chain_colormap;      // "": render::chain_colormap's choice; else viridis|magma|inferno|cividis
  std::string arch_halo = "on";    // on | off: the gold halo and bonds of the blocking arch
  std::vector<std::string> track;  // grain ids to follow
  std::string track_region;        // "X0,Y0,X1,Y1@T": the grains whose centres are in this box at T s
  int track_arch = 0;              // K >= 1: the members of the K-th long-lasting arch (the rule removed)
  int track_clog = 0;              // K >= 1: the members of the arch standing as the K-th clog forms
  double trail_s = 2.0;
  std::vector<std::string> annotate;       // "T0:T1:X,Y:TEXT": a note with an arrow, shown from T0 to T1 s
  std::vector<std::string> species_color;  // "NAME=#rrggbb": a species' colour (the shorthand's too)

  void add_to(CLI::App& cmd);
  // Checked against a scene of n_grains grains (the tracked ids) and --transparent; throws core::InputError
  // naming the option.
  void apply(int n_grains, bool transparent, render::Style& style, render::OverlayOptions& overlay) const;
  // What the metadata records of them, from the style they were applied to.
  io::Facts facts(const render::Style& style) const;
  // Grains tagged by region or by role, found by simulating the scene ahead from the same seed (a run is
  // repeatable, so the recording shows these grains doing what the look-ahead saw); added to style.tracked.
  // Call after apply (which checks the options' form) and after every other check: it costs a simulation.
  void resolve_tags(const core::Model& model, render::Style& style, bool quiet) const;
  // --species-color applied to a panel's overlay data (its species' colours, which the painter uses); throws
  // core::InputError naming the option, the species the scene has and the colour's form.
  void color_species(render::OverlayData& d) const;
  // The notes of --annotate, parsed (throws core::InputError naming the note).
  std::vector<render::TimedNote> notes() const;
};

}  // namespace app
