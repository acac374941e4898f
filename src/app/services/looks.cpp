#include "app/services/looks.h"
#include "app/services/cli.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "app/services/recording.h"
#include "core/error.h"
#include "core/format.h"
#include "core/setup.h"

namespace app {

namespace {
struct Region {
  double x0, y0, x1, y1, t;
};
// "X0,Y0,X1,Y1@T", the box's corners in either order, T >= 0.
Region parse_region(const std::string& text) {
  Region r{};
  char tail = 0;
  const int n = std::sscanf(text.c_str(), "%lf,%lf,%lf,%lf@%lf%c", &r.x0, &r.y0, &r.x1, &r.y1, &r.t, &tail);
  if (n != 5 || !std::isfinite(r.x0 + r.y0 + r.x1 + r.y1 + r.t) || r.t < 0 || r.x0 == r.x1 || r.y0 == r.y1)
    throw core::InputError("--track-region " + text +
                           ": expected X0,Y0,X1,Y1@T (a box in metres with non-zero width and height, and a "
                           "time in seconds >= 0), e.g. -0.3,0,0.3,0.4@2");
  if (r.x0 > r.x1) std::swap(r.x0, r.x1);
  if (r.y0 > r.y1) std::swap(r.y0, r.y1);
  return r;
}
}  // namespace

void LookOptions::add_to(CLI::App& cmd) {
  cmd.add_option(
      "--force-chains", chains,
      "draw the contact network: a segment between the centres of each pair in contact whose normal "
      "force is at least MIN newtons, width and colour growing with the force up to MAX (MIN or "
      "MIN:MAX; e.g. 2 or 2:30; MAX default 20)");
  cmd.add_option(
      "--chain-colormap", chain_colormap,
      "the force chains' colour map: viridis, magma, inferno or cividis (default: the grains' map, "
      "or magma when the grains are coloured on a viridis scale, so chains stand out)");
  cmd.add_option("--annotate", annotate,
                 "T0:T1:X,Y:TEXT: a note in a box with an arrow to the point X,Y (m, the outlet's centre at "
                 "0,0), shown from T0 to T1 s (repeatable; e.g. 2:6:0,0.2:the arch forms)");
  cmd.add_option(
         "--overlay-at", overlay_at,
         "where the boxes go: auto (each at the clear spot nearest its own corner, off the grains, walls "
         "and arch), or the information box's corner (top-right, top-left, bottom-right, bottom-left), or "
         "ELEMENT=CORNER,... for info, plot, colorbar and scale, e.g. plot=bottom-left,scale=top-left")
      ->capture_default_str();
  cmd.add_option("--species-color", species_color,
                 "NAME=#rrggbb: a species' colour, the paper's original and added too (repeatable; e.g. "
                 "original=#444444)");
  cmd.add_option("--arch-halo", arch_halo, "on or off: the halo and bonds that mark the blocking arch")
      ->capture_default_str();
  cmd.add_option("--background", background, "white, or dark (light walls and text: projectors, dark slides)")
      ->capture_default_str();
  cmd.add_option("--font-scale", font_scale,
                 "text size over the default (1/42 of the picture's height); 1.5-2 for a projector")
      ->capture_default_str();
  cmd.add_option(
         "--track", track,
         "follow these grains (ids, comma-separated; the inspector's panel and the exports show ids): a "
         "green ring and a trail of their last --trail seconds")
      ->delimiter(',');
  cmd.add_option("--track-region", track_region,
                 "follow the grains whose centres are inside the box X0,Y0,X1,Y1 (m) at time T (s): "
                 "X0,Y0,X1,Y1@T");
  cmd.add_option("--track-arch", track_arch,
                 "follow the members of the K-th long-lasting arch (the K-th removal of the clog rule, "
                 "arches.csv's row K), from the start of the movie");
  cmd.add_option(
      "--track-clog", track_clog,
      "follow the members of the arch standing as the K-th clog forms (clogs.csv's row K), from the "
      "start of the movie");
  cmd.add_option("--trail", trail_s, "length of the tracked grains' trails, s")->capture_default_str();
}

void LookOptions::apply(int n_grains, bool transparent, render::Style& style,
                        render::OverlayOptions& overlay) const {
  const auto num = [](double v) { return core::format_g(v, 6); };
  if (background != "white" && background != "dark")
    throw core::InputError("--background " + background + ": expected white or dark");
  style.dark = background == "dark";
  if (arch_halo != "on" && arch_halo != "off")
    throw core::InputError("--arch-halo " + arch_halo + ": expected on or off");
  style.show_arch = arch_halo == "on";
  if (!chain_colormap.empty())
    style.chain_colormap =
        for_flag("--chain-colormap", [&] { return render::parse_colormap(chain_colormap); });
  (void)notes();  // every note's form checked now, before any work
  render::parse_placement(overlay_at, "--overlay-at", overlay);
  if (transparent && style.dark)
    throw core::InputError(
        "--background dark and --transparent: choose one (a transparent frame has no background)");
  if (!(font_scale >= 0.5 && font_scale <= 4))
    throw core::InputError("--font-scale " + num(font_scale) + ": allowed range is 0.5 to 4");
  overlay.font_scale = font_scale;
  if (!(trail_s >= 0 && trail_s <= 1000))
    throw core::InputError("--trail " + num(trail_s) + ": allowed range is 0 to 1000 s");
  style.trail_s = trail_s;
  for (const auto& id : track) {
    char* end = nullptr;
    const long v = std::strtol(id.c_str(), &end, 10);
    if (id.empty() || *end != '\0' || v < 0 || v >= n_grains)
      throw core::InputError("--track " + id + ": expected grain ids from 0 to " +
                             std::to_string(n_grains - 1) + " (this scene has " + std::to_string(n_grains) +
                             " grains), comma-separated");
    style.tracked.push_back(static_cast<int>(v));
  }
  if (!track_region.empty()) parse_region(track_region);
  if (track_arch < 0)
    throw core::InputError("--track-arch " + std::to_string(track_arch) + ": expected K >= 1");
  if (track_clog < 0)
    throw core::InputError("--track-clog " + std::to_string(track_clog) + ": expected K >= 1");
  if (chains.empty()) return;
  render::set_chains(style, chains, "--force-chains");
}

void LookOptions::resolve_tags(const core::Model& model, render::Style& style, bool quiet) const {
  const core::Scene& scene = model.scene;
  auto add = [&](const std::vector<int>& ids) {
    for (int id : ids)
      if (std::find(style.tracked.begin(), style.tracked.end(), id) == style.tracked.end())
        style.tracked.push_back(id);
  };
  if (!track_region.empty()) {
    const Region r = parse_region(track_region);
    if (r.t > scene.duration)
      throw core::InputError("--track-region " + track_region + ": T is after the run's end (" +
                             core::format_g(scene.duration, 6) + " s)");
    const std::vector<int> ids = grains_in_box(model, r.x0, r.y0, r.x1, r.y1, r.t, !quiet);
    if (ids.empty())
      throw core::InputError("--track-region " + track_region + ": no grain's centre is in the box at " +
                             core::format_g(r.t, 6) + " s");
    if (!quiet)
      std::fprintf(stderr, "siloscope: --track-region: %zu grains in the box at %s s\n", ids.size(),
                   core::format_g(r.t, 6).c_str());
    add(ids);
  }
  if (track_clog > 0) {
    const std::vector<int> ids = clog_arch_members(model, track_clog, !quiet);
    if (!quiet) std::fprintf(stderr, "siloscope: --track-clog %d: %zu grains\n", track_clog, ids.size());
    add(ids);
  }
  if (track_arch > 0) {
    const std::vector<int> ids = long_arch_members(model, track_arch, !quiet);
    if (!quiet) std::fprintf(stderr, "siloscope: --track-arch %d: %zu grains\n", track_arch, ids.size());
    add(ids);
  }
}

void LookOptions::color_species(render::OverlayData& d) const {
  for (const auto& spec : species_color) {
    const size_t eq = spec.find('=');
    const std::string name = spec.substr(0, eq);
    std::string names;
    for (const auto& n : d.species_names) names += (names.empty() ? "" : ", ") + n;
    if (eq == std::string::npos)
      throw core::InputError("--species-color '" + spec + "': expected NAME=#rrggbb (species: " + names +
                             ")");
    std::array<float, 3> rgb{};
    if (!core::parse_hex_color(spec.substr(eq + 1), rgb))
      throw core::InputError("--species-color '" + spec + "': the colour is not #rrggbb (hex), e.g. #2a9d8f");
    const auto it = std::find(d.species_names.begin(), d.species_names.end(), name);
    if (it == d.species_names.end())
      throw core::InputError("--species-color '" + spec + "': no species named '" + name +
                             "' (this scene has " + names + ")");
    const size_t k = static_cast<size_t>(it - d.species_names.begin());
    if (d.species_colors.size() < d.species_names.size()) d.species_colors.resize(d.species_names.size());
    d.species_colors[k] = {rgb[0], rgb[1], rgb[2], 1};
  }
}

std::vector<render::TimedNote> LookOptions::notes() const {
  std::vector<render::TimedNote> out;
  for (const auto& a : annotate) out.push_back(render::parse_note(a, "--annotate"));
  return out;
}

io::Facts LookOptions::facts(const render::Style& style) const {
  std::string ids;
  for (int id : style.tracked) ids += (ids.empty() ? "" : ",") + std::to_string(id);
  return {{"annotate", annotate},
          {"species_colors", species_color},
          {"overlay_at", overlay_at},
          {"background", background},
          {"font_scale", font_scale},
          {"tracked_grains", ids},
          {"track_region", track_region},
          {"track_arch", track_arch},
          {"track_clog", track_clog},
          {"trail_s", style.trail_s},
          {"force_chains", style.chains},
          {"force_chain_min_N", style.chain_min},
          {"force_chain_max_N", style.chain_max},
          {"force_chain_colormap", std::string(render::colormap_name(render::chain_colormap(style)))},
          {"arch_halo", arch_halo}};
}

}  // namespace app
