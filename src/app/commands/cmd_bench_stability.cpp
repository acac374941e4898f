// siloscope bench stability: where the methods fail. A map of time step against dipole strength for r = 0.2
// and 0.4: for every cell, do the static checks (dipole and kinematic safe time steps) refuse it, and does
// the integration actually break (health monitor, run with --unsafe)? A good check refuses what breaks and
// accepts what does not.
#include <atomic>
#include <cmath>
#include <cstdio>
#include <mutex>
#include <thread>

#include "app/services/campaign.h"
#include "app/services/cli.h"
#include "app/services/process.h"
#include "app/services/run_outputs.h"
#include "app/services/session.h"
#include "app/services/terminal.h"
#include "core/error.h"
#include "core/physics.h"
#include "core/setup.h"
#include "io/metadata.h"
#include "io/output.h"
#include "sim/silo.h"

namespace app {

namespace {
struct StabilityOptions {
  double seconds = 3;
  int threads = 2;
  std::string csv = "docs/accuracy/stability.csv", chart = "docs/accuracy/stability.png";
};

struct Cell {
  double r, dt, ratio, mu = 0, safe_dt = 0;
  bool refused = false;
  long warnings = 0;
  std::string failure;
};

int bench_stability(const StabilityOptions& o) {
  io::check_destination(o.csv, true, "CSV file", io::OutputKind::Csv,
                        "size_ratio,dt_s,dipole_force_ratio,mu,safe_dt_s,refused,broke,outcome", false);
  std::vector<Cell> cells;
  for (double r : {0.2, 0.4})
    for (double dt : {2.5e-4, 5e-4, 1e-3, 2e-3, 5e-3, 1e-2})
      for (double ratio : {0.0, 1.0, 10.0, 100.0, 1000.0})
        cells.push_back(Cell{r, dt, ratio, 0.0, 0.0, false, 0, {}});
  std::printf("siloscope %s, bench stability: %zu cells, %g s of discharge each, %d threads\n",
              io::version_string().c_str(), cells.size(), o.seconds, o.threads);
  std::atomic<size_t> next{0};
  std::mutex m;
  auto worker = [&] {
    for (size_t i; (i = next++) < cells.size();) {
      Cell& c = cells[i];
      core::Scene s;
      s.size_ratio = c.r;
      s.dt = c.dt;
      s.mu = core::mu_for_force_ratio(s, c.ratio);
      s.settle_time = 2.0;
      s.duration = o.seconds;
      s.unsafe = true;  // run it anyway: we want to know whether it really breaks
      c.mu = s.mu;
      const core::Model model = core::compile(s);
      const core::Setup& st = model.setup;
      c.safe_dt = std::min(core::dipole_safe_dt(st), core::kinematic_safe_dt(st, s.gravity));
      c.refused = s.dt > c.safe_dt;
      try {
        Session session({model});
        session.run(s.duration, FrameClock::none(), {});
        c.warnings =
            session.world(0).health_warnings() - (c.refused ? 1 : 0);  // the static refusal: one warning
      } catch (const std::exception& e) {
        c.failure = e.what();
        c.warnings = std::max(1L, c.warnings);
      }
      if (interrupted()) return;
    }
  };
  std::vector<std::thread> pool;
  for (int i = 0; i < std::max(1, o.threads); ++i) pool.emplace_back(worker);
  for (auto& t : pool) t.join();
  if (interrupted()) return 130;

  std::string csv = "size_ratio,dt_s,dipole_force_ratio,mu,safe_dt_s,refused,broke,outcome\n";
  int missed = 0, correct = 0, conservative = 0;
  std::printf("\n%-6s %-9s %-9s %-10s %-8s %-6s %s\n", "r", "dt [s]", "F/W", "safe dt", "refused", "broke",
              "outcome");
  for (const auto& c : cells) {
    const bool broke = c.warnings > 0 || !c.failure.empty();
    const char* outcome = c.refused ? (broke ? "refused-breaks" : "refused-runs-clean")
                                    : (broke ? "ACCEPTED-BREAKS" : "accepted-clean");
    missed += !c.refused && broke;
    correct += c.refused == broke;
    conservative += c.refused && !broke;
    std::printf("%-6g %-9g %-9g %-10.3g %-8s %-6s %s\n", c.r, c.dt, c.ratio, c.safe_dt,
                c.refused ? "yes" : "no", broke ? "yes" : "no", outcome);
    char line[256];
    std::snprintf(line, sizeof line, "%g,%g,%g,%.6g,%.6g,%d,%d,%s\n", c.r, c.dt, c.ratio, c.mu, c.safe_dt,
                  c.refused, broke, outcome);
    csv += line;
  }
  std::printf(
      "\n%d of %zu cells judged right; %d refused although they ran clean (conservative); %d accepted but "
      "broke\n",
      correct, cells.size(), conservative, missed);
  io::write_file_atomic(o.csv, csv);
  std::printf("written %s\n", o.csv.c_str());
  if (!o.chart.empty()) {
    if (run_python(script_path("stability_chart.py"), {o.csv, o.chart}) != 0)
      std::fprintf(stderr, "siloscope: the chart could not be drawn\n");
  }
  return missed == 0 ? 0 : 1;
}
}  // namespace

void add_bench_stability_command(CLI::App& bench, Action& action) {
  auto o = std::make_shared<StabilityOptions>();
  auto* cmd = bench.add_subcommand("stability",
                                   "map time step x dipole strength: refused by the check, broken in fact");
  cmd->add_option("--seconds", o->seconds, "s of discharge per cell")->capture_default_str();
  cmd->add_option("--threads", o->threads, "cells run side by side")
      ->check(whole_number(1, 256))
      ->capture_default_str();
  cmd->add_option("--csv", o->csv, "CSV output")->capture_default_str();
  cmd->add_option("--chart", o->chart, "PNG chart (empty: none)")->capture_default_str();
  cmd->callback([o, &action] { action = [o] { return bench_stability(*o); }; });
}

}  // namespace app
