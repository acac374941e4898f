// Shared pieces of the command-line subcommands: scene options, progress display, Ctrl-C handling.
#pragma once

#include <CLI/CLI.hpp>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "analysis/measure.h"
#include "core/frame.h"
#include "core/model.h"
#include "core/scene.h"
#include "io/metadata.h"

namespace sim {
class Silo;
}
namespace io {
struct TrajectoryInfo;
}

namespace app {

// The header of a trajectory of `h`: radii, species, the scene's clog settings, `metadata` (TOML text).
io::TrajectoryInfo trajectory_info(const sim::Silo& h, double frame_interval, const std::string& metadata);

// The [health] table of a run's metadata: warnings under --unsafe, disks in flight, the "ballistic" warning.
io::Facts health_facts(const sim::Silo& h);
// A finished run's measurements over `duration` s of discharge, with its health (for summary.csv).
analysis::Measurements measure_run(const sim::Silo& h, double duration);
// A run's outputs, written the same way by run and record into `dir`: exits/clogs/arches.csv, summary.csv,
// survival.csv and metadata.toml (info, with the run's health added). Returns the measurements of `duration`
// s.
// arch_shapes.csv: per arch the clog rule removed, the descriptors of core::arch_descriptors.
std::string arch_shapes_csv(const core::Events& ev, const std::vector<double>& radii);
analysis::Measurements write_run_outputs(const std::filesystem::path& dir, const sim::Silo& h,
                                         double duration, io::RunInfo info);
// A CLI11 check for integer options: digits only (a sign only where negatives are allowed), within [lo, hi].
// "--seed -1" is refused with the allowed range instead of wrapping to 2^64 - 1.
CLI::Validator whole_number(long double lo, long double hi);
// Levenshtein distance (for "did you mean").
size_t edit_distance(const std::string& a, const std::string& b);

// SCENE [--seed N] [--duration S] [--set key=value ...], shared by run, record and bench.
struct SceneOptions {
  std::string path;
  std::optional<std::uint64_t> seed;
  std::optional<double> duration;
  std::vector<std::string> overrides;
  bool unsafe = false;

  void add_to(CLI::App& cmd, bool scene_required = true);
  // File, then --set, then --seed/--duration/--unsafe; validated. Throws core::InputError.
  core::Scene load() const;
  // The scene compiled once (core/model.h): what a command hands to every layer below it.
  core::Model compile() const;
};

// Debian's python3 (where python3-matplotlib installs), even when another python3 comes first on PATH.
std::string python_interpreter();

// The command line as one string, for metadata.
std::string command_line();
void set_command_line(int argc, char** argv);

// Ctrl-C / SIGTERM: the first sets a flag the long loops poll; a second one terminates at once.
void install_interrupt_handler();
bool interrupted();

// A one-line progress bar on stderr when it is a terminal; silent otherwise (CI logs stay clean).
class Progress {
 public:
  Progress(std::string label, double total, bool enabled = true);
  void update(double done, const std::string& extra = "");
  void finish();

 private:
  std::string label_;
  double total_;
  bool enabled_;
  std::chrono::steady_clock::time_point start_, last_;
};

using Action = std::function<int()>;
void add_run_command(CLI::App& app, Action& action);
void add_bench_command(CLI::App& app, Action& action);
void add_analyze_command(CLI::App& app, Action& action);
void add_record_command(CLI::App& app, Action& action);
void add_sweep_command(CLI::App& app, Action& action);
void add_inspect_command(CLI::App& app, Action& action);
void add_figures_command(CLI::App& app, Action& action);
void add_export_command(CLI::App& app, Action& action);
void add_scene_command(CLI::App& app, Action& action);
void add_gallery_command(CLI::App& app, Action& action);
void add_claims_command(CLI::App& app, Action& action);
// Aggregate run directories (or directories holding them) into out_dir; see `siloscope analyze`.
// Interrupted and unhealthy runs are left out (named on stderr) unless included.
int analyze_runs(const std::vector<std::string>& inputs, const std::string& out_dir, bool force, bool quiet,
                 bool include_interrupted = false, bool include_unhealthy = false,
                 const std::vector<std::string>& by = {});
void add_bench_arch_command(CLI::App& bench, Action& action);
void add_bench_accuracy_command(CLI::App& bench, Action& action);
void add_bench_stability_command(CLI::App& bench, Action& action);
void add_bench_sweep_command(CLI::App& bench, Action& action);
void add_bench_record_command(CLI::App& bench, Action& action);

}  // namespace app
