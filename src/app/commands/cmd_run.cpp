// siloscope run SCENE --out DIR: a headless run that writes events, measurements and metadata.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "analysis/measure.h"
#include "analysis/tidy.h"
#include "app/services/cli.h"
#include "app/services/hindsight.h"
#include "app/services/process.h"
#include "app/services/run_outputs.h"
#include "app/services/session.h"
#include "app/services/sinks.h"
#include "app/services/terminal.h"
#include "core/error.h"
#include "core/format.h"
#include "core/scene.h"
#include "io/events_csv.h"
#include "io/metadata.h"
#include "io/output.h"
#include "io/run.h"
#include "io/trajectory.h"
#include "sim/silo.h"

namespace app {

namespace {
struct RunOptions {
  SceneOptions scene;
  std::string out;
  std::string protocol;  // a protocol file (siloscope.Simulation's, written by Simulation.write_run), or ""
  double trajectory_fps = 0;
  bool force = false;
  bool quiet = false;
  bool record_refusal = false;
};

// A protocol: what a Python Simulation did, replayed here exactly (the same steps, the changes between the
// same two steps). One line each: `to T` (step until t >= T - dt/2, as advance_to does), `set
// kick_impulse_max J`, `set outlet_open true|false`, `finish` (the last line, if any); # starts a comment.
struct Protocol {
  struct Entry {
    double t = -1;  // a `to` line's time; < 0: a `set` line
    std::string key, value;
    double number = 0;  // kick_impulse_max's value
  };
  std::vector<Entry> entries;
  double end = 0;  // s: the last `to`
  std::string text;
};

Protocol read_protocol(const std::string& path) {
  core::check_text_file(path, "--protocol", "");
  std::ifstream in(path);
  if (!in) throw core::InputError("--protocol " + path + ": cannot open it");
  Protocol p;
  int n = 0;
  bool finished = false;
  for (std::string line; std::getline(in, line);) {
    ++n;
    const std::string where = path + ":" + std::to_string(n) + ": ";
    std::stringstream ss(line.substr(0, line.find('#')));
    std::string word, a, b, extra;
    if (!(ss >> word)) continue;
    ss >> a >> b >> extra;
    if (finished) throw core::InputError(where + "'" + line + "' after `finish` (it ends the protocol)");
    if (word == "to" && !a.empty() && b.empty()) {
      char* end = nullptr;
      const double t = std::strtod(a.c_str(), &end);
      if (*end || !std::isfinite(t) || t < p.end)
        throw core::InputError(where + "to " + a + ": expected a finite time (s) not before the last (" +
                               core::format_g(p.end, 9) + ")");
      p.entries.push_back({t, "", "", 0});
      p.end = t;
    } else if (word == "set" && !b.empty() && extra.empty() &&
               (a == "kick_impulse_max" || (a == "outlet_open" && (b == "true" || b == "false")))) {
      double v = 0;
      if (a == "kick_impulse_max") {
        char* end = nullptr;
        v = std::strtod(b.c_str(), &end);
        if (*end || !std::isfinite(v) || v < 0)
          throw core::InputError(where + "set kick_impulse_max " + b +
                                 ": expected a finite impulse >= 0 N*s");
      }
      p.entries.push_back({-1, a, b, v});
    } else if (word == "finish" && a.empty()) {
      finished = true;
    } else {
      throw core::InputError(where + "'" + line +
                             "': expected `to T`, `set kick_impulse_max J`, `set outlet_open " +
                             "true|false` or `finish`");
    }
    p.text += line + "\n";
  }
  if (p.end <= 0)
    throw core::InputError("--protocol " + path + ": no `to T` line with T > 0 (nothing to run)");
  return p;
}

int simulate(const RunOptions& o, const core::Model& model, const Protocol& protocol);

// A run the health monitor stops is refused for good (the same scene, seed and numerics stop again). With
// --record-refusal (campaign jobs) that outcome is written as OUT.refused.toml: the scene with its seed and
// the reason, which `sweep` reads to leave the realization settled and `analyze` counts as n_refused.
int run(const RunOptions& given) {
  RunOptions o = given;
  Protocol protocol;
  if (!o.protocol.empty()) {
    if (o.scene.duration)
      throw core::InputError(
          "--duration and --protocol: the protocol's last `to` line is the run's end; give one");
    protocol = read_protocol(o.protocol);
    o.scene.duration = protocol.end;
  }
  const core::Model model = o.scene.compile();
  const core::Scene& scene = model.scene;
  try {
    return simulate(o, model, protocol);
  } catch (const core::Unstable& e) {
    if (o.record_refusal)
      io::write_file_atomic(
          o.out + ".refused.toml",
          "# " + o.out +
              ": refused by the health monitor (exit 3); the same seed and numerics refuse\n"
              "# again, so `sweep` does not rerun it and `analyze` counts it as n_refused at its "
              "point.\n# Delete this file to run it again (with other numerics, say).\n"
              "# reason: " +
              std::string(e.what()) + "\n" + core::scene_toml(scene));
    throw;
  }
}

int simulate(const RunOptions& o, const core::Model& model, const Protocol& protocol) {
  const core::Scene& scene = model.scene;
  if (o.trajectory_fps < 0)
    throw core::InputError("--trajectory-fps " + core::format_g(o.trajectory_fps) + ": must be > 0");
  // Frames every whole number of steps (the one rule of every command, app/session.h).
  const FrameClock clock = o.trajectory_fps > 0
                               ? FrameClock::every(scene.dt, 1.0 / o.trajectory_fps, "--trajectory-fps")
                               : FrameClock::none();
  io::OutputDir dir(o.out, o.force, io::DirKind::Run);  // checked before hours of simulation, not after

  Progress progress("run", scene.duration, !o.quiet, false);
  auto wall0 = std::chrono::steady_clock::now();
  Session session({model});  // deposits, settles, opens: t = 0
  sim::Silo& hopper = session.world(0);
  auto wall1 = std::chrono::steady_clock::now();
  std::unique_ptr<TrajectorySink> trajectory;
  std::vector<Sink*> sinks;
  if (clock.steps > 0) {
    io::RunInfo tinfo{command_line(), {}, {}, {}};
    trajectory = std::make_unique<TrajectorySink>(
        dir.file(io::run_file::kTrajectory),
        trajectory_info(hopper, clock.frame_interval, io::metadata_toml(model, tinfo)));
    sinks.push_back(trajectory.get());
  }
  auto report = [&](double t) {
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall1).count();
    char extra[96];
    std::snprintf(extra, sizeof extra, "t = %.1f s, %zu exits, %.1fx real time", t,
                  hopper.events().exits.size(), t / std::max(wall, 1e-9));
    progress.update(t, extra);
  };
  // The trajectory sees each arch from its formation: its frames reach it clog_min_gap late.
  HindsightSink hindsight(sinks, scene.clog_min_gap + clock.frame_interval);
  // The protocol's segments (or the whole duration), its changes between them.
  bool whole = true;
  for (const auto& e : protocol.entries) {
    if (e.t < 0) {
      if (e.key == "kick_impulse_max")
        hopper.set_kick_impulse_max(e.number);
      else
        hopper.set_outlet_open(e.value == "true");
    } else if (!(whole = session.run(e.t, clock, {&hindsight}, interrupted, report))) {
      break;
    }
  }
  if (!whole || !session.run(scene.duration, clock, {&hindsight}, interrupted, report)) {
    progress.finish();
    std::fprintf(stderr, "siloscope: interrupted at t = %.1f s; nothing written\n", hopper.time());
    return 130;
  }
  session.finish({&hindsight});  // the trajectory keeps the clog the run's end closed
  if (trajectory) trajectory->close();
  progress.finish();
  auto wall2 = std::chrono::steady_clock::now();
  const double settle_wall = std::chrono::duration<double>(wall1 - wall0).count();
  const double run_wall = std::chrono::duration<double>(wall2 - wall1).count();

  io::RunInfo info;
  info.command = command_line();
  info.facts = {{"steps", hopper.steps()},
                {"settle_max_speed_m_per_s", hopper.settle_max_speed()},
                {"arch_fallbacks", hopper.arch_fallbacks()},
                {"wall_time_settle_s", settle_wall},
                {"wall_time_discharge_s", run_wall},
                {"speed_vs_real_time", scene.duration / std::max(run_wall, 1e-9)}};
  if (clock.steps > 0) info.facts.push_back({"trajectory_steps_per_frame", clock.steps});
  if (!protocol.text.empty()) info.facts.push_back({"protocol", protocol.text});  // what was done, timed
  const analysis::Measurements m = write_run_outputs(dir.file(""), hopper, scene.duration, info);
  dir.commit();

  if (!o.quiet) {
    std::printf("%s",
                analysis::summary_text(m, hopper.setup().species_names(), hopper.setup().clog_rule).c_str());
    std::printf("speed       %.2fx real time (%.1f s wall for %.1f s; settling %.1f s wall)\n",
                scene.duration / std::max(run_wall, 1e-9), run_wall, scene.duration, settle_wall);
    std::printf("written     %s/{exits,clogs,arches,summary,species,survival}.csv, metadata.toml\n",
                o.out.c_str());
  }
  return 0;
}
}  // namespace

void define_run_command(CLI::App& command, Action& action) {
  auto opts = std::make_shared<RunOptions>();
  CLI::App* cmd = &command;
  opts->scene.add_to(*cmd);
  cmd->add_option("--out", opts->out, "output directory (created whole when the run completes)")->required();
  cmd->add_option("--trajectory-fps", opts->trajectory_fps,
                  "also write trajectory.sstraj with this many frames per simulated second (for inspect)");
  cmd->add_option(
      "--protocol", opts->protocol,
      "replay a Python Simulation's protocol (lines `to T`, `set KEY VALUE`, `finish`): its steps and "
      "changes, exactly; the last `to` is the run's end");
  cmd->add_flag("--force", opts->force, "replace an existing output directory");
  cmd->add_flag("--quiet", opts->quiet, "print nothing but errors");
  cmd->add_flag("--record-refusal", opts->record_refusal,
                "if the health monitor stops the run (exit 3), write OUT.refused.toml (scene, seed, reason): "
                "how campaign jobs record a refused realization");
  cmd->callback([opts, &action] { action = [opts] { return run(*opts); }; });
}

}  // namespace app
