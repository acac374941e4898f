// siloscope timeline RUN --out F.pdf|svg|png: the run's discharge as a figure of its own: each species'
// cumulative exits against time (the staircase), every clog as a band coloured by how it ended, axis ticks
// and labels, a legend, the run named. Vector in PDF and SVG (text stays text); drawn by matplotlib
// (src/figures/timeline.py) from the run's own event files, read and checked here.
#include <cstdio>
#include <filesystem>

#include "app/services/cli.h"
#include "app/services/looks.h"
#include "app/services/process.h"
#include "core/error.h"
#include "core/format.h"
#include "core/model.h"
#include "io/metadata.h"
#include "io/output.h"
#include "io/run.h"
#include "render/overlay.h"
#include "render/palette.h"

namespace app {

namespace {
namespace fs = std::filesystem;

struct TimelineOptions {
  std::string run, out;
  double from = 0, to = -1;  // s; to < 0: the run's end
  bool force = false;
  LookOptions looks;  // the run's own look unless given: species' colours, background, text size
  FigureWidth width;  // a journal's column, or the figure's own size
};

int timeline(const TimelineOptions& o) {
  const io::Run run = io::Run::open(o.run, "timeline", io::Run::kEvents);
  const fs::path out = io::output_path(o.out);
  const std::string ext = out.extension().string();
  if (ext != ".pdf" && ext != ".svg" && ext != ".png")
    throw core::InputError("--out " + o.out + ": the figure is .pdf, .svg or .png");
  const double width_pt = o.width.points();
  // The run's own files, checked as analyze checks them (times in order, species known, clogs in range).
  const core::Model& model = run.model();
  const core::Events& ev = run.events();
  const double end = model.scene.duration;
  const double to = o.to < 0 ? end : o.to;
  if (!(o.from >= 0) || !(to > o.from) || to > end + 1e-9)
    throw core::InputError("--from " + core::format_g(o.from) + " --to " + core::format_g(to) +
                           ": expected 0 <= FROM < TO <= the run's duration (" + core::format_g(end) + " s)");
  io::check_not_input(
      out,
      {run.file(io::run_file::kExits), run.file(io::run_file::kClogs), run.file(io::run_file::kMetadata)},
      "figure");
  io::OutputLock lock(out);
  io::check_destination(out, o.force, "timeline", io::OutputKind::Sheet);
  fs::path partial = out;
  partial += ".partial" + ext;  // matplotlib picks the format from the extension
  // Each species in the colour the run's pictures give it, on their background and at their text size, so
  // that the figure and a frame beside it on a slide agree.
  LookOptions looks = o.looks;
  looks.inherit(run.metadata());
  const Look look = looks.resolve(model);
  const int status =
      run_python(script_path("timeline.py"),
                 {run.dir().string(), partial.string(), core::format_g(o.from, 9), core::format_g(to, 9),
                  io::version_string(), command_line(), look.species_hex(model), look.figure_spec(width_pt)});
  if (status != 0) {
    std::error_code ec;
    fs::remove(partial, ec);
    throw core::RuntimeFault("timeline: the matplotlib script timeline.py failed");
  }
  io::place_output(partial, out);
  std::printf("%zu exits, %zu clogs -> %s\n", ev.exits.size(), ev.clogs.size(), out.c_str());
  return 0;
}
}  // namespace

void define_timeline_command(CLI::App& command, Action& action) {
  auto o = std::make_shared<TimelineOptions>();
  CLI::App* cmd = &command;
  cmd->add_option("run", o->run, "a run or recording directory (metadata.toml, exits.csv, clogs.csv)")
      ->required();
  cmd->add_option("--out", o->out, "the figure: .pdf, .svg (vector, text as text) or .png")->required();
  cmd->add_option("--from", o->from, "start of the time axis, s")->capture_default_str();
  cmd->add_option("--to", o->to, "end of the time axis, s (default: the run's end)");
  cmd->add_flag("--force", o->force, "replace an earlier timeline or gallery figure of the same name");
  o->looks.add_to(*cmd);
  o->width.add_to(*cmd);
  cmd->callback([o, &action] { action = [o] { return timeline(*o); }; });
}

}  // namespace app
