// siloscope bench accuracy: every numerical setting against a fine reference, on the default, pure and
// magnetic scenes: speed (simulated s per CPU second of the discharge), overlaps, Q and Q~ with 95%
// intervals, the distribution of clog durations (KS distance), and the energy drift of an isolated magnetic
// pair. Table, CSV and a chart.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "analysis/stats.h"
#include "app/services/accuracy.h"
#include "app/services/campaign.h"
#include "app/services/cli.h"
#include "app/services/process.h"
#include "app/services/run_outputs.h"
#include "app/services/terminal.h"
#include "core/error.h"
#include "core/format.h"
#include "core/physics.h"
#include "io/metadata.h"
#include "io/output.h"

namespace app {

namespace {
std::string num6(double v) {
  return core::format_g(v, 6);
}
namespace fs = std::filesystem;

struct AccuracyOptions {
  SceneOptions scene;
  int realizations = 6, threads = 2;
  std::string csv = "docs/accuracy/accuracy.csv", chart = "docs/accuracy/accuracy.png";
  std::vector<std::string> scenes = {"default", "pure", "magnetic", "vibrated"};
  std::vector<std::string> settings;  // empty: all; the first is the one the others are compared with
  bool quick = false;
};

constexpr const char* kHeader =
    "setting,scene,dt_s,velocity_iterations,position_iterations,length_scale,continuous,dipole_cutoff_m,"
    "realizations,"
    "failures,sim_per_cpu,speedup_vs_reference,q_per_s,q_ci95,q_tilde_per_s,q_tilde_ci95,q_tilde_rel_error,"
    "q_tilde_within_reference_ci,overlap_mean_pct,overlap_max_pct,clogs,clog_ks_distance,avalanches,"
    "avalanche_mean,avalanche_ci95,avalanche_ks_distance,avalanche_ks_critical,gaps,gap_ks_distance,"
    "gap_ks_critical,pair_energy_drift,clogs_ended,clogs_vibration,vibration_fraction,vibration_fraction_"
    "ci95,"
    "clog_ks_critical,skipped_fraction,arrest_skip,arrest_skip_shift";

std::vector<NumericSetting> settings() {
  // The reference first: the finest setting we can afford. Then one change at a time around the default.
  // Names go into CSV unquoted: no commas.
  return {
      {"reference", 2.5e-4, 30, 10, 10, true, 0},
      {"default", 1e-3, 8, 3, 10, false, 0},
      {"dt=0.5ms", 5e-4, 8, 3, 10, false, 0},
      {"dt=2ms", 2e-3, 8, 3, 10, false, 0},
      {"dt=5ms", 5e-3, 8, 3, 10, false, 0},
      {"iter4-2", 1e-3, 4, 2, 10, false, 0},
      {"iter20-8", 1e-3, 20, 8, 10, false, 0},
      {"metres(L=1)", 1e-3, 8, 3, 1, false, 0},
      {"ccd-on", 1e-3, 8, 3, 10, true, 0},
      {"dt=2ms+iter20-8", 2e-3, 20, 8, 10, false, 0},
      {"dipole-cutoff-1%", 1e-3, 8, 3, 10, false, 0.01},
      // The arrested-state shortcut (scene key arrest_skip) at the default numerics.
      {"skip1", 1e-3, 8, 3, 10, false, 0, 1},
      {"skip3", 1e-3, 8, 3, 10, false, 0, 3},
      {"skip1-shift5%", 1e-3, 8, 3, 10, false, 0, 1, 0.05},
  };
}

// The settings named by --settings, in that order (all when none), each name checked.
std::vector<NumericSetting> chosen_settings(const std::vector<std::string>& names) {
  const std::vector<NumericSetting> all = settings();
  if (names.empty()) return all;
  std::vector<NumericSetting> out;
  for (const auto& n : names) {
    auto it = std::find_if(all.begin(), all.end(), [&](const NumericSetting& s) { return s.name == n; });
    if (it == all.end()) {
      std::string known;
      for (const auto& s : all) known += (known.empty() ? "" : ", ") + s.name;
      throw core::InputError("--settings: '" + n + "' is not a setting; allowed: " + known);
    }
    out.push_back(*it);
  }
  return out;
}

// The share of clogs kicks broke, with a Wilson 95% half-width.
std::pair<double, double> share(long k, long n) {
  if (n <= 0) return {NAN, NAN};
  const double z = 1.959964, p = static_cast<double>(k) / n, d = 1 + z * z / n;
  return {p, z * std::sqrt(p * (1 - p) / n + z * z / (4.0 * n * n)) / d};
}

struct SceneCase {
  std::string name;
  core::Scene scene;
};

// The scene cases the bench compares settings on: the base scene (default), pure, magnetic (dipoles at 10x
// the weight) and vibrated (the 100x kick).
std::vector<SceneCase> scene_cases(const std::vector<std::string>& names, const core::Scene& base) {
  std::vector<SceneCase> scenes;
  for (const auto& name : names) {
    core::Scene s = base;
    if (name == "pure") {
      s.chi = 0;
    } else if (name == "magnetic") {
      s.mu = core::mu_for_force_ratio(s, 10.0);
    } else if (name == "vibrated") {
      s.kick_impulse_max = 5e-3;  // the kick of assets/scenes/paper-vibrated.toml: 100x the literal impulse
    } else if (name != "default") {
      throw core::InputError("--scenes: '" + name +
                             "' is not a scene case; allowed: default, pure, magnetic, vibrated");
    }
    scenes.push_back({name, s});
  }
  return scenes;
}

int bench_accuracy(const AccuracyOptions& o) {
  core::Scene base = o.scene.load();
  const int realizations = o.quick ? 3 : o.realizations;
  const double duration = o.quick ? 15 : o.scene.duration.value_or(60.0);
  if (realizations < 2 || !(duration > 0))
    throw core::InputError("--realizations must be >= 2 and --duration > 0");
  io::check_destination(o.csv, true, "CSV file", io::OutputKind::Csv, kHeader, false);
  base.duration = duration;
  const std::vector<NumericSetting> grid = chosen_settings(o.settings);
  const std::vector<SceneCase> scenes = scene_cases(o.scenes, base);
  std::printf("siloscope %s, bench accuracy: %d realizations x %g s per setting and scene, %d threads\n",
              io::version_string().c_str(), realizations, duration, o.threads);
  for (const auto& sc : scenes)
    std::printf("scene %-8s: r = %g, chi = %g, mu = %.4g A*m^2, kick = %g N*s\n", sc.name.c_str(),
                sc.scene.size_ratio, sc.scene.chi, sc.scene.mu, sc.scene.kick_impulse_max);
  std::printf(
      "KSa, KSg, KSc: KS distance of the avalanche sizes, of the gaps between original exits and of the "
      "clogs'\ndurations from the first setting's (%s), over the distance two samples of one distribution "
      "exceed 5%% of\nthe time (< 1: indistinguishable); vib. %%: clogs a kick broke (95%% interval); "
      "skip%%: "
      "simulated time the\narrested-state shortcut did not integrate; speed: simulated s per CPU s of the "
      "discharge on its\nthread (not wall time: work beside the benchmark does not move the ratios)\n\n",
      grid.front().name.c_str());

  std::string csv = std::string(kHeader) + "\n";
  std::printf("%-17s %-8s %6s %6s %13s %5s %6s %6s %5s %13s %5s %5s %5s %11s %5s %8s\n", "setting", "scene",
              "speed", "x ref", "Q~ [1/s]", "in CI", "ovl %", "max %", "aval", "mean size", "KSa", "KSg",
              "KSc", "vib. %", "skip%", "E drift");
  core::Scene magnetic = base;
  magnetic.mu = core::mu_for_force_ratio(magnetic, 10.0);
  for (const auto& sc : scenes) {
    SettingResult ref;
    analysis::Estimate ref_qt;
    double ref_speed = 0;
    bool first = true;
    for (const auto& st : grid) {
      // The dipole cutoff only matters with dipoles; the magnetic scene is run at the reference and default
      // settings and the cutoff, to keep the benchmark's cost in bounds.
      const bool magnetic_case = sc.name == "magnetic";
      if (st.dipole_cutoff_fraction > 0 && !magnetic_case) continue;
      if (magnetic_case && o.settings.empty() && st.name != "reference" && st.name != "default" &&
          st.dipole_cutoff_fraction == 0)
        continue;
      if (interrupted()) return 130;
      SettingResult r = run_setting(sc.scene, st, realizations, o.threads);
      std::vector<double> qt;
      for (const auto& m : r.runs) qt.push_back(m.q_tilde);
      std::vector<double> q;
      for (const auto& m : r.runs) q.push_back(m.q);
      auto eq = analysis::estimate(q), eqt = analysis::estimate(qt),
           eav = analysis::estimate(r.avalanche_sizes);
      // Throughput per core: the threads ran side by side, each realization single-threaded.
      const double speed = r.cpu_seconds > 0 ? r.sim_seconds / r.cpu_seconds : NAN;
      // The comparisons are with the first setting run (the reference, unless --settings names another
      // first).
      const bool is_ref = first;
      if (first) ref = r, ref_qt = eqt, ref_speed = speed, first = false;
      const double rel = std::abs(eqt.mean - ref_qt.mean) / ref_qt.mean;
      const bool within = std::abs(eqt.mean - ref_qt.mean) <= ref_qt.half_width;
      const double ks = ks_distance(r.clog_durations, ref.clog_durations);
      const double crit_clog = ks_critical_95(r.clog_durations.size(), ref.clog_durations.size());
      const auto vib = share(r.clogs_vibration, r.clogs_ended);
      const double skipped = r.sim_seconds > 0 ? r.skipped_seconds / r.sim_seconds : 0;
      const double ks_av = ks_distance(r.avalanche_sizes, ref.avalanche_sizes);
      const double crit_av = ks_critical_95(r.avalanche_sizes.size(), ref.avalanche_sizes.size());
      const double ks_gap = ks_distance(r.original_gaps, ref.original_gaps);
      const double crit_gap = ks_critical_95(r.original_gaps.size(), ref.original_gaps.size());
      core::Scene cfg = sc.scene;
      st.apply(cfg);
      double drift = NAN;
      if (magnetic_case || st.name != "dipole-cutoff-1%") {
        try {
          drift = pair_energy_drift(magnetic, st, 0.3);
        } catch (const std::exception&) {
        }
      }
      std::printf(
          "%-17s %-8s %6.2f %6.2f %6.3f+-%5.3f %5s %6.2f %6.1f %5zu %6.1f+-%5.1f %5.2f %5.2f %5.2f "
          "%5.2f+-%4.2f "
          "%5.1f %8.2e%s\n",
          st.name.c_str(), sc.name.c_str(), speed, speed / ref_speed, eqt.mean, eqt.half_width,
          within ? "yes" : "no", 100 * r.overlap_mean, 100 * r.overlap_max, r.avalanche_sizes.size(),
          eav.mean, eav.half_width, is_ref ? 0.0 : ks_av / crit_av, is_ref ? 0.0 : ks_gap / crit_gap,
          is_ref ? 0.0 : ks / crit_clog, 100 * vib.first, 100 * vib.second, 100 * skipped, drift,
          r.failures ? ("  FAILED " + std::to_string(r.failures) + "x: " + r.failure.substr(0, 80)).c_str()
                     : "");
      std::fflush(stdout);
      csv += st.name + "," + sc.name + "," + num6(st.dt) + "," + std::to_string(st.velocity_iterations) +
             "," + std::to_string(st.position_iterations) + "," + num6(st.length_scale) + "," +
             (st.continuous ? "1" : "0") + "," + num6(cfg.dipole_cutoff) + "," +
             std::to_string(realizations) + "," + std::to_string(r.failures) + "," + num6(speed) + "," +
             num6(speed / ref_speed) + "," + num6(eq.mean) + "," + num6(eq.half_width) + "," +
             num6(eqt.mean) + "," + num6(eqt.half_width) + "," + num6(rel) + "," + (within ? "1" : "0") +
             "," + num6(100 * r.overlap_mean) + "," + num6(100 * r.overlap_max) + "," +
             std::to_string(r.clog_durations.size()) + "," + num6(ks) + "," +
             std::to_string(r.avalanche_sizes.size()) + "," + num6(eav.mean) + "," + num6(eav.half_width) +
             "," + num6(ks_av) + "," + num6(crit_av) + "," + std::to_string(r.original_gaps.size()) + "," +
             num6(ks_gap) + "," + num6(crit_gap) + "," + num6(drift) + "," + std::to_string(r.clogs_ended) +
             "," + std::to_string(r.clogs_vibration) + "," + num6(vib.first) + "," + num6(vib.second) + "," +
             num6(crit_clog) + "," + num6(skipped) + "," + std::to_string(st.arrest_skip) + "," +
             num6(st.arrest_skip_shift) + "\n";
      // Written after every row (atomically): a bench stopped part-way keeps every row it finished.
      fs::create_directories(fs::path(o.csv).parent_path().empty() ? fs::path(".")
                                                                   : fs::path(o.csv).parent_path());
      io::write_file_atomic(o.csv, csv);
    }
  }
  std::printf("\nwritten %s\n", o.csv.c_str());
  if (!o.chart.empty()) {
    if (run_python(script_path("accuracy_chart.py"), {o.csv, o.chart}) != 0) {
      std::fprintf(stderr, "siloscope: the chart could not be drawn (accuracy_chart.py)\n");
      return 1;
    }
  }
  return 0;
}
}  // namespace

void add_bench_accuracy_command(CLI::App& bench, Action& action) {
  auto o = std::make_shared<AccuracyOptions>();
  auto* cmd = bench.add_subcommand("accuracy",
                                   "speed versus accuracy of every numerical setting against a reference");
  o->scene.add_to(*cmd, false);
  cmd->add_option("--realizations", o->realizations, "seeds per setting and scene")
      ->check(whole_number(1, 1000))
      ->capture_default_str();
  cmd->add_option("--threads", o->threads, "realizations run side by side")
      ->check(whole_number(1, 256))
      ->capture_default_str();
  cmd->add_option("--csv", o->csv, "CSV output")->capture_default_str();
  cmd->add_option("--chart", o->chart, "PNG chart (empty: none)")->capture_default_str();
  cmd->add_option("--scenes", o->scenes,
                  "scene cases: default, pure (chi = 0), magnetic (contact force 10 weights), vibrated (kick "
                  "5e-3 N*s)")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--settings", o->settings,
                  "settings to run, the first being the one the others are compared with (default: all, "
                  "the reference first)")
      ->delimiter(',');
  cmd->add_flag("--quick", o->quick,
                "3 realizations of 15 s: a smoke run of the whole grid (default: 6 of --duration, 60 s)");
  cmd->callback([o, &action] { action = [o] { return bench_accuracy(*o); }; });
}

}  // namespace app
