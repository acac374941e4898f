// siloscope inspect DIR: step through a recorded run frame by frame, in a window or from a script off-screen.
// siloscope live SCENE: the simulation running in a window, with a panel to change the scene and restart.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "app/services/cli.h"
#include "app/services/inspect_files.h"
#include "app/services/live_silo.h"
#include "app/services/process.h"
#include "app/services/run_outputs.h"
#include "app/services/session.h"
#include "app/services/terminal.h"
#include "core/error.h"
#include "core/physics.h"
#include "io/metadata.h"
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
int frame(const FrameOptions& o) {
  io::Trajectory traj(trajectory_path(o.path));
  const core::Model& model = run_model(traj, o.path);
  std::unique_ptr<io::Contacts> contacts;
  const fs::path contacts_path = trajectory_path(o.path).parent_path() / "contacts.sscon";
  if (fs::exists(contacts_path))
    contacts = std::make_unique<io::Contacts>(contacts_path, traj.info().n_particles);
  const TrajectoryFrames frames(traj, contacts.get());
  const RecordFiles files;
  ui::Inspector insp(frames, model, &files);
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
  fc->add_option("run", fo->path, "a recording (or a run written with --trajectory-fps)")->required();
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
