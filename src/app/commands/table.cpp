// The table of subcommands (app/services/commands.h): one row each, in the order --help lists them.
#include "app/services/commands.h"

namespace app {

void define_run_command(CLI::App& cmd, Action& action);
void define_record_command(CLI::App& cmd, Action& action);
void define_inspect_command(CLI::App& cmd, Action& action);
void define_live_command(CLI::App& cmd, Action& action);
void define_frame_command(CLI::App& cmd, Action& action);
void define_filmstrip_command(CLI::App& cmd, Action& action);
void define_sweep_command(CLI::App& cmd, Action& action);
void define_analyze_command(CLI::App& cmd, Action& action);
void define_figures_command(CLI::App& cmd, Action& action);
void define_claims_command(CLI::App& cmd, Action& action);
void define_gallery_command(CLI::App& cmd, Action& action);
void define_timeline_command(CLI::App& cmd, Action& action);
void define_share_command(CLI::App& cmd, Action& action);
void define_export_command(CLI::App& cmd, Action& action);
void define_import_command(CLI::App& cmd, Action& action);
void define_detect_command(CLI::App& cmd, Action& action);
void define_scene_command(CLI::App& cmd, Action& action);
void define_breaking_command(CLI::App& cmd, Action& action);
void define_bench_command(CLI::App& cmd, Action& action);

const std::vector<Command>& command_table() {
  static const std::vector<Command> table = {
      {"run", "simulate a scene headless; write events, measurements and metadata", define_run_command,
       "run {scene} --duration 600 --out {out}", true},
      {"record", "film a discharge: an MP4 movie, optional PNG frames, events and metadata",
       define_record_command, "record {scene} --duration 600 --size 640x360 --out {out}", true},
      {"inspect", "step through a recorded run frame by frame (window, or --script off-screen)",
       define_inspect_command, "inspect {recording} --script {script}", true},
      {"live", "the simulation running in a window, with a panel to change mu, r, chi, kicks",
       define_live_command, "live {scene} --frames 100000", false},
      {"frame",
       "one high-resolution picture of a recorded run at a clog, a rule removal or a time (PNG, SVG, PDF)",
       define_frame_command, "frame {run} --at t:3.9 --out {out}.png", true},
      {"filmstrip",
       "one clog of a recording at several times, one row of tiles on one colour scale (PDF, SVG: vector; "
       "PNG)",
       define_filmstrip_command, "filmstrip {recording} --clog 1 --times=-0.5,0,0.5,1 --out {out}.pdf", true},
      {"sweep", "run a campaign (a grid of scenes x realizations) on all cores, resumably",
       define_sweep_command, "sweep {campaign} --results {out}", true},
      {"analyze", "aggregate run directories into tidy CSV with 95% confidence intervals",
       define_analyze_command, "analyze {results} --out {out}", false},
      {"figures", "the paper's figures (PNG, SVG, PDF) from a campaign's tidy CSV", define_figures_command,
       "figures {analysis} --out {out}", true},
      {"claims", "the paper's seven claims against campaign results: a verdict table", define_claims_command,
       "claims x={analysis} --out {out}.md", false},
      {"gallery", "one sheet (PDF, SVG or PNG) with every long-lasting arch of a run", define_gallery_command,
       "gallery {run} --out {out}.pdf", true},
      {"timeline",
       "a run's discharge as a figure: exits per species against time, clogs as bands (PDF, SVG, PNG)",
       define_timeline_command, "timeline {run} --out {out}.pdf", true},
      {"share",
       "a run as one self-contained HTML page to open in any browser (play, scrub, clogs, arches, grains)",
       define_share_command, "share {recording} --out {out}.html", true},
      {"export", "a recording's trajectory as extended XYZ (OVITO, ASE), CSV, VTU (ParaView) or GSD",
       define_export_command, "export {recording} --format vtu --out {out}", true},
      {"import",
       "a lab experiment's tracked particles (CSV) as a run: trajectory, exits, clogs and their arches",
       define_import_command, "import {tracks} --out {out}", false},
      {"detect",
       "locate and track the disks of a film (a video or a directory of frames) as the CSV import reads",
       define_detect_command, "detect {video} --out {out}.csv", true},
      {"breaking",
       "the kick that breaks each arrested clog's arch: copies of the state, kicked harder until it flows",
       define_breaking_command, "breaking {run} --out {out}", true},
      {"scene", "list every scene key (--keys), or validate and resolve a scene file", define_scene_command,
       "scene {scene}", false},
      {"bench", "benchmarks that print tables and write CSV", define_bench_command,
       "bench sim {scene} --repeats 1000", true},
  };
  return table;
}

}  // namespace app
