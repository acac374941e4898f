#include "app/services/looks.h"
#include "app/services/cli.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

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
  auto keep = [&](const char* key, CLI::Option* opt) { options_.push_back({key, opt}); };
  keep("palette", cmd.add_option("--palette", palette, "paper (red/blue) or colorblind (Okabe-Ito)")
                      ->capture_default_str());
  keep("species_colors",
       cmd.add_option("--species-color", species_color,
                      "NAME=#rrggbb: a species' colour, the paper's original and added too (repeatable; e.g. "
                      "original=#444444)"));
  keep("color", cmd.add_option("--color", color,
                               "colour grains by species, speed, force (summed contact force), displacement "
                               "(since --displacement-from), coordination (contacts per grain), stress (the "
                               "pressure of each grain's Love-Weber stress, N/m) or id")
                    ->capture_default_str());
  keep("color_max",
       cmd.add_option("--color-max", color_max,
                      "the colour scale, MAX or MIN:MAX in the quantity's unit (m/s, N, m, contacts, N/m), "
                      "or auto (speed "
                      "and force: the 99th percentile of the first 2 s of discharge; displacement: each "
                      "frame's largest); "
                      "default: fixed scales (0.5 m/s, 20 N, 0-6 contacts, 60 N/m), displacement auto"));
  keep("colormap",
       cmd.add_option("--colormap", colormap, "viridis, magma, inferno or cividis")->capture_default_str());
  keep("displacement_from_s",
       cmd.add_option(
              "--displacement-from", displacement_from,
              "--color displacement: from where each grain stood at this time, s (0: the outlet opens)")
           ->capture_default_str());
  keep("background", cmd.add_option("--background", background,
                                    "white, or dark (light walls and text: projectors, dark slides)")
                         ->capture_default_str());
  keep("font_scale", cmd.add_option("--font-scale", font_scale,
                                    "text size over the default (1/42 of the picture's height); 1.5-2 for a "
                                    "projector")
                         ->capture_default_str());
  keep("overlay", cmd.add_option("--overlay", overlay,
                                 "all, all+plot, none, or a list of time,counts,rate,timer,arch,legend,scale,"
                                 "events,zoombox,plot,colorbar,ids")
                      ->capture_default_str());
  keep("overlay_at",
       cmd.add_option(
              "--overlay-at", overlay_at,
              "where the boxes go: auto (each at the clear spot nearest its own corner, off the grains, "
              "walls and arch), or the information box's corner (top-right, top-left, bottom-right, "
              "bottom-left), or ELEMENT=CORNER,... for info, plot, colorbar and scale")
           ->capture_default_str());
  keep("annotate", cmd.add_option("--annotate", annotate,
                                  "T0:T1:X,Y:TEXT: a note in a box with an arrow to the point X,Y (m, the "
                                  "outlet's centre at 0,0), shown from T0 to T1 s (repeatable)"));
  keep(
      "arch_forces",
      cmd.add_option("--arch-forces", arch_forces,
                     "on or off: arrows of the forces the blocking arch takes from the grains above and from "
                     "the walls, at their contact points, the largest a member's diameter long (from the "
                     "solver's contacts; a recording made before contacts kept their points shows none)")
          ->capture_default_str());
  keep("arch_halo",
       cmd.add_option("--arch-halo", arch_halo, "on or off: the halo and bonds that mark the blocking arch")
           ->capture_default_str());
  keep("force_chains",
       cmd.add_option(
           "--force-chains", chains,
           "draw the contact network: a segment between the centres of each pair in contact whose "
           "normal force is at least MIN newtons, width and colour growing with the force up to MAX "
           "(MIN or MIN:MAX; e.g. 2 or 2:30; MAX default 20)"));
  keep(
      "force_chain_colormap",
      cmd.add_option("--chain-colormap", chain_colormap,
                     "the force chains' colour map: viridis, magma, inferno or cividis (default: the grains' "
                     "map, or magma when the grains are coloured on a viridis scale)"));
  keep("transparent", cmd.add_flag("--transparent", transparent, "transparent background in PNG pictures"));
}

bool LookOptions::given(const std::string& key) const {
  for (const auto& [k, opt] : options_)
    if (k == key) return opt && opt->count() > 0;
  return false;
}

void LookOptions::inherit(const toml::table& metadata) {
  const toml::table* look = metadata["look"].as_table();
  if (!look) return;
  auto text = [&](const char* key, std::string& v) {
    if (!given(key))
      if (auto x = (*look)[key].value<std::string>()) v = *x;
  };
  auto number = [&](const char* key, double& v) {
    if (!given(key))
      if (auto x = (*look)[key].value<double>()) v = *x;
  };
  auto list = [&](const char* key, std::vector<std::string>& v) {
    if (given(key) || !(*look)[key].as_array()) return;
    v.clear();
    for (const auto& item : *(*look)[key].as_array())
      if (auto x = item.value<std::string>()) v.push_back(*x);
  };
  text("palette", palette);
  text("color", color);
  text("color_max", color_max);
  text("colormap", colormap);
  number("displacement_from_s", displacement_from);
  text("background", background);
  number("font_scale", font_scale);
  text("overlay", overlay);
  text("overlay_at", overlay_at);
  text("arch_halo", arch_halo);
  text("arch_forces", arch_forces);
  text("force_chains", chains);
  text("force_chain_colormap", chain_colormap);
  list("annotate", annotate);
  list("species_colors", species_color);
  if (!given("transparent")) transparent = (*look)["transparent"].value_or(transparent);
}

namespace {
// --species-color over the scene's own colours, by species index.
std::vector<render::Rgba> species_colors_of(const core::Model& model, const std::vector<std::string>& specs) {
  const render::OverlayData d = render::overlay_data_for(model);
  std::vector<render::Rgba> colors = d.species_colors;
  colors.resize(d.species_names.size(), render::Rgba{0, 0, 0, 0});
  std::string names;
  for (const auto& n : d.species_names) names += (names.empty() ? "" : ", ") + n;
  for (const auto& spec : specs) {
    const size_t eq = spec.find('=');
    if (eq == std::string::npos)
      throw core::InputError("--species-color '" + spec + "': expected NAME=#rrggbb (species: " + names +
                             ")");
    std::array<float, 3> rgb{};
    if (!core::parse_hex_color(spec.substr(eq + 1), rgb))
      throw core::InputError("--species-color '" + spec + "': the colour is not #rrggbb (hex), e.g. #2a9d8f");
    const std::string name = spec.substr(0, eq);
    const auto it = std::find(d.species_names.begin(), d.species_names.end(), name);
    if (it == d.species_names.end())
      throw core::InputError("--species-color '" + spec + "': no species named '" + name +
                             "' (this scene has " + names + ")");
    colors[static_cast<size_t>(it - d.species_names.begin())] = {rgb[0], rgb[1], rgb[2], 1};
  }
  return colors;
}

// The colour scale's options into the style.
void resolve_scale(const LookOptions& o, Look& look) {
  render::Style& style = look.style;
  const auto num = [](double v) { return core::format_g(v, 6); };
  if (!(o.displacement_from >= 0) || o.displacement_from > 1e6)
    throw core::InputError("--displacement-from " + num(o.displacement_from) +
                           ": allowed range is 0 to 1e6 s");
  if (o.displacement_from > 0 && style.color != render::ColorMode::Displacement)
    throw core::InputError("--displacement-from applies to --color displacement, not " + o.color);
  style.displacement_from = o.displacement_from;
  look.color_scale_from_data = o.color_max == "auto" && (style.color == render::ColorMode::Speed ||
                                                         style.color == render::ColorMode::Force);
  if (o.color_max.empty() || look.color_scale_from_data) return;
  try {
    render::set_color_range(style, o.color_max);
  } catch (const core::InputError& e) {
    throw core::InputError("--color-max " + o.color_max + ": " + e.what());
  }
}
}  // namespace

Look LookOptions::resolve(const core::Model& model) const {
  Look look;
  render::Style& style = look.style;
  style.palette = for_flag("--palette", [&] { return render::parse_palette(palette); });
  style.color = for_flag("--color", [&] { return render::parse_color_mode(color); });
  style.colormap = for_flag("--colormap", [&] { return render::parse_colormap(colormap); });
  resolve_scale(*this, look);
  look.overlay = for_flag("--overlay", [&] { return render::parse_overlay(overlay); });
  render::parse_placement(overlay_at, "--overlay-at", look.overlay);
  if (background != "white" && background != "dark")
    throw core::InputError("--background " + background + ": expected white or dark");
  style.dark = background == "dark";
  if (transparent && style.dark)
    throw core::InputError(
        "--background dark and --transparent: choose one (a transparent picture has no background)");
  style.transparent = transparent;
  if (arch_halo != "on" && arch_halo != "off")
    throw core::InputError("--arch-halo " + arch_halo + ": expected on or off");
  style.show_arch = arch_halo == "on";
  if (arch_forces != "on" && arch_forces != "off")
    throw core::InputError("--arch-forces " + arch_forces + ": expected on or off");
  if (arch_forces == "on" && !style.show_arch)
    throw core::InputError("--arch-forces on draws on the arch: it needs --arch-halo on");
  style.arch_forces = arch_forces == "on";
  if (!(font_scale >= 0.5 && font_scale <= 4))
    throw core::InputError("--font-scale " + core::format_g(font_scale, 6) + ": allowed range is 0.5 to 4");
  look.overlay.font_scale = font_scale;
  if (!chains.empty()) render::set_chains(style, chains, "--force-chains");
  if (!chain_colormap.empty())
    style.chain_colormap =
        for_flag("--chain-colormap", [&] { return render::parse_colormap(chain_colormap); });
  for (const auto& a : annotate) look.notes.push_back(render::parse_note(a, "--annotate"));
  look.species_colors = species_colors_of(model, species_color);
  style.species_colors = look.species_colors;
  return look;
}

std::string Look::species_hex(const core::Model& model) const {
  std::string colors;
  for (size_t k = 0; k < model.setup.species.size(); ++k)
    colors += (k ? "," : "") + render::hex_rgb(render::species_color(style, static_cast<core::Species>(k)));
  return colors;
}

std::string Look::figure_spec(double width_pt) const {
  return std::string("background=") + (style.dark ? "dark" : "white") +
         ";font_scale=" + core::format_g(overlay.font_scale, 6) +
         (width_pt > 0 ? ";width_pt=" + core::format_g(width_pt, 9) : "");
}

void FigureWidth::add_to(CLI::App& cmd) {
  cmd.add_option(
      "--width", given,
      "lay the figure out at this width on the page, text 7-9 pt there: 85mm, 8.5cm, 3.35in, 241pt, "
      "single (a journal's column, 86 mm) or double (178 mm)");
}

double FigureWidth::points() const {
  if (given.empty()) return 0;
  constexpr double mm = 72.0 / 25.4;
  if (given == "single") return 86 * mm;
  if (given == "double") return 178 * mm;
  const std::pair<const char*, double> units[] = {{"mm", mm}, {"cm", 10 * mm}, {"in", 72.0}, {"pt", 1.0}};
  for (const auto& [unit, factor] : units) {
    const size_t n = std::strlen(unit);
    if (given.size() <= n || given.compare(given.size() - n, n, unit) != 0) continue;
    const std::string number = given.substr(0, given.size() - n);
    char* end = nullptr;
    const double v = std::strtod(number.c_str(), &end);
    if (*end || !std::isfinite(v)) break;
    const double pt = v * factor;
    // From a narrow column (40 mm) to a landscape page (300 mm).
    if (pt < 40 * mm - 1e-9 || pt > 300 * mm + 1e-9)
      throw core::InputError("--width " + given + ": " + core::format_g(pt / mm, 4) +
                             " mm is outside 40 mm to 300 mm");
    return pt;
  }
  throw core::InputError(
      "--width " + given +
      ": expected a length with its unit (85mm, 8.5cm, 3.35in, 241pt) or single (86 mm) or "
      "double (178 mm)");
}

io::Facts LookOptions::facts(const Look& look) const {
  const render::Style& style = look.style;
  // A scale taken from the data is kept as the numbers it gave, so a picture made later uses the same.
  const std::string range = look.color_scale_from_data ? core::format_g(style.color_min, 9) + ":" +
                                                             core::format_g(render::color_scale_max(style), 9)
                                                       : color_max;
  return {{"palette", palette},
          {"species_colors", species_color},
          {"color", color},
          {"color_max", range},
          {"colormap", colormap},
          {"displacement_from_s", displacement_from},
          {"background", background},
          {"font_scale", font_scale},
          {"overlay", overlay},
          {"overlay_at", overlay_at},
          {"annotate", annotate},
          {"arch_halo", arch_halo},
          {"arch_forces", arch_forces},
          {"force_chains", chains},
          {"force_chain_colormap", chain_colormap},
          {"transparent", transparent}};
}

void TrackOptions::add_to(CLI::App& cmd) {
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

void TrackOptions::apply(int n_grains, render::Style& style) const {
  if (!(trail_s >= 0 && trail_s <= 1000))
    throw core::InputError("--trail " + core::format_g(trail_s, 6) + ": allowed range is 0 to 1000 s");
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
}

io::Facts TrackOptions::facts(const render::Style& style) const {
  std::string ids;
  for (int id : style.tracked) ids += (ids.empty() ? "" : ",") + std::to_string(id);
  return {{"tracked_grains", ids},
          {"track_region", track_region},
          {"track_arch", track_arch},
          {"track_clog", track_clog},
          {"trail_s", style.trail_s}};
}

void TrackOptions::resolve_tags(const core::Model& model, render::Style& style, bool quiet) const {
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

}  // namespace app
