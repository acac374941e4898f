// siloscope inspect DIR: step through a recorded run frame by frame, in a window or from a script off-screen.
// siloscope live SCENE: the simulation running in a window, with a panel to change the scene and restart.
// (frame and filmstrip, pictures of a run made the inspector's way: cmd_frame.cpp.)
#include <unistd.h>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <sstream>

#include <toml++/toml.h>

#include "app/services/branch.h"
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

struct InspectOptions {
  std::string path, script, size = "1280x720", screenshot;
  int frames = 0;
  bool quiet = false;
  LookOptions looks;  // the recording's own look unless given
};

struct LiveOptions {
  SceneOptions scene;
  std::string size = "1280x720", screenshot;
  int frames = 0;
  LookOptions looks;
};

int inspect(const InspectOptions& o) {
  const auto t0 = std::chrono::steady_clock::now();
  const io::Run run = io::Run::open(o.path, "inspect", io::Run::kTrajectory);
  const io::Trajectory& traj = run.trajectory();
  const core::Model& model = run.model();
  // The contacts beside the trajectory, when the run kept them (recordings do): force chains.
  if (const io::Contacts* contacts = run.contacts(); contacts && contacts->size() != traj.size() && !o.quiet)
    std::fprintf(stderr, "siloscope: %s holds %ld frames of the trajectory's %ld; later frames have none\n",
                 run.file(io::run_file::kContacts).c_str(), contacts->size(), traj.size());
  const TrajectoryFrames frames(run);
  const RecordFiles files;
  ui::Inspector insp(frames, model, &files);
  const RunBrancher brancher(run);  // "what if": the run re-simulated from a frame
  if (!run.imported()) insp.set_brancher(&brancher);
  title_imported(insp, run);
  apply_look(insp, o.looks, run);
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

int live(const LiveOptions& o) {
  const core::Model model = o.scene.compile();
  ui::WindowOptions w;
  render::parse_size(o.size, "--size", w.width, w.height, 320, 240);
  w.screenshot = o.screenshot;
  w.frames = o.frames > 0 ? o.frames : (o.screenshot.empty() ? 0 : 3);
  const RecordFiles files;
  w.files = &files;
  const Look look = o.looks.resolve(model);
  w.style = look.style;
  w.overlay = look.overlay;
  LiveSilo source(model);
  source.species_colors = look.species_colors;
  ui::run_live_window(source, w);
  return 0;
}
}  // namespace

void define_inspect_command(CLI::App& command, Action& action) {
  auto o = std::make_shared<InspectOptions>();
  CLI::App* cmd = &command;
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
  o->looks.add_to(*cmd);
  cmd->callback([o, &action] { action = [o] { return inspect(*o); }; });
}

void define_live_command(CLI::App& command, Action& action) {
  auto l = std::make_shared<LiveOptions>();
  CLI::App* lc = &command;
  l->scene.add_to(*lc);
  lc->add_option("--size", l->size, "window size")->capture_default_str();
  lc->add_option("--screenshot", l->screenshot,
                 "save the window's pixels to PNG after --frames frames, then close");
  lc->add_option("--frames", l->frames, "close the window after N frames")->check(whole_number(0, 100000000));
  l->looks.add_to(*lc);
  lc->callback([l, &action] { action = [l] { return live(*l); }; });
}

}  // namespace app
