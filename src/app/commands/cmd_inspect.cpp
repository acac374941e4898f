// siloscope inspect DIR: step through a recorded run frame by frame, in a window or from a script off-screen.
// siloscope live SCENE: the simulation running in a window, with a panel to change the scene and restart.
#include <unistd.h>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <sstream>

#include <toml++/toml.h>

#include "app/services/cli.h"
#include "app/services/inspect_files.h"
#include "app/services/live_silo.h"
#include "app/services/process.h"
#include "app/services/run_outputs.h"
#include "app/services/session.h"
#include "app/services/sinks.h"
#include "app/services/terminal.h"
#include "core/error.h"
#include "core/format.h"
#include "core/physics.h"
#include "io/events_csv.h"
#include "io/manifest.h"
#include "io/metadata.h"
#include "io/output.h"
#include "io/trajectory.h"
#include "render/camera.h"
#include "render/context.h"
#include "render/overlay.h"
#include "sim/silo.h"
#include "ui/inspector.h"
#include "ui/window.h"

namespace app {

namespace {
namespace fs = std::filesystem;

struct InspectOptions {
  std::string path, script, size = "1280x720", screenshot;
  int frames = 0;
  bool quiet = false;
};

struct LiveOptions {
  SceneOptions scene;
  std::string size = "1280x720", screenshot;
  int frames = 0;
};

fs::path trajectory_path(const std::string& p) {
  fs::path path = p;
  if (fs::is_directory(path)) path /= "trajectory.sstraj";
  if (!fs::exists(path))
    throw core::InputError(
        p + ": no trajectory here (record writes one; run writes one with --trajectory-fps 30)");
  return path;
}

// An imported lab run (siloscope import) is named as such in the information box, not by the geometry scene's
// r, chi and mu (which it was not made with).
void title_imported(ui::Inspector& insp, const io::Trajectory& traj) {
  toml::table t;
  try {
    t = toml::parse(traj.info().metadata);
  } catch (const toml::parse_error&) {
    return;
  }
  if (!t["run"]["imported"].value_or(false)) return;
  insp.overlay_data.title =
      "imported: " + fs::path(t["run"]["imported_from"].value_or(std::string())).filename().string() +
      " (contacts: gap <= " + core::format_g(t["run"]["contact_tolerance"].value_or(0.0), 3) + " d)";
}

int inspect(const InspectOptions& o) {
  const auto t0 = std::chrono::steady_clock::now();
  io::Trajectory traj(trajectory_path(o.path));
  // The scene the run was made with, compiled once from the trajectory's own metadata.
  const core::Model& model = run_model(traj, o.path);
  // The contacts beside the trajectory, when the run kept them (recordings do): force chains in the
  // inspector.
  std::unique_ptr<io::Contacts> contacts;
  const fs::path contacts_path = trajectory_path(o.path).parent_path() / "contacts.sscon";
  if (fs::exists(contacts_path)) {
    contacts = std::make_unique<io::Contacts>(contacts_path, traj.info().n_particles);
    if (contacts->size() != traj.size() && !o.quiet)
      std::fprintf(stderr, "siloscope: %s holds %ld frames of the trajectory's %ld; later frames have none\n",
                   contacts_path.c_str(), contacts->size(), traj.size());
  }
  const TrajectoryFrames frames(traj, contacts.get());
  const RecordFiles files;
  ui::Inspector insp(frames, model, &files);
  title_imported(insp, traj);
  const double open_ms = 1e3 * std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!o.quiet)
    std::fprintf(stderr, "trajectory: %ld frames%s, %zu clogs, opened in %.0f ms\n", traj.size(),
                 traj.truncated() ? " (cut off: a partial last frame was dropped)" : "", insp.clogs().size(),
                 open_ms);
  if (!o.script.empty()) {
    render::OffscreenContext ctx;
    if (!o.quiet) std::fprintf(stderr, "siloscope: OpenGL %s\n", ctx.description().c_str());
    ui::Painter painter;
    const int n = ui::run_script(insp, painter, o.script);
    if (!o.quiet) std::fprintf(stderr, "script: %d commands done\n", n);
    return 0;
  }
  ui::WindowOptions w;
  render::parse_size(o.size, "--size", w.width, w.height, 320, 240);
  w.screenshot = o.screenshot;
  w.frames = o.frames > 0 ? o.frames : (o.screenshot.empty() ? 0 : 3);
  w.files = &files;
  w.source_name = o.path;
  const double redraw = ui::run_inspector_window(insp, w);
  if (!o.quiet && redraw > 0) std::fprintf(stderr, "median redraw after a frame change: %.1f ms\n", redraw);
  return 0;
}

struct FrameOptions {
  std::string path, at, size = "3840x2160", out, camera = "split", color = "species", overlay = "all";
};

// siloscope frame RUN --at ...: one picture of a recorded run at an event, as the inspector's script makes it
// (the same lines: zoom, color, overlay, goto, snapshot), so a figure for a talk is one command.
// A run written without a trajectory (run without --trajectory-fps) is simulated again from its metadata
// (runs are deterministic), as far as --at needs, at 30 frames a second, into `tmp`; the re-simulation must
// give the run's own exits up to there. Progress on a terminal.
fs::path resimulate_for_frame(const fs::path& run, const std::string& kind, const std::string& value,
                              const fs::path& tmp) {
  for (const char* f : {"metadata.toml", "exits.csv", "clogs.csv", "arches.csv"})
    if (fs::exists(run / f)) io::verify_listed(run / f, "frame: run");
  const core::Model model = core::compile(core::load_scene((run / "metadata.toml").string()));
  const core::Events ev = io::read_events(run, model.setup.species_names());
  char* end = nullptr;
  const double v = std::strtod(value.c_str(), &end);
  if (value.empty() || *end || !std::isfinite(v) || v < 0)
    throw core::InputError("--at " + kind + ":" + value + ": expected clog:K, rule:K, t:SECONDS or frame:N");
  double until = 0;
  if (kind == "clog") {
    if (v < 1 || v > static_cast<double>(ev.clogs.size()) || v != std::floor(v))
      throw core::InputError("--at clog:" + value + ": the run has " + std::to_string(ev.clogs.size()) +
                             " clogs (numbered from 1)");
    until = ev.clogs[static_cast<size_t>(v) - 1].end + 0.2;
  } else if (kind == "rule") {
    if (v < 1 || v > static_cast<double>(ev.arches.size()) || v != std::floor(v))
      throw core::InputError("--at rule:" + value + ": the run has " + std::to_string(ev.arches.size()) +
                             " long-lasting arches (numbered from 1)");
    until = ev.arches[static_cast<size_t>(v) - 1].t + 0.1;
  } else {
    until = (kind == "frame" ? (v + 1) / 30.0 : v) + 0.1;
  }
  const double stop = std::min(model.scene.duration, until);
  const FrameClock clock = FrameClock::every(model.scene.dt, 1.0 / 30, "frame");
  fs::create_directories(tmp);
  Session session({model});
  io::RunInfo info{command_line(), {}, {}};
  TrajectorySink sink(tmp / "trajectory.sstraj", trajectory_info(session.world(0), clock.frame_interval,
                                                                 io::metadata_toml(model, info)));
  Progress progress("frame: re-simulating the run (it has no trajectory)", stop, true);
  session.run(stop, clock, {&sink}, {}, [&](double t) { progress.update(t); });
  session.finish({&sink});
  sink.close();
  progress.finish();
  const auto& again = session.world(0).events().exits;
  for (size_t k = 0; k < again.size() && k < ev.exits.size(); ++k)
    if (again[k].id != ev.exits[k].id || std::fabs(again[k].t - ev.exits[k].t) > 1e-6)
      throw core::RuntimeFault("frame: re-simulating " + run.string() + " did not give its exits (exit " +
                               std::to_string(k + 1) + "): a different build or physics?");
  return tmp / "trajectory.sstraj";
}

int frame(const FrameOptions& o) {
  // --at: clog:K (where clog K's final arch first stands), rule:K (the K-th long-lasting arch, the frame
  // before the rule removed it), t:SECONDS or frame:N.
  const size_t colon = o.at.find(':');
  const std::string kind = o.at.substr(0, colon),
                    value = colon == std::string::npos ? "" : o.at.substr(colon + 1);
  std::string go;
  if (kind == "clog" && !value.empty())
    go = "goto clog " + value + " arch";
  else if (kind == "rule" && !value.empty())
    go = "goto arch " + value;
  else if (kind == "t" && !value.empty())
    go = "goto time " + value;
  else if (kind == "frame" && !value.empty())
    go = "goto frame " + value;
  else
    throw core::InputError("--at " + o.at + ": expected clog:K, rule:K, t:SECONDS or frame:N");
  const std::string ext = fs::path(o.out).extension().string();
  if (ext != ".png" && ext != ".svg" && ext != ".pdf")
    throw core::InputError("--out " + o.out + ": the frame is .png, .svg or .pdf");
  // A run without a trajectory is simulated again into a temporary directory beside the output.
  struct Cleanup {
    fs::path p;
    ~Cleanup() {
      std::error_code ec;
      if (!p.empty()) fs::remove_all(p, ec);
    }
  } cleanup;
  fs::path source = o.path;
  if (fs::is_directory(source) && !fs::exists(source / "trajectory.sstraj") &&
      fs::exists(source / "metadata.toml")) {
    cleanup.p = fs::absolute(fs::path(o.out)).parent_path() / (".frame-resim-" + std::to_string(::getpid()));
    source = resimulate_for_frame(o.path, kind, value, cleanup.p);
  }
  io::Trajectory traj(trajectory_path(source.string()));
  const core::Model& model = run_model(traj, source.string());
  std::unique_ptr<io::Contacts> contacts;
  const fs::path contacts_path = trajectory_path(source.string()).parent_path() / "contacts.sscon";
  if (fs::exists(contacts_path))
    contacts = std::make_unique<io::Contacts>(contacts_path, traj.info().n_particles);
  const TrajectoryFrames frames(traj, contacts.get());
  const RecordFiles files;
  ui::Inspector insp(frames, model, &files);
  title_imported(insp, traj);
  int w = 0, h = 0;
  render::parse_size(o.size, "--size", w, h, 64, 64);
  render::OffscreenContext ctx;
  ui::Painter painter;
  for (const std::string& line : {"zoom " + o.camera, "color " + o.color, "overlay " + o.overlay, go}) {
    try {
      insp.execute(line, &painter);
    } catch (const core::InputError& e) {
      // Name the option the line came from, not the script line.
      const std::string opt = line.rfind("zoom", 0) == 0      ? "--camera"
                              : line.rfind("color", 0) == 0   ? "--color"
                              : line.rfind("overlay", 0) == 0 ? "--overlay"
                                                              : "--at";
      throw core::InputError(opt + ": " + e.what());
    }
  }
  const std::string written = insp.snapshot(o.out, w, h, &painter);
  std::printf("%s at frame %ld (t = %.3f s) -> %s\n", o.at.c_str(), insp.frame_index(),
              insp.trajectory().time(insp.frame_index()), written.c_str());
  return 0;
}

struct FilmstripOptions {
  std::string path, out, times = "-1,-0.5,0,2", camera = "outlet", color = "species";
  long clog = 1;
  bool force = false;
};

// siloscope filmstrip RECORDING --clog K --times ...: clog K at several times from its start (s), one row of
// vector tiles on one colour scale, each captioned with its time; drawn by the gallery's sheet script.
int filmstrip(const FilmstripOptions& o) {
  io::Trajectory traj(trajectory_path(o.path));
  const core::Model& model = run_model(traj, o.path);
  const TrajectoryFrames frames(traj);
  const RecordFiles files;
  ui::Inspector insp(frames, model, &files);
  title_imported(insp, traj);
  if (o.clog < 1 || o.clog > static_cast<long>(insp.clogs().size()))
    throw core::InputError("--clog " + std::to_string(o.clog) + ": the recording has " +
                           std::to_string(insp.clogs().size()) + " clogs (numbered from 1)");
  std::vector<double> dts;
  {
    std::stringstream ss(o.times);
    for (std::string item; std::getline(ss, item, ',');) {
      char* end = nullptr;
      const double v = std::strtod(item.c_str(), &end);
      if (item.empty() || *end || !std::isfinite(v))
        throw core::InputError("--times " + o.times + ": '" + item +
                               "' is not a number of seconds from the clog's start (e.g. -1,-0.5,0,+2)");
      dts.push_back(v);
    }
  }
  if (dts.empty() || dts.size() > 12) throw core::InputError("--times " + o.times + ": give 1 to 12 times");
  const fs::path out = io::output_path(o.out);
  const std::string ext = out.extension().string();
  if (ext != ".pdf" && ext != ".svg" && ext != ".png")
    throw core::InputError("--out " + o.out + ": the filmstrip is .pdf, .svg or .png");
  for (const std::string& line : {"zoom " + o.camera, "color " + o.color}) {
    try {
      insp.execute(line);
    } catch (const core::InputError& e) {
      throw core::InputError((line[0] == 'z' ? std::string("--camera: ") : std::string("--color: ")) +
                             e.what());
    }
  }
  const double start = insp.clogs()[static_cast<size_t>(o.clog - 1)].event.start;
  io::OutputLock lock(out);
  io::check_destination(out, o.force, "filmstrip", io::OutputKind::Sheet);
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
  std::string index = "tile,t_s,window_m,label\n";
  std::string scale;
  for (size_t k = 0; k < dts.size(); ++k) {
    const double t = start + dts[k];
    try {
      insp.goto_time(t);
    } catch (const core::InputError& e) {
      throw core::InputError("--times: " + core::format_g(dts[k], 6) + " s from clog " +
                             std::to_string(o.clog) + "'s start: " + e.what());
    }
    double w = 0, h = 0;
    std::string caption;
    const std::string table = insp.vector_table(1000, 1000, w, h, caption);
    const std::string name = "tile_" + std::to_string(k) + ".csv";
    io::write_file_atomic(tmp / name, table);
    const core::Frame f = insp.current();
    // Before the clog: flowing; from its start (its last exit) on: the time without an exit, and the arch
    // once the clog is open.
    char label[200];
    const std::string clog_no = f.clog_number > 0 ? " (clog " + std::to_string(f.clog_number) + ")" : "";
    const std::string state =
        f.clog_open
            ? (f.arch.empty() ? "clogged" + clog_no + ", no arch found yet"
                              : "clogged" + clog_no + ": a " + std::to_string(f.arch.size()) + "-grain arch")
        : t < start - 1e-9 ? "flowing"
                           : "no exit for " + core::format_g(f.since_last_exit, 2) + " s";
    std::snprintf(label, sizeof label, "%+g s (t = %.2f s)\\n%s", dts[k], f.t, state.c_str());
    index += name + "," + core::format_g(f.t, 9) + "," + core::format_g(w, 9) + ",\"" + label + "\"\n";
    const size_t nl = caption.find("\ncolour: ");
    if (nl != std::string::npos) scale = caption.substr(nl + 1);
  }
  io::write_file_atomic(tmp / "index.csv", index);
  const std::string title = "clog " + std::to_string(o.clog) + " of " +
                            fs::absolute(o.path).filename().string() + ", starting at " +
                            core::format_g(start, 6) + " s" + (scale.empty() ? "" : "; " + scale);
  fs::path partial = out;
  partial += ".partial" + ext;
  const int status = run_python(
      script_path("gallery.py"),
      {tmp.string(), partial.string(), title, io::version_string(), std::to_string(dts.size()), "480",
       "each tile the view at its time from the clog's start (clogs.csv's start_s, its last exit); a "
       "clog is open once no grain has left for clog_min_gap; arches ringed, bonds dark; one colour "
       "scale for every tile"});
  if (status != 0) {
    std::error_code ec;
    fs::remove(partial, ec);
    throw core::RuntimeFault("filmstrip: the matplotlib script gallery.py failed");
  }
  io::rename_into_place(partial, out);
  io::record_output(out);
  std::printf("clog %ld at %zu times -> %s\n", o.clog, dts.size(), out.c_str());
  return 0;
}

int live(const LiveOptions& o) {
  const core::Model model = o.scene.compile();
  ui::WindowOptions w;
  render::parse_size(o.size, "--size", w.width, w.height, 320, 240);
  w.screenshot = o.screenshot;
  w.frames = o.frames > 0 ? o.frames : (o.screenshot.empty() ? 0 : 3);
  const RecordFiles files;
  w.files = &files;
  LiveSilo source(model);
  ui::run_live_window(source, w);
  return 0;
}
}  // namespace

void add_inspect_command(CLI::App& app, Action& action) {
  auto o = std::make_shared<InspectOptions>();
  auto* cmd = app.add_subcommand(
      "inspect", "step through a recorded run frame by frame (window, or --script off-screen)");
  cmd->set_version_flag("--version", io::version_string());
  cmd->add_option("run", o->path, "a run or recording directory (with trajectory.sstraj), or the file")
      ->required();
  cmd->add_option("--script", o->script,
                  "run inspector commands from FILE off-screen, no window (see docs/inspector.md)");
  cmd->add_option("--size", o->size, "window size")->capture_default_str();
  cmd->add_option("--screenshot", o->screenshot,
                  "save the window's pixels to PNG after --frames frames, then close");
  cmd->add_option("--frames", o->frames, "close the window after N frames (stepping one frame each)")
      ->check(whole_number(0, 100000000));
  cmd->add_flag("--quiet", o->quiet, "print nothing but errors");
  cmd->callback([o, &action] { action = [o] { return inspect(*o); }; });

  auto fo = std::make_shared<FrameOptions>();
  auto* fc = app.add_subcommand(
      "frame",
      "one high-resolution picture of a recorded run at a clog, a rule removal or a time (PNG, SVG, PDF)");
  fc->set_version_flag("--version", io::version_string());
  fc->add_option("run", fo->path,
                 "a recording, or any run (one without a trajectory is simulated again from its metadata, as "
                 "far as --at needs)")
      ->required();
  fc->add_option("--at", fo->at,
                 "clog:K (where clog K's final arch first stands), rule:K (the K-th long-lasting arch just "
                 "before the rule removed it), t:SECONDS or frame:N")
      ->required();
  fc->add_option("--out", fo->out, "F.png, F.svg or F.pdf ({frame} and {t} are filled in; never over a file)")
      ->required();
  fc->add_option("--size", fo->size, "picture size")->capture_default_str();
  fc->add_option("--camera", fo->camera, "split, outlet, hopper or window:X0,Y0,X1,Y1")
      ->capture_default_str();
  fc->add_option("--color", fo->color, "species, speed, force, displacement, coordination or id [range]")
      ->capture_default_str();
  fc->add_option("--overlay", fo->overlay, "as record's --overlay")->capture_default_str();
  fc->callback([fo, &action] { action = [fo] { return frame(*fo); }; });

  auto fs_o = std::make_shared<FilmstripOptions>();
  auto* fsc =
      app.add_subcommand("filmstrip",
                         "one clog of a recording at several times, one row of tiles on one colour scale "
                         "(PDF, SVG: vector; PNG)");
  fsc->set_version_flag("--version", io::version_string());
  fsc->add_option("run", fs_o->path, "a recording (or a run written with --trajectory-fps)")->required();
  fsc->add_option("--clog", fs_o->clog, "which clog (clogs.csv's row K)")->capture_default_str();
  fsc->add_option("--times", fs_o->times, "seconds from the clog's start, comma-separated")
      ->capture_default_str();
  fsc->add_option("--out", fs_o->out, "F.pdf, F.svg or F.png")->required();
  fsc->add_option("--camera", fs_o->camera, "outlet, hopper or window:X0,Y0,X1,Y1")->capture_default_str();
  fsc->add_option("--color", fs_o->color, "species, speed, force, displacement, coordination or id [range]")
      ->capture_default_str();
  fsc->add_flag("--force", fs_o->force, "replace an earlier filmstrip or gallery sheet");
  fsc->callback([fs_o, &action] { action = [fs_o] { return filmstrip(*fs_o); }; });

  auto l = std::make_shared<LiveOptions>();
  auto* lc = app.add_subcommand(
      "live", "the simulation running in a window, with a panel to change mu, r, chi, kicks");
  lc->set_version_flag("--version", io::version_string());
  l->scene.add_to(*lc);
  lc->add_option("--size", l->size, "window size")->capture_default_str();
  lc->add_option("--screenshot", l->screenshot,
                 "save the window's pixels to PNG after --frames frames, then close");
  lc->add_option("--frames", l->frames, "close the window after N frames")->check(whole_number(0, 100000000));
  lc->callback([l, &action] { action = [l] { return live(*l); }; });
}

}  // namespace app
