// siloscope bench arch: the cost of arch detection per call on the default scene, and how much detection at
// every video frame (30 fps of simulated time) slows the simulation down.
#include <algorithm>
#include <cstdio>

#include "analysis/stats.h"
#include "app/services/cli.h"
#include "app/services/process.h"
#include "app/services/run_outputs.h"
#include "app/services/session.h"
#include "app/services/terminal.h"
#include "core/error.h"
#include "io/metadata.h"
#include "io/output.h"
#include "sim/silo.h"

namespace app {

namespace {
using Clock = std::chrono::steady_clock;

struct ArchBenchOptions {
  SceneOptions scene;
  double seconds = 20;
  int repeats = 3;
  double fps = 30;
  std::string csv;
};

int bench_arch(const ArchBenchOptions& o) {
  const core::Model model = o.scene.compile();
  const core::Scene& scene = model.scene;
  if (o.repeats < 1 || !(o.seconds > 0) || !(o.fps > 0))
    throw core::InputError("--repeats, --seconds and --fps must be > 0");
  if (!o.csv.empty())
    io::check_destination(o.csv, true, "CSV file", io::OutputKind::Csv, "metric,value,unit", false);
  const FrameClock clock = FrameClock::every(scene.dt, 1.0 / o.fps, "--fps");
  std::printf("siloscope %s, bench arch: %g s simulated per repeat, detection every %ld steps (%g fps)\n",
              io::version_string().c_str(), o.seconds, clock.steps, o.fps);
  std::vector<double> per_call, plain_wall, detect_wall;
  long calls_found = 0, calls = 0;
  for (int r = 0; r < o.repeats; ++r) {
    // The same run twice, with and without detection; alternate which goes first.
    for (int pass = 0; pass < 2; ++pass) {
      bool detect = (pass + r) % 2 == 0;
      Session session({model});
      double in_detection = 0;
      FunctionSink probe;
      probe.frames = false;  // the detection is what is timed; no frames are built
      probe.on_frame = [&](const FrameTick& tick) {
        auto a = Clock::now();
        auto arch = tick.worlds[0]->current_arch();
        in_detection += std::chrono::duration<double>(Clock::now() - a).count();
        ++calls;
        calls_found += !arch.empty();
      };
      auto t0 = Clock::now();
      session.run(o.seconds, detect ? clock : FrameClock::none(), {&probe});
      double wall = std::chrono::duration<double>(Clock::now() - t0).count();
      if (detect) {
        detect_wall.push_back(wall);
        per_call.push_back(1e6 * in_detection / std::max(1.0, o.seconds * o.fps));
      } else {
        plain_wall.push_back(wall);
      }
      if (interrupted()) return 130;
    }
  }
  const double us = analysis::median(per_call),
               slow = analysis::median(detect_wall) / analysis::median(plain_wall) - 1.0;
  std::printf("%-36s %10.1f  (target < 50)\n", "arch detection, us per call", us);
  std::printf("%-36s %9.1f%%\n", "frames with an arch found", 100.0 * calls_found / std::max(1L, calls));
  std::printf("%-36s %10.2f\n", "wall s without detection (median)", analysis::median(plain_wall));
  std::printf("%-36s %10.2f\n", "wall s with detection (median)", analysis::median(detect_wall));
  std::printf("%-36s %9.1f%%  (target < 5%%)\n", "slowdown from detection per frame", 100 * slow);
  if (!o.csv.empty()) {
    std::string s = "metric,value,unit\n";
    s += "arch_detection_per_call," + std::to_string(us) + ",us\n";
    s +=
        "frames_with_arch," + std::to_string(static_cast<double>(calls_found) / std::max(1L, calls)) + ",1\n";
    s += "slowdown_detection_every_frame," + std::to_string(slow) + ",1\n";
    io::write_file_atomic(o.csv, s);
  }
  return 0;
}
}  // namespace

void add_bench_arch_command(CLI::App& bench, Action& action) {
  auto opts = std::make_shared<ArchBenchOptions>();
  auto* cmd = bench.add_subcommand("arch", "time arch detection per call and its cost at every video frame");
  opts->scene.add_to(*cmd, false);
  cmd->add_option("--seconds", opts->seconds, "simulated seconds per repeat");
  cmd->add_option("--repeats", opts->repeats, "repeats (median reported)")->check(whole_number(1, 1000));
  cmd->add_option("--fps", opts->fps, "detections per simulated second");
  cmd->add_option("--csv", opts->csv, "write the table as CSV here");
  cmd->callback([opts, &action] { action = [opts] { return bench_arch(*opts); }; });
}

}  // namespace app
