// siloscope bench sim: time the simulation's stages and compare its step with a bare Box2D loop on the same
// world. Prints a table and writes CSV. Medians over repeats; the two loops alternate within each repeat so
// machine noise hits both alike. --scaling: the cost per grain-step at 250, 1000 and 5000 grains, with and
// without dipoles, in a silo that widens with the grains.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>

#include "analysis/stats.h"
#include "app/services/cli.h"
#include "app/services/process.h"
#include "app/services/run_outputs.h"
#include "app/services/terminal.h"
#include "core/error.h"
#include "core/format.h"
#include "core/physics.h"
#include "core/setup.h"
#include "io/metadata.h"
#include "io/output.h"
#include "sim/silo.h"

namespace app {

namespace {
using Clock = std::chrono::steady_clock;

const char* kScalingHeader =
    "grains,dipoles,us_per_step,us_per_grain_step,over_250,box2d_us,contacts_us,solver_us,dipoles_us,"
    "bookkeeping_us,bare_box2d_us";

struct BenchOptions {
  SceneOptions scene;
  int repeats = 5;
  int steps = 2000;
  bool scaling = false;
  std::string csv;
};

// Medians over the repeats, us per step.
struct StepCost {
  double ours = 0, bare = 0, kicks = 0, dipoles = 0, box2d = 0, contacts = 0, solver = 0, toi = 0, book = 0;
  double min_ours = 0, max_ours = 0;
};

double us(double seconds, int steps) {
  return 1e6 * seconds / steps;
}

// Time `steps` steps of the scene `repeats` times: siloscope's step, a bare Box2D step on a copy of the same
// world, and a profiled copy for the stages.
StepCost time_steps(const core::Model& model, int steps, int repeats) {
  sim::Silo ours(model), bare(model), profiled(model);
  profiled.set_profiling(true);
  std::vector<double> o, b, k, d, x, c, s, t, bk;
  for (int r = 0; r < repeats; ++r) {
    auto t0 = Clock::now();
    for (int i = 0; i < steps; ++i) ours.step();
    auto t1 = Clock::now();
    bare.step_box2d_only(steps);
    auto t2 = Clock::now();
    const sim::StageTimes before = profiled.stage_times();
    for (int i = 0; i < steps; ++i) profiled.step();
    const sim::StageTimes& after = profiled.stage_times();
    o.push_back(us(std::chrono::duration<double>(t1 - t0).count(), steps));
    b.push_back(us(std::chrono::duration<double>(t2 - t1).count(), steps));
    k.push_back(us(after.kicks - before.kicks, steps));
    d.push_back(us(after.dipoles - before.dipoles, steps));
    x.push_back(us(after.box2d - before.box2d, steps));
    c.push_back(us(after.contacts - before.contacts, steps));
    s.push_back(us(after.solver - before.solver, steps));
    t.push_back(us(after.toi - before.toi, steps));
    bk.push_back(us(after.bookkeeping - before.bookkeeping, steps));
    if (interrupted()) throw core::RuntimeFault("interrupted");
  }
  StepCost cost{analysis::median(o),
                analysis::median(b),
                analysis::median(k),
                analysis::median(d),
                analysis::median(x),
                analysis::median(c),
                analysis::median(s),
                analysis::median(t),
                analysis::median(bk),
                *std::min_element(o.begin(), o.end()),
                *std::max_element(o.begin(), o.end())};
  return cost;
}

// The scaling scene: the paper's disks (r_o = 0.065 m, r = 0.4, chi = 0.4) and outlet in a flat-bottomed silo
// 1 m wide per 250 grains and 5 m tall, so the column keeps its height and every grain its neighbourhood
// while the count grows; with dipoles, the added disks repel at 3 weights at contact, pairs cut off where the
// force falls to 1% of a weight (a cell list).
core::Scene scaling_scene(int n, bool dipoles, std::uint64_t seed) {
  core::Scene s;
  core::apply_overrides(s, {"n_total=" + std::to_string(n), "container=flat",
                            "silo_width=" + core::format_g(n / 250.0, 6), "silo_height=5"});
  s.seed = seed;
  if (dipoles) {
    const double ratio = 3.0;
    s.mu = core::mu_for_force_ratio(s, ratio);
    s.dipole_cutoff = 2 * s.radius_added() * std::pow(ratio / 0.01, 0.25);
  }
  core::validate(s);
  return s;
}

int bench_scaling(const BenchOptions& o, std::uint64_t seed) {
  const int steps = std::min(o.steps, 500), repeats = std::min(o.repeats, 3);
  std::printf(
      "siloscope %s, bench sim --scaling: the paper's disks in a flat silo 1 m wide per 250 grains; %d "
      "repeats of %d steps, medians\n",
      io::version_string().c_str(), repeats, steps);
  std::printf("%-7s %-8s %12s %14s %10s %12s %12s %12s\n", "grains", "dipoles", "us/step", "us/grain-step",
              "x 250", "box2d us", "dipoles us", "bookkeep us");
  std::string csv = std::string(kScalingHeader) + "\n";
  for (bool dip : {false, true}) {
    double base = 0;
    for (int n : {250, 1000, 5000}) {
      std::fprintf(stderr, "settling %d grains%s...\n", n, dip ? " with dipoles" : "");
      const StepCost c = time_steps(core::compile(scaling_scene(n, dip, seed)), steps, repeats);
      const double per = c.ours / n;
      if (n == 250) base = per;
      std::printf("%-7d %-8s %12.1f %14.4f %10.2f %12.1f %12.1f %12.1f\n", n, dip ? "yes" : "no", c.ours, per,
                  per / base, c.box2d, c.dipoles, c.book);
      csv += std::to_string(n) + "," + (dip ? "1" : "0") + "," + core::format_g(c.ours, 6) + "," +
             core::format_g(per, 6) + "," + core::format_g(per / base, 4) + "," + core::format_g(c.box2d, 6) +
             "," + core::format_g(c.contacts, 6) + "," + core::format_g(c.solver, 6) + "," +
             core::format_g(c.dipoles, 6) + "," + core::format_g(c.book, 6) + "," +
             core::format_g(c.bare, 6) + "\n";
    }
  }
  std::printf(
      "goal: at 5000 grains within 1.5x of the 250-grain cost per grain-step, with and without dipoles\n");
  if (!o.csv.empty()) {
    io::write_file_atomic(o.csv, csv);
    std::printf("written %s\n", o.csv.c_str());
  }
  return 0;
}

int bench_sim(const BenchOptions& o) {
  const core::Model model = o.scene.compile();
  const core::Scene& scene = model.scene;
  if (o.repeats < 1 || o.steps < 1) throw core::InputError("--repeats and --steps must be >= 1");
  if (!o.csv.empty())
    io::check_destination(o.csv, true, "CSV file", io::OutputKind::Csv,
                          o.scaling ? kScalingHeader : "metric,value,unit", false);
  if (o.scaling) return bench_scaling(o, scene.seed);
  const core::Setup& setup = model.setup;
  std::printf(
      "siloscope %s, bench sim: %d grains in %zu species, dt = %g s, iterations (%lld, %lld), "
      "length_scale %g%s\n",
      io::version_string().c_str(), setup.n_total, setup.species.size(), scene.dt,
      static_cast<long long>(scene.velocity_iterations), static_cast<long long>(scene.position_iterations),
      scene.length_scale, setup.any_dipole() ? ", dipoles" : "");
  std::printf("settling three copies of the scene (seed %llu)...\n",
              static_cast<unsigned long long>(scene.seed));
  StepCost c;
  try {
    c = time_steps(model, o.steps, o.repeats);
  } catch (const core::RuntimeFault&) {
    return 130;
  }
  const double stages[] = {c.box2d, c.contacts, c.solver, c.toi, c.dipoles, c.kicks, c.book};
  const char* names[] = {"box2d_step", "  contacts", "  solver",   "  continuous",
                         "dipoles",    "kicks",      "bookkeeping"};
  const char* keys[] = {"box2d_step", "box2d_contacts", "box2d_solver", "box2d_continuous",
                        "dipoles",    "kicks",          "bookkeeping"};
  const double stage_sum = c.box2d + c.dipoles + c.kicks + c.book;

  std::printf("\n%d repeats of %d steps (%.1f s simulated each); medians\n", o.repeats, o.steps,
              o.steps * scene.dt);
  std::printf("%-28s %12s %10s\n", "stage", "us/step", "share");
  for (int k = 0; k < 7; ++k)
    std::printf("%-28s %12.1f %9.1f%%\n", names[k], stages[k], 100 * stages[k] / stage_sum);
  std::printf("%-28s %12.1f\n", "siloscope step", c.ours);
  std::printf("%-28s %12.1f\n", "bare Box2D step", c.bare);
  std::printf("%-28s %12.3f  (target <= 1.10)\n", "ratio siloscope / bare", c.ours / c.bare);
  std::printf("%-28s %12.2f  (target >= 5)\n", "simulated s per wall s", scene.dt / (c.ours * 1e-6));
  std::printf(
      "%-28s %12s\n", "spread siloscope us (min-max)",
      (std::to_string(static_cast<int>(c.min_ours)) + "-" + std::to_string(static_cast<int>(c.max_ours)))
          .c_str());

  if (!o.csv.empty()) {
    std::string s = "metric,value,unit\n";
    for (int k = 0; k < 7; ++k) s += std::string(keys[k]) + "," + std::to_string(stages[k]) + ",us/step\n";
    s += "siloscope_step," + std::to_string(c.ours) + ",us/step\n";
    s += "bare_box2d_step," + std::to_string(c.bare) + ",us/step\n";
    s += "ratio_siloscope_over_bare," + std::to_string(c.ours / c.bare) + ",1\n";
    s += "simulated_per_wall_second," + std::to_string(scene.dt / (c.ours * 1e-6)) + ",1\n";
    io::write_file_atomic(o.csv, s);
    std::printf("written %s\n", o.csv.c_str());
  }
  return 0;
}
}  // namespace

void define_bench_command(CLI::App& command, Action& action) {
  CLI::App* bench = &command;
  bench->require_subcommand(1);
  auto opts = std::make_shared<BenchOptions>();
  auto* cmd = bench->add_subcommand("sim", "time the simulation step by stage against a bare Box2D loop");
  opts->scene.add_to(*cmd, false);
  cmd->add_option("--repeats", opts->repeats, "timed repeats (median reported)")
      ->check(whole_number(1, 1000));
  cmd->add_option("--steps", opts->steps, "steps per repeat")->check(whole_number(1, 100000000));
  cmd->add_flag("--scaling", opts->scaling,
                "the cost per grain-step at 250, 1000 and 5000 grains, with and without dipoles");
  cmd->add_option("--csv", opts->csv, "write the table as CSV here");
  cmd->callback([opts, &action] { action = [opts] { return bench_sim(*opts); }; });
  add_bench_arch_command(*bench, action);
  add_bench_accuracy_command(*bench, action);
  add_bench_stability_command(*bench, action);
  add_bench_sweep_command(*bench, action);
  add_bench_record_command(*bench, action);
  add_bench_roundtrip_command(*bench, action);
}

}  // namespace app
