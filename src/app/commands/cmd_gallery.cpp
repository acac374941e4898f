// siloscope gallery RUN --out arches.pdf|svg|png: one sheet with every long-lasting arch of a run, each a
// zoomed outlet view just before the 5 s rule removed it, members highlighted, labelled with the time, the
// clog's duration, the members and their species. The run is re-simulated from its metadata (runs are
// deterministic: the trajectory is not needed), and each re-simulated removal is checked against the run's
// own arches.csv. An imported lab run (siloscope import) has no rule and cannot be re-simulated: its tiles
// are its clogs' arches, drawn from its trajectory.
#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <sstream>

#include "app/services/cli.h"
#include "app/services/looks.h"
#include "app/services/process.h"
#include "app/services/replay.h"
#include "app/services/run_outputs.h"
#include "app/services/session.h"
#include "app/services/terminal.h"
#include "core/arch.h"
#include "core/error.h"
#include "core/format.h"
#include "core/setup.h"
#include "io/csv_table.h"
#include "io/events_csv.h"
#include "io/manifest.h"
#include "io/metadata.h"
#include "io/output.h"
#include "io/run.h"
#include "render/camera.h"
#include "render/draw_list.h"
#include "render/overlay.h"
#include "sim/silo.h"

namespace app {

namespace {
namespace fs = std::filesystem;

struct GalleryOptions {
  std::string run, out;
  int tile = 480, columns = 0, max_arches = 60;
  bool force = false;
  LookOptions looks;  // the run's own look unless given
  FigureWidth width;  // a journal's column, or the figure's own size
};

// The index's row of one tile: the arch's time, members, species and the descriptors of the literature
// (core::arch_descriptors) from the frame the tile shows.
std::string tile_row(const std::string& name, const core::ArchEvent& a, const core::Frame& f,
                     const std::vector<std::string>& names, double window_m) {
  int added = 0;
  std::string species;
  for (auto s : a.species) {
    added += s != core::Species::Original;
    const size_t i = static_cast<size_t>(core::species_index(s));
    species += std::string(species.empty() ? "" : ";") + (i < names.size() ? names[i] : "?");
  }
  std::vector<core::Vec2> pos;
  std::vector<double> radius;
  for (const auto& p : f.particles) pos.push_back({p.x, p.y}), radius.push_back(p.radius);
  const core::ArchDescriptors ad = core::arch_descriptors(a.ids, pos, radius);
  return name + "," + core::format_g(a.t, 6) + "," + core::format_g(a.clog_duration, 4) + "," +
         std::to_string(a.ids.size()) + "," + std::to_string(added) + "," + species + "," +
         core::arch_method_name(a.method) + "," + core::format_g(a.geometry.span, 4) + "," +
         core::format_g(ad.rise, 4) + "," + core::format_g(ad.aspect, 4) + "," +
         core::format_g(ad.theta_max_deg, 4) + "," + std::to_string(ad.defects) + "," +
         core::format_g(ad.angle_sd_deg, 4) + "," + core::format_g(window_m, 6) + "\n";
}

// An imported sheet's caption: how the import found each clog's arch (lab/import.cpp).
constexpr const char* kImportedCaption =
    "members ringed, bonds dark; each clog's arch where it last stood at rest, found on the positions "
    "averaged while it rested (contacts by distance: import's --contact-tolerance, or more for noisy "
    "tracks), drawn at that frame; h/(s/2): rise over half the span; \u03b8max: the largest bead angle; "
    "defects: bead angles above 180\u00b0";

// An imported run's tiles: each clog's arch (clog_arches.csv) at the frame of its trajectory the import took
// it from. Returns the frames' indices; the arches go into `recorded` in place of the rule's removals.
std::vector<long> imported_arches(const io::Run& run, core::Events& recorded) {
  const io::Trajectory& traj = run.trajectory();
  std::vector<long> at;
  recorded.arches.clear();
  for (const io::Run::ClogArch& c : run.clog_arches()) {
    core::ArchEvent a;
    a.t = c.t;
    a.clog_duration = a.t - recorded.clogs[static_cast<size_t>(c.clog) - 1].start;
    long k = 0;
    while (k + 1 < traj.size() && traj.time(k) < a.t - 1e-6) ++k;
    const core::Frame f = traj.frame(k);
    for (int id : c.ids) {
      a.ids.push_back(id);
      a.species.push_back(f.particles[static_cast<size_t>(id)].species);
    }
    std::vector<core::Vec2> pos;
    std::vector<double> radius;
    for (const auto& p : f.particles) pos.push_back({p.x, p.y}), radius.push_back(p.radius);
    a.geometry = core::arch_geometry(a.ids, pos, radius);
    recorded.arches.push_back(std::move(a));
    at.push_back(k);
  }
  return at;
}

// The sheet's title: the run, its scene (r, chi, mu, kick and seed for the paper's shorthand), how many
// arches of how many, and the force chains' scale.
std::string sheet_title(const io::Run& run, bool imported, size_t n, size_t of, const render::Style& style) {
  const core::Scene& scene = run.model().scene;
  const std::string what =
      imported ? std::string("from tracked particles, contacts by distance")
      : run.model().setup.shorthand
          ? "r = " + core::format_g(scene.size_ratio) + ", chi = " + core::format_g(scene.chi) +
                ", mu = " + core::format_g(scene.mu) + " A m^2, kick " +
                core::format_g(scene.kick_impulse_max) + " N s, seed " + std::to_string(scene.seed)
          : render::overlay_data_for(run.model()).title;
  return (imported ? "clogs' arches of the imported run " : "long-lasting arches of ") + run.name() + ": " +
         what + " (" + std::to_string(n) + " of " + std::to_string(of) + ")" +
         (style.chains ? "; force chains from " + core::format_g(style.chain_min, 4) + " N, viridis to " +
                             core::format_g(style.chain_max, 4) + " N"
                       : "");
}

// The sheet's key (src/figures/look.py read_key): each species' colour, the arch's ring, the grain's size.
std::string sheet_key(const std::vector<std::string>& names, const render::Style& style, double diameter) {
  std::string k = std::string("background\t") + (style.dark ? "dark" : "white") + "\n";
  for (size_t s = 0; s < names.size(); ++s)
    k += "species\t" + names[s] + "\t" +
         render::hex_rgb(render::species_color(style, static_cast<core::Species>(s))) + "\n";
  if (style.show_arch) k += "arch\tarch members\t" + render::hex_rgb(render::arch_color(style)) + "\n";
  return k + "scale\t" + core::format_g(diameter, 6) + "\t1 d = " + core::format_g(100 * diameter, 3) +
         " cm\n";
}

int gallery(const GalleryOptions& o) {
  const fs::path out = o.out;
  const std::string ext = out.extension().string();
  if (ext != ".pdf" && ext != ".svg" && ext != ".png")
    throw core::InputError("--out " + o.out + ": the sheet is .pdf, .svg or .png");
  if (o.tile < 120 || o.tile > 2000 || o.tile % 2)
    throw core::InputError("--tile " + std::to_string(o.tile) +
                           ": allowed are even sizes from 120 to 2000 pixels");
  const double width_pt = o.width.points();
  // The run opened once: its manifest checked, its scene compiled (the re-simulation, the pictures and the
  // species' names share it), its events read.
  const io::Run run = io::Run::open(o.run, "gallery", io::Run::kEvents);
  const core::Model& model = run.model();
  const core::Scene& scene = model.scene;
  const core::Setup& setup = model.setup;
  const std::vector<std::string> names = setup.species_names();
  core::Events recorded = run.events();
  // A lab run (siloscope import) has no rule and nothing to re-simulate: its tiles are its clogs' arches, at
  // the frame of its trajectory the import took each from (clog_arches.csv).
  const bool imported = run.has(io::run_file::kClogArches) && run.has_trajectory();
  std::vector<long> traj_frame;
  if (imported) traj_frame = imported_arches(run, recorded);
  if (recorded.arches.empty())
    throw core::InputError("gallery: " + o.run +
                           (imported ? " has no clog with an arch (clog_arches.csv is empty)"
                                     : " has no long-lasting arch (arches.csv is empty)"));
  const size_t n = std::min(recorded.arches.size(), static_cast<size_t>(o.max_arches));
  io::OutputLock lock(out);
  io::check_destination(out, o.force, "gallery", io::OutputKind::Sheet);

  // Tiles into a temporary directory beside the sheet, removed afterwards.
  fs::path tmp = out;
  tmp += ".tiles-" + std::to_string(::getpid());
  fs::create_directories(tmp);
  struct Cleanup {
    fs::path p;
    ~Cleanup() {
      std::error_code ec;
      fs::remove_all(p, ec);
    }
  } cleanup{tmp};

  LookOptions looks = o.looks;
  looks.inherit(run.metadata());
  const Look look = looks.resolve(model);
  render::Style style = look.style;
  const core::Geometry& geo = setup.geo;
  // The outlet camera of a square tile: the window each tile shows.
  const render::View view = render::layout_views(render::parse_camera("outlet"), geo, o.tile, o.tile).front();
  // Re-simulate the run, one frame one step before each recorded rule firing: the clog as it stood. Each tile
  // is the draw list of that frame as a table (vector shapes: the sheet draws them as circles, polygons and
  // paths in PDF and SVG alike), with the arch's descriptors (core::arch_descriptors) in the index.
  std::vector<long> at;
  for (size_t k = 0; k < n; ++k) at.push_back(std::lround(recorded.arches[k].t / scene.dt) - 1);
  // The re-simulation takes as long as the run did: say how far it has got (on a terminal, as run does).
  const double until = recorded.arches[n - 1].t + 0.5 * scene.dt;
  std::string index =
      "tile,t_s,clog_s,members,added,species,method,span_m,rise_m,aspect,theta_max_deg,defects,angle_sd_deg,"
      "window_m\n";
  size_t k = 0;
  FunctionSink tiles;
  tiles.forces = style.chains;
  auto make_tile = [&](core::Frame f) {
    const core::ArchEvent& a = recorded.arches[k];
    // The frame just before the rule fires: its clog is open, and its arch is the one the rule removes.
    f.arch = a.ids;
    f.clog_open = f.clog_arrested = true;
    f.since_last_exit = a.clog_duration;
    render::ArchStyle arch;
    arch.halo_m = arch.bond_m = 0.012 * geo.grain_diameter / 0.13;
    const render::DrawList list = render::build_draw_list(f, geo, style, arch);
    const double half = 0.5 * view.cam.height;
    char name[32];
    std::snprintf(name, sizeof name, "tile_%03zu.csv", k);
    io::write_file_atomic(tmp / name,
                          render::draw_list_csv(list, view.cam.cx, view.cam.cy, view.cam.angle, half, half));
    index += tile_row(name, a, f, names, 2 * half);
    ++k;
  };
  tiles.on_frame = [&](const FrameTick& tick) { make_tile(tick.frames[0]); };
  if (imported) {
    for (size_t i = 0; i < n; ++i) make_tile(run.trajectory().frame(traj_frame[i]));
  } else {
    // The re-simulation must give the recorded arches: the same physics, build and seed (resimulate checks).
    resimulate(run, until, FrameClock::at_steps(at), {&tiles}, "gallery: re-simulating");
  }
  io::write_file_atomic(tmp / "index.csv", index);
  io::write_file_atomic(tmp / "key.tsv", sheet_key(names, style, geo.grain_diameter));
  const std::string title = sheet_title(run, imported, n, recorded.arches.size(), style);
  fs::path partial = out;
  partial += ".partial" + ext;  // matplotlib picks the format from the extension
  const int status =
      run_python(script_path("gallery.py"),
                 {tmp.string(), partial.string(), title, io::version_string(), std::to_string(o.columns),
                  std::to_string(o.tile), imported ? kImportedCaption : "", look.figure_spec(width_pt)});
  if (status != 0) {
    std::error_code ec;
    fs::remove(partial, ec);
    throw core::RuntimeFault("gallery: the matplotlib script gallery.py failed");
  }
  io::place_output(partial, out);
  std::printf("%zu arches -> %s\n", n, out.c_str());
  return 0;
}
}  // namespace

void define_gallery_command(CLI::App& command, Action& action) {
  auto o = std::make_shared<GalleryOptions>();
  CLI::App* cmd = &command;
  cmd->add_option("run", o->run, "a run or recording directory (metadata.toml, arches.csv)")->required();
  cmd->add_option("--out", o->out, "the sheet: .pdf, .svg or .png")->required();
  cmd->add_option("--tile", o->tile, "tile size in pixels of a PNG sheet (PDF and SVG are vector)")
      ->check(whole_number(120, 2000))
      ->capture_default_str();
  cmd->add_option("--columns", o->columns, "tiles per row (0: about square)")->check(whole_number(0, 20));
  cmd->add_option("--max", o->max_arches, "at most this many arches, the first ones")
      ->check(whole_number(1, 1000))
      ->capture_default_str();
  o->looks.add_to(*cmd);
  o->width.add_to(*cmd);
  cmd->add_flag("--force", o->force, "replace an earlier gallery sheet");
  cmd->callback([o, &action] { action = [o] { return gallery(*o); }; });
}

}  // namespace app
