// siloscope run SCENE --out DIR: a headless run that writes events, measurements and metadata.
#include <cstdio>

#include "analysis/measure.h"
#include "analysis/tidy.h"
#include "app/common.h"
#include "core/error.h"
#include "io/events_csv.h"
#include "io/metadata.h"
#include "io/output.h"
#include "sim/hopper.h"

namespace app {

namespace {
struct RunOptions {
  SceneOptions scene;
  std::string out;
  bool force = false;
  bool quiet = false;
};

std::string num(double v) {
  char b[40];
  std::snprintf(b, sizeof b, "%.9g", v);
  return b;
}

int run(const RunOptions& o) {
  const core::Scene scene = o.scene.load();
  io::OutputDir dir(o.out, o.force);  // checked before hours of simulation, not after
  install_interrupt_handler();

  Progress progress("run", scene.duration, !o.quiet);
  auto wall0 = std::chrono::steady_clock::now();
  sim::Hopper hopper(scene);  // deposits, settles, opens: t = 0
  auto wall1 = std::chrono::steady_clock::now();
  const double report_every = 0.5;
  for (double next = report_every; hopper.time() < scene.duration - 0.5 * scene.dt;) {
    hopper.step();
    if (hopper.time() >= next) {
      next += report_every;
      if (interrupted()) {
        progress.finish();
        std::fprintf(stderr, "siloscope: interrupted at t = %.1f s; nothing written\n", hopper.time());
        return 130;
      }
      double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall1).count();
      char extra[96];
      std::snprintf(extra, sizeof extra, "t = %.1f s, %zu exits, %.1fx real time", hopper.time(),
                    hopper.events().exits.size(), hopper.time() / std::max(wall, 1e-9));
      progress.update(hopper.time(), extra);
    }
  }
  hopper.finish();
  progress.finish();
  auto wall2 = std::chrono::steady_clock::now();
  const double settle_wall = std::chrono::duration<double>(wall1 - wall0).count();
  const double run_wall = std::chrono::duration<double>(wall2 - wall1).count();

  const analysis::Measurements m = analysis::measure(hopper.events(), scene.duration);
  io::write_events(dir.file(""), hopper.events());
  io::write_file_atomic(dir.file("summary.csv"), analysis::summary_header() + "\n" + analysis::summary_row(scene, m) + "\n");
  io::write_file_atomic(dir.file("survival.csv"), analysis::survival_csv(scene, hopper.events().exits));
  io::RunInfo info;
  info.command = command_line();
  info.facts = {{"steps", std::to_string(hopper.steps())},
                {"settle_max_speed_m_per_s", num(hopper.settle_max_speed())},
                {"arch_fallbacks", std::to_string(hopper.arch_fallbacks())},
                {"wall_time_settle_s", num(settle_wall)},
                {"wall_time_discharge_s", num(run_wall)},
                {"speed_vs_real_time", num(scene.duration / std::max(run_wall, 1e-9))}};
  io::write_file_atomic(dir.file("metadata.toml"), io::metadata_toml(scene, info));
  dir.commit();

  if (!o.quiet) {
    std::printf("%s", analysis::summary_text(m).c_str());
    std::printf("speed       %.2fx real time (%.1f s wall for %.1f s; settling %.1f s wall)\n",
                scene.duration / std::max(run_wall, 1e-9), run_wall, scene.duration, settle_wall);
    std::printf("written     %s/{exits,clogs,arches,summary,survival}.csv, metadata.toml\n", o.out.c_str());
  }
  return 0;
}
}  // namespace

void add_run_command(CLI::App& app, Action& action) {
  auto opts = std::make_shared<RunOptions>();
  auto* cmd = app.add_subcommand("run", "simulate a scene headless; write events, measurements and metadata");
  cmd->set_version_flag("--version", io::version_string());
  opts->scene.add_to(*cmd);
  cmd->add_option("--out", opts->out, "output directory (created whole when the run completes)")->required();
  cmd->add_flag("--force", opts->force, "replace an existing output directory");
  cmd->add_flag("--quiet", opts->quiet, "print nothing but errors");
  cmd->callback([opts, &action] { action = [opts] { return run(*opts); }; });
}

}  // namespace app
