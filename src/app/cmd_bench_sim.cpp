// siloscope bench sim: time the simulation's stages and compare its step with a bare Box2D loop on the same
// world. Prints a table and writes CSV. Medians over repeats; the two loops alternate within each repeat so
// machine noise hits both alike.
#include <algorithm>
#include <cstdio>
#include <fstream>

#include "analysis/stats.h"
#include "app/common.h"
#include "core/error.h"
#include "io/metadata.h"
#include "io/output.h"
#include "sim/hopper.h"

namespace app {

namespace {
using Clock = std::chrono::steady_clock;

struct BenchOptions {
  SceneOptions scene;
  int repeats = 5;
  int steps = 2000;
  std::string csv;
};

int bench_sim(const BenchOptions& o) {
  core::Scene scene = o.scene.load();
  if (o.repeats < 1 || o.steps < 1) throw core::InputError("--repeats and --steps must be >= 1");
  if (!o.csv.empty())
    io::check_destination(o.csv, true, "CSV file", io::OutputKind::Csv, "metric,value,unit");
  std::printf(
      "siloscope %s, bench sim: %lld disks, r = %g, chi = %g, mu = %g A*m^2, dt = %g s, iterations (%lld, "
      "%lld), "
      "length_scale %g\n",
      io::version_string().c_str(), static_cast<long long>(scene.n_total), scene.size_ratio, scene.chi,
      scene.mu, scene.dt, static_cast<long long>(scene.velocity_iterations),
      static_cast<long long>(scene.position_iterations), scene.length_scale);
  std::printf("settling two copies of the scene (seed %llu)...\n",
              static_cast<unsigned long long>(scene.seed));
  sim::Hopper ours(scene), bare(scene);
  sim::Hopper profiled(scene);
  profiled.set_profiling(true);

  std::vector<double> us_ours, us_bare, kicks, dipoles, box2d, book;
  for (int r = 0; r < o.repeats; ++r) {
    auto t0 = Clock::now();
    for (int i = 0; i < o.steps; ++i) ours.step();
    auto t1 = Clock::now();
    bare.step_box2d_only(o.steps);
    auto t2 = Clock::now();
    sim::StageTimes before = profiled.stage_times();
    for (int i = 0; i < o.steps; ++i) profiled.step();
    const sim::StageTimes& after = profiled.stage_times();
    us_ours.push_back(1e6 * std::chrono::duration<double>(t1 - t0).count() / o.steps);
    us_bare.push_back(1e6 * std::chrono::duration<double>(t2 - t1).count() / o.steps);
    kicks.push_back(1e6 * (after.kicks - before.kicks) / o.steps);
    dipoles.push_back(1e6 * (after.dipoles - before.dipoles) / o.steps);
    box2d.push_back(1e6 * (after.box2d - before.box2d) / o.steps);
    book.push_back(1e6 * (after.bookkeeping - before.bookkeeping) / o.steps);
    if (interrupted()) return 130;
  }
  const double m_ours = analysis::median(us_ours), m_bare = analysis::median(us_bare);
  const double stages[] = {analysis::median(box2d), analysis::median(dipoles), analysis::median(kicks),
                           analysis::median(book)};
  const char* names[] = {"box2d_step", "dipoles", "kicks", "bookkeeping"};
  double stage_sum = 0;
  for (double s : stages) stage_sum += s;

  std::printf("\n%d repeats of %d steps (%.1f s simulated each); medians\n", o.repeats, o.steps,
              o.steps * scene.dt);
  std::printf("%-28s %12s %10s\n", "stage", "us/step", "share");
  for (int k = 0; k < 4; ++k)
    std::printf("%-28s %12.1f %9.1f%%\n", names[k], stages[k], 100 * stages[k] / stage_sum);
  std::printf("%-28s %12.1f\n", "siloscope step", m_ours);
  std::printf("%-28s %12.1f\n", "bare Box2D step", m_bare);
  std::printf("%-28s %12.3f  (target <= 1.10)\n", "ratio siloscope / bare", m_ours / m_bare);
  std::printf("%-28s %12.2f  (target >= 5)\n", "simulated s per wall s", scene.dt / (m_ours * 1e-6));
  std::printf("%-28s %12s\n", "spread siloscope us (min-max)",
              (std::to_string(static_cast<int>(*std::min_element(us_ours.begin(), us_ours.end()))) + "-" +
               std::to_string(static_cast<int>(*std::max_element(us_ours.begin(), us_ours.end()))))
                  .c_str());

  if (!o.csv.empty()) {
    std::string s = "metric,value,unit\n";
    for (int k = 0; k < 4; ++k) s += std::string(names[k]) + "," + std::to_string(stages[k]) + ",us/step\n";
    s += "siloscope_step," + std::to_string(m_ours) + ",us/step\n";
    s += "bare_box2d_step," + std::to_string(m_bare) + ",us/step\n";
    s += "ratio_siloscope_over_bare," + std::to_string(m_ours / m_bare) + ",1\n";
    s += "simulated_per_wall_second," + std::to_string(scene.dt / (m_ours * 1e-6)) + ",1\n";
    io::write_file_atomic(o.csv, s);
    std::printf("written %s\n", o.csv.c_str());
  }
  return 0;
}
}  // namespace

void add_bench_command(CLI::App& app, Action& action) {
  auto* bench = app.add_subcommand("bench", "benchmarks that print tables and write CSV");
  bench->set_version_flag("--version", io::version_string());
  bench->require_subcommand(1);
  auto opts = std::make_shared<BenchOptions>();
  auto* cmd = bench->add_subcommand("sim", "time the simulation step by stage against a bare Box2D loop");
  cmd->set_version_flag("--version", io::version_string());
  opts->scene.add_to(*cmd, false);
  cmd->add_option("--repeats", opts->repeats, "timed repeats (median reported)")
      ->check(whole_number(1, 1000));
  cmd->add_option("--steps", opts->steps, "steps per repeat")->check(whole_number(1, 100000000));
  cmd->add_option("--csv", opts->csv, "write the table as CSV here");
  cmd->callback([opts, &action] { action = [opts] { return bench_sim(*opts); }; });
  add_bench_arch_command(*bench, action);
  add_bench_accuracy_command(*bench, action);
  add_bench_stability_command(*bench, action);
  add_bench_sweep_command(*bench, action);
  add_bench_record_command(*bench, action);
}

}  // namespace app
