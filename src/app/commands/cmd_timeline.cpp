// siloscope timeline RUN --out F.pdf|svg|png: the run's discharge as a figure of its own: each species'
// cumulative exits against time (the staircase), every clog as a band coloured by how it ended, axis ticks
// and labels, a legend, the run named. Vector in PDF and SVG (text stays text); drawn by matplotlib
// (src/figures/timeline.py) from the run's own event files, read and checked here.
#include <cstdio>
#include <filesystem>

#include "app/services/cli.h"
#include "app/services/process.h"
#include "core/error.h"
#include "core/format.h"
#include "core/model.h"
#include "io/events_csv.h"
#include "io/manifest.h"
#include "io/metadata.h"
#include "io/output.h"
#include "render/overlay.h"
#include "render/palette.h"

namespace app {

namespace {
namespace fs = std::filesystem;

struct TimelineOptions {
  std::string run, out;
  double from = 0, to = -1;  // s; to < 0: the run's end
  bool force = false;
};

int timeline(const TimelineOptions& o) {
  const fs::path run = o.run;
  if (!fs::is_directory(run) || !fs::exists(run / "metadata.toml") || !fs::exists(run / "exits.csv") ||
      !fs::exists(run / "clogs.csv"))
    throw core::InputError("timeline: " + o.run +
                           " is not a run directory (metadata.toml, exits.csv and clogs.csv)");
  const fs::path out = io::output_path(o.out);
  const std::string ext = out.extension().string();
  if (ext != ".pdf" && ext != ".svg" && ext != ".png")
    throw core::InputError("--out " + o.out + ": the figure is .pdf, .svg or .png");
  for (const char* f : {"metadata.toml", "exits.csv", "clogs.csv"})
    io::verify_listed(run / f, "timeline: run");
  // The run's own files, checked as analyze checks them (times in order, species known, clogs in range).
  const core::Model model = core::compile(core::load_scene((run / "metadata.toml").string()));
  const core::Events ev = io::read_events(run, model.setup.species_names());
  const double end = model.scene.duration;
  const double to = o.to < 0 ? end : o.to;
  if (!(o.from >= 0) || !(to > o.from) || to > end + 1e-9)
    throw core::InputError("--from " + core::format_g(o.from) + " --to " + core::format_g(to) +
                           ": expected 0 <= FROM < TO <= the run's duration (" + core::format_g(end) + " s)");
  io::check_not_input(out, {run / "exits.csv", run / "clogs.csv", run / "metadata.toml"}, "figure");
  io::OutputLock lock(out);
  io::check_destination(out, o.force, "timeline", io::OutputKind::Sheet);
  fs::path partial = out;
  partial += ".partial" + ext;  // matplotlib picks the format from the extension
  // Each species in the colour the movies give it (the scene's own, else the paper palette's), so that the
  // figure and a frame beside it on a slide agree.
  render::Style style;
  style.species_colors = render::overlay_data_for(model).species_colors;
  std::string colors;
  for (size_t k = 0; k < model.setup.species.size(); ++k)
    colors += (k ? "," : "") + render::hex_rgb(render::species_color(style, static_cast<core::Species>(k)));
  const int status = run_python(script_path("timeline.py"),
                                {run.string(), partial.string(), core::format_g(o.from, 9),
                                 core::format_g(to, 9), io::version_string(), command_line(), colors});
  if (status != 0) {
    std::error_code ec;
    fs::remove(partial, ec);
    throw core::RuntimeFault("timeline: the matplotlib script timeline.py failed");
  }
  io::rename_into_place(partial, out);
  io::record_output(out);
  std::printf("%zu exits, %zu clogs -> %s\n", ev.exits.size(), ev.clogs.size(), out.c_str());
  return 0;
}
}  // namespace

void add_timeline_command(CLI::App& app, Action& action) {
  auto o = std::make_shared<TimelineOptions>();
  auto* cmd = app.add_subcommand(
      "timeline",
      "a run's discharge as a figure: exits per species against time, clogs as bands (PDF, SVG, PNG)");
  cmd->set_version_flag("--version", io::version_string());
  cmd->add_option("run", o->run, "a run or recording directory (metadata.toml, exits.csv, clogs.csv)")
      ->required();
  cmd->add_option("--out", o->out, "the figure: .pdf, .svg (vector, text as text) or .png")->required();
  cmd->add_option("--from", o->from, "start of the time axis, s")->capture_default_str();
  cmd->add_option("--to", o->to, "end of the time axis, s (default: the run's end)");
  cmd->add_flag("--force", o->force, "replace an earlier timeline or gallery figure of the same name");
  cmd->callback([o, &action] { action = [o] { return timeline(*o); }; });
}

}  // namespace app
