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
#include "app/services/process.h"
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
#include "io/trajectory.h"
#include "render/camera.h"
#include "render/draw_list.h"
#include "render/overlay.h"
#include "sim/silo.h"

namespace app {

namespace {
namespace fs = std::filesystem;

struct GalleryOptions {
  std::string run, out, palette = "paper";
  std::string chains;  // --force-chains MIN[:MAX]: the contact network of each tile
  int tile = 480, columns = 0, max_arches = 60;
  bool force = false;
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

int gallery(const GalleryOptions& o) {
  const fs::path run = o.run;
  if (!fs::is_directory(run) || !fs::exists(run / "metadata.toml") || !fs::exists(run / "arches.csv"))
    throw core::InputError("gallery: " + o.run + " is not a run directory (metadata.toml and arches.csv)");
  const fs::path out = o.out;
  const std::string ext = out.extension().string();
  if (ext != ".pdf" && ext != ".svg" && ext != ".png")
    throw core::InputError("--out " + o.out + ": the sheet is .pdf, .svg or .png");
  if (o.tile < 120 || o.tile > 2000 || o.tile % 2)
    throw core::InputError("--tile " + std::to_string(o.tile) +
                           ": allowed are even sizes from 120 to 2000 pixels");
  // What the run's manifest lists must be as written (a cut or edited metadata.toml would re-simulate
  // another run).
  for (const char* f : {"metadata.toml", "exits.csv", "clogs.csv", "arches.csv"})
    if (fs::exists(run / f)) io::verify_listed(run / f, "gallery: run");
  // The run's scene compiled once: the re-simulation, the pictures and the species' names share it.
  const core::Model model = core::compile(core::load_scene((run / "metadata.toml").string()));
  const core::Scene& scene = model.scene;
  const core::Setup& setup = model.setup;
  const std::vector<std::string> names = setup.species_names();
  core::Events recorded = io::read_events(run, names);
  // A lab run (siloscope import) has no rule and nothing to re-simulate: its tiles are its clogs' arches, at
  // the frame of its trajectory the import took each from (clog_arches.csv).
  const bool imported = fs::exists(run / "clog_arches.csv") && fs::exists(run / "trajectory.sstraj");
  std::unique_ptr<io::Trajectory> traj;
  std::vector<long> traj_frame;
  if (imported) {
    for (const char* f : {"clog_arches.csv", "trajectory.sstraj"}) io::verify_listed(run / f, "gallery: run");
    traj = std::make_unique<io::Trajectory>(run / "trajectory.sstraj");
    const io::CsvTable rows =
        io::CsvTable::read((run / "clog_arches.csv").string(), "an imported run's clog arches");
    recorded.arches.clear();
    for (size_t r = 0; r < rows.rows(); ++r) {
      core::ArchEvent a;
      a.t = rows.num(r, "t_s");
      const double clog = rows.num(r, "clog");
      if (!(clog >= 1) || clog > static_cast<double>(recorded.clogs.size()))
        throw core::InputError((run / "clog_arches.csv").string() + ":" + std::to_string(r + 2) + ": clog " +
                               rows.text(r, "clog") + " is not a row of clogs.csv");
      a.clog_duration = a.t - recorded.clogs[static_cast<size_t>(clog) - 1].start;
      long k = 0;
      while (k + 1 < traj->size() && traj->time(k) < a.t - 1e-6) ++k;
      const core::Frame f = traj->frame(k);
      std::istringstream ids(rows.text(r, "ids"));
      for (int id; ids >> id;) {
        if (id < 0 || static_cast<size_t>(id) >= f.particles.size())
          throw core::InputError((run / "clog_arches.csv").string() + ":" + std::to_string(r + 2) +
                                 ": grain " + std::to_string(id) + " is not in the trajectory");
        a.ids.push_back(id);
        a.species.push_back(f.particles[static_cast<size_t>(id)].species);
      }
      std::vector<core::Vec2> pos;
      std::vector<double> radius;
      for (const auto& p : f.particles) pos.push_back({p.x, p.y}), radius.push_back(p.radius);
      a.geometry = core::arch_geometry(a.ids, pos, radius);
      recorded.arches.push_back(std::move(a));
      traj_frame.push_back(k);
    }
  }
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

  render::Style style;
  style.palette = for_flag("--palette", [&] { return render::parse_palette(o.palette); });
  if (!o.chains.empty()) render::set_chains(style, o.chains, "--force-chains");  // as record's
  const core::Geometry& geo = setup.geo;
  // The outlet camera of a square tile: the window each tile shows.
  const render::View view = render::layout_views(render::parse_camera("outlet"), geo, o.tile, o.tile).front();
  const render::OverlayData data = render::overlay_data_for(model);  // the species' colours
  style.species_colors = data.species_colors;
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
    for (size_t i = 0; i < n; ++i) make_tile(traj->frame(traj_frame[i]));
  } else {
    Progress progress("gallery: re-simulating", until, true);
    Session session({model});
    session.run(until, FrameClock::at_steps(at), {&tiles}, {}, [&](double t) {
      progress.update(t, std::to_string(k) + " of " + std::to_string(n) + " arches");
    });
    progress.finish();
    // The re-simulation must give the recorded arches: the same physics, build and seed.
    const auto& again = session.world(0).events().arches;
    for (size_t i = 0; i < n; ++i)
      if (again.size() <= i || again[i].ids != recorded.arches[i].ids)
        throw core::RuntimeFault("gallery: re-simulating " + o.run + " did not reproduce its arch " +
                                 std::to_string(i) + " at t = " + core::format_g(recorded.arches[i].t, 6) +
                                 " s (a different build or physics?)");
  }
  io::write_file_atomic(tmp / "index.csv", index);
  const std::string title =
      (imported ? "clogs' arches of the imported run " : "long-lasting arches of ") +
      fs::absolute(run).filename().string() + ": " +
      (imported ? std::string("from tracked particles, contacts by distance")
       : setup.shorthand
           ? "r = " + core::format_g(scene.size_ratio) + ", chi = " + core::format_g(scene.chi) +
                 ", mu = " + core::format_g(scene.mu) + " A m^2, kick " +
                 core::format_g(scene.kick_impulse_max) + " N s, seed " + std::to_string(scene.seed)
           : data.title) +
      " (" + std::to_string(n) + " of " + std::to_string(recorded.arches.size()) + ")" +
      (style.chains ? "; force chains from " + core::format_g(style.chain_min, 4) + " N, viridis to " +
                          core::format_g(style.chain_max, 4) + " N"
                    : "");
  fs::path partial = out;
  partial += ".partial" + ext;  // matplotlib picks the format from the extension
  const int status = run_python(
      script_path("gallery.py"),
      imported ? std::vector<std::string>{tmp.string(), partial.string(), title, io::version_string(),
                                          std::to_string(o.columns), std::to_string(o.tile),
                                          "members ringed, bonds dark; each clog's arch at the last frame "
                                          "it stood, found from positions (contacts by distance, import's "
                                          "--contact-tolerance); h/(s/2): rise over half the span; "
                                          "\u03b8max: the largest bead angle; defects: bead angles above "
                                          "180\u00b0"}
               : std::vector<std::string>{tmp.string(), partial.string(), title, io::version_string(),
                                          std::to_string(o.columns), std::to_string(o.tile)});
  if (status != 0) {
    std::error_code ec;
    fs::remove(partial, ec);
    throw core::RuntimeFault("gallery: the matplotlib script gallery.py failed");
  }
  io::rename_into_place(partial, out);
  io::record_output(out);
  std::printf("%zu arches -> %s\n", n, out.c_str());
  return 0;
}
}  // namespace

void add_gallery_command(CLI::App& app, Action& action) {
  auto o = std::make_shared<GalleryOptions>();
  auto* cmd =
      app.add_subcommand("gallery", "one sheet (PDF, SVG or PNG) with every long-lasting arch of a run");
  cmd->set_version_flag("--version", io::version_string());
  cmd->add_option("run", o->run, "a run or recording directory (metadata.toml, arches.csv)")->required();
  cmd->add_option("--out", o->out, "the sheet: .pdf, .svg or .png")->required();
  cmd->add_option("--tile", o->tile, "tile size in pixels of a PNG sheet (PDF and SVG are vector)")
      ->check(whole_number(120, 2000))
      ->capture_default_str();
  cmd->add_option("--columns", o->columns, "tiles per row (0: about square)")->check(whole_number(0, 20));
  cmd->add_option("--max", o->max_arches, "at most this many arches, the first ones")
      ->check(whole_number(1, 1000))
      ->capture_default_str();
  cmd->add_option("--palette", o->palette, "paper or colorblind")->capture_default_str();
  cmd->add_option(
      "--force-chains", o->chains,
      "draw each tile's contact network: pairs with a normal force of at least MIN newtons, width and "
      "colour growing up to MAX (MIN or MIN:MAX)");
  cmd->add_flag("--force", o->force, "replace an earlier gallery sheet");
  cmd->callback([o, &action] { action = [o] { return gallery(*o); }; });
}

}  // namespace app
