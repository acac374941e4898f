// siloscope frame RUN --at ...: one picture of a run at an event; siloscope filmstrip RECORDING --clog K: one
// clog at several times, a row of tiles. Both are drawn the inspector's way (the same commands, the run's own
// look unless told otherwise).
#include <unistd.h>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <sstream>

#include <toml++/toml.h>

#include "app/services/cli.h"
#include "app/services/inspect_files.h"
#include "app/services/live_silo.h"
#include "app/services/looks.h"
#include "app/services/process.h"
#include "app/services/replay.h"
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

struct FrameOptions {
  std::string path, at, size = "3840x2160", out, camera = "split";
  LookOptions looks;  // the recording's own look unless given
  FigureWidth width;  // .svg and .pdf: a journal's column
};

// siloscope frame RUN --at ...: one picture of a recorded run at an event, as the inspector's script makes it
// (the same lines: zoom, color, overlay, goto, snapshot), so a figure for a talk is one command.
// A run written without a trajectory (run without --trajectory-fps) is simulated again from its metadata
// (runs are deterministic), as far as --at needs, at 30 frames a second, into `tmp`; the re-simulation must
// give the run's own exits up to there. Progress on a terminal.
fs::path resimulate_for_frame(const io::Run& run, const std::string& kind, const std::string& value,
                              const fs::path& tmp) {
  const core::Model& model = run.model();
  const core::Events& ev = run.events();
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
  const fs::path path = tmp / io::run_file::kTrajectory;
  io::RunInfo info{command_line(), {}, {}, {}};
  std::unique_ptr<TrajectorySink> sink;
  resimulate(
      run, stop, clock,
      [&](const sim::Silo& world) -> std::vector<Sink*> {
        sink = std::make_unique<TrajectorySink>(
            path, trajectory_info(world, clock.frame_interval, io::metadata_toml(model, info)));
        return {sink.get()};
      },
      "frame: re-simulating the run (it has no trajectory)");
  sink->close();
  return path;
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
  const double width_pt = o.width.points();
  if (width_pt > 0 && ext == ".png")
    throw core::InputError("--width " + o.width.given +
                           ": a page width is for a vector figure (--out F.pdf or F.svg); a .png is --size "
                           "pixels");
  // A run without a trajectory is simulated again into a temporary directory beside the output.
  struct Cleanup {
    fs::path p;
    ~Cleanup() {
      std::error_code ec;
      if (!p.empty()) fs::remove_all(p, ec);
    }
  } cleanup;
  const io::Run run = io::Run::open(o.path, "frame");
  std::optional<io::Run> resimulated;
  if (!run.has_trajectory()) {
    cleanup.p = fs::absolute(fs::path(o.out)).parent_path() / (".frame-resim-" + std::to_string(::getpid()));
    resimulated = io::Run::open(resimulate_for_frame(run, kind, value, cleanup.p), "frame");
  }
  const io::Run& source = resimulated ? *resimulated : run;
  const TrajectoryFrames frames(source);
  RecordFiles files;
  files.figure_width_pt = width_pt;
  ui::Inspector insp(frames, run.model(), &files);
  title_imported(insp, run);
  int w = 0, h = 0;
  render::parse_size(o.size, "--size", w, h, 64, 64);
  render::OffscreenContext ctx;
  ui::Painter painter;
  apply_look(insp, o.looks, run);
  for (const std::string& line : {"zoom " + o.camera, go}) {
    try {
      insp.execute(line, &painter);
    } catch (const core::InputError& e) {
      // Name the option the line came from, not the script line.
      throw core::InputError((line.rfind("zoom", 0) == 0 ? "--camera: " : "--at: ") + std::string(e.what()));
    }
  }
  std::string written;
  try {
    written = insp.snapshot(o.out, w, h, &painter);
  } catch (const core::InputError& e) {
    throw core::InputError("--out " + o.out + ": " + e.what());
  }
  std::printf("%s at frame %ld (t = %.3f s) -> %s\n", o.at.c_str(), insp.frame_index(),
              insp.trajectory().time(insp.frame_index()), written.c_str());
  return 0;
}

struct FilmstripOptions {
  std::string path, out, times = "-1,-0.5,0,2", camera = "outlet";
  long clog = 1;
  bool force = false;
  LookOptions looks;  // the recording's own look unless given
  FigureWidth width;
};

// siloscope filmstrip RECORDING --clog K --times ...: clog K at several times from its start (s), one row of
// vector tiles on one colour scale, each captioned with its time; drawn by the gallery's sheet script.
int filmstrip(const FilmstripOptions& o) {
  const io::Run run = io::Run::open(o.path, "filmstrip", io::Run::kTrajectory);
  const TrajectoryFrames frames(run);
  const RecordFiles files;
  ui::Inspector insp(frames, run.model(), &files);
  title_imported(insp, run);
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
  const double width_pt = o.width.points();
  const fs::path out = io::output_path(o.out);
  const std::string ext = out.extension().string();
  if (ext != ".pdf" && ext != ".svg" && ext != ".png")
    throw core::InputError("--out " + o.out + ": the filmstrip is .pdf, .svg or .png");
  const Look look = apply_look(insp, o.looks, run);
  try {
    insp.execute("zoom " + o.camera);
  } catch (const core::InputError& e) {
    throw core::InputError(std::string("--camera: ") + e.what());
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
  std::string scale, key;  // the key (legend, scale bar): a tile's with the arch where one shows it
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
    const std::string tile_key = insp.vector_key();
    if (key.empty() || tile_key.find("\narch\t") != std::string::npos) key = tile_key;
    const size_t nl = caption.find("\ncolour: ");
    if (nl != std::string::npos) scale = caption.substr(nl + 1);
  }
  io::write_file_atomic(tmp / "index.csv", index);
  io::write_file_atomic(tmp / "key.tsv", key);
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
       "scale for every tile",
       look.figure_spec(width_pt)});
  if (status != 0) {
    std::error_code ec;
    fs::remove(partial, ec);
    throw core::RuntimeFault("filmstrip: the matplotlib script gallery.py failed");
  }
  io::place_output(partial, out);
  std::printf("clog %ld at %zu times -> %s\n", o.clog, dts.size(), out.c_str());
  return 0;
}

}  // namespace

void define_frame_command(CLI::App& command, Action& action) {
  auto fo = std::make_shared<FrameOptions>();
  CLI::App* fc = &command;
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
  fo->looks.add_to(*fc);
  fo->width.add_to(*fc);
  fc->callback([fo, &action] { action = [fo] { return frame(*fo); }; });
}

void define_filmstrip_command(CLI::App& command, Action& action) {
  auto fs_o = std::make_shared<FilmstripOptions>();
  CLI::App* fsc = &command;
  fsc->add_option("run", fs_o->path, "a recording (or a run written with --trajectory-fps)")->required();
  fsc->add_option("--clog", fs_o->clog, "which clog (clogs.csv's row K)")->capture_default_str();
  fsc->add_option("--times", fs_o->times, "seconds from the clog's start, comma-separated")
      ->capture_default_str();
  fsc->add_option("--out", fs_o->out, "F.pdf, F.svg or F.png")->required();
  fsc->add_option("--camera", fs_o->camera, "outlet, hopper or window:X0,Y0,X1,Y1")->capture_default_str();
  fs_o->looks.add_to(*fsc);
  fs_o->width.add_to(*fsc);
  fsc->add_flag("--force", fs_o->force, "replace an earlier filmstrip or gallery sheet");
  fsc->callback([fs_o, &action] { action = [fs_o] { return filmstrip(*fs_o); }; });
}

}  // namespace app
