// The command line's shared pieces: the scene options every simulating command takes, integer checks,
// "did you mean" and the command line as one string (the subcommands' table: app/services/commands.h).
#pragma once

#include <CLI/CLI.hpp>

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/model.h"
#include "core/scene.h"

namespace app {

// A CLI11 check for integer options: digits only (a sign only where negatives are allowed), within [lo, hi].
// "--seed -1" is refused with the allowed range instead of wrapping to 2^64 - 1.
CLI::Validator whole_number(long double lo, long double hi);
// A finite number in [lo, hi]; the message prints the bounds as a person writes them (CLI11's own Range
// printed "0.100000 to 10000.000000").
CLI::Validator number_in(double lo, double hi, const std::string& unit = "");
// Levenshtein distance (for "did you mean").
size_t edit_distance(const std::string& a, const std::string& b);

// A scene given on the command line: a file, or a preset by its name (`paper`: SHARE/scenes/paper.toml);
// throws core::InputError listing the presets when it is neither.
std::string scene_file(const std::string& given);

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

// The command line as one string, for metadata.
std::string command_line();
void set_command_line(int argc, char** argv);

using Action = std::function<int()>;
// Aggregate run directories (or directories holding them) into out_dir; see `siloscope analyze`.
// Interrupted and unhealthy runs are left out (named on stderr) unless included. avalanche_end: "auto" (per
// protocol: analysis::avalanche_end_for), "gaps" or "held" (analysis/measure.h).
int analyze_runs(const std::vector<std::string>& inputs, const std::string& out_dir, bool force, bool quiet,
                 bool include_interrupted = false, bool include_unhealthy = false,
                 const std::vector<std::string>& by = {}, const std::string& avalanche_end = "auto");
// bench record's rule for a stage against its committed figure: "" within 1.5x, else the flag's text.
std::string slowed_stage(const std::string& name, const std::string& stage, double measured,
                         double reference);
// bench's own subcommands (bench is a row of the command table, app/services/commands.h).
void add_bench_arch_command(CLI::App& bench, Action& action);
void add_bench_accuracy_command(CLI::App& bench, Action& action);
void add_bench_stability_command(CLI::App& bench, Action& action);
void add_bench_sweep_command(CLI::App& bench, Action& action);
void add_bench_record_command(CLI::App& bench, Action& action);
void add_bench_roundtrip_command(CLI::App& bench, Action& action);

// A value parsed for a command-line flag: a parser's error (which names the value, not how it was given, so
// that an inspector script can name its own line) gets the flag in front.
template <class F>
auto for_flag(const char* flag, F&& parse) -> decltype(parse()) {
  try {
    return parse();
  } catch (const core::InputError& e) {
    throw core::InputError(std::string(flag) + ": " + e.what());
  }
}

}  // namespace app
