// siloscope figures DIR: the paper's figures from a campaign's tidy CSV, drawn by matplotlib
// (src/figures/figures.py) so users can restyle them without touching C++.
#include <sys/wait.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>

#include "analysis/claims.h"
#include "app/services/cli.h"
#include "app/services/process.h"
#include "app/services/run_outputs.h"
#include "app/services/terminal.h"
#include "core/error.h"
#include "core/format.h"
#include "io/manifest.h"
#include "io/metadata.h"
#include "io/output.h"

namespace app {

namespace {
namespace fs = std::filesystem;

// DIR itself, or DIR/analysis when only that holds `file`: a campaign's results directory or its analysis.
fs::path analysis_holding(const fs::path& dir, const char* file) {
  return !fs::exists(dir / file) && fs::exists(dir / "analysis" / file) ? dir / "analysis" : dir;
}

struct FiguresOptions {
  std::string dir, out;
  bool force = false;
};

int figures(const FiguresOptions& o) {
  // DIR may be a campaign's results directory (with analysis/) or an analysis directory itself.
  const fs::path src = analysis_holding(o.dir, "points.csv");
  if (!fs::exists(src / "points.csv"))
    throw core::InputError("figures: " + o.dir +
                           " holds no points.csv (run `siloscope analyze` or `sweep` first)");
  fs::path out = o.out.empty() ? src.parent_path() / "figures" : fs::path(o.out);
  const char* env = std::getenv("SILOSCOPE_FIGURES_SCRIPT");
  fs::path script = env ? env : script_path("figures.py");
  if (!fs::exists(script)) throw core::InputError("figures: the script " + script.string() + " is missing");
  if (run_process({python_interpreter(), "-c", "import matplotlib, pandas"}, "", "/dev/null") != 0)
    throw core::RuntimeFault(
        "figures: python3 with matplotlib and pandas is needed (Debian: apt-get install "
        "python3-matplotlib python3-pandas)");
  // Drawn into a temporary directory, moved into place when complete; an existing figures directory is
  // replaced only with --force and only when it is siloscope's figures holding what its manifest lists.
  io::check_not_input(io::output_path(out.string()), {src}, "figures directory");
  io::OutputDir dir(out.string(), o.force, io::DirKind::Figures);
  const fs::path tmp = dir.file("");
  const int status = run_python(script.string(), {src.string(), tmp.string()});
  if (status == 2)
    throw core::InputError("figures: " + src.string() + " cannot be drawn (the line above says why)");
  if (status != 0) throw core::RuntimeFault("figures: the matplotlib script " + script.string() + " failed");
  std::string meta = "# siloscope figures metadata: made from the analysis in [run].source\n[siloscope]\n" +
                     std::string("version = ") + core::toml_string(io::version_string()) + "\n" +
                     "command = " + core::toml_string(command_line()) +
                     "\n\n[run]\nsource = " + core::toml_string(fs::absolute(src).string()) + "\n";
  io::write_file_atomic(dir.file(io::kMetadataFile), meta);
  dir.commit();
  std::printf("figures in %s\n", out.c_str());
  return 0;
}
}  // namespace

namespace {
struct ClaimsOptions {
  std::vector<std::string> results, columns;
  std::string out;
  bool force = false;
};

int claims(const ClaimsOptions& o) {
  std::vector<std::string> specs;
  for (const auto& r : o.results) {
    const auto eq = r.find('=');
    if (eq == std::string::npos || eq == 0)
      throw core::InputError("claims: '" + r +
                             "': expected LABEL=RESULTS, e.g. literal=docs/campaigns/paper");
    const fs::path dir = analysis_holding(r.substr(eq + 1), "points.csv");
    if (!fs::exists(dir / "points.csv"))
      throw core::InputError("claims: " + r.substr(eq + 1) +
                             " holds no points.csv (run `siloscope analyze` first)");
    // Checked against the analysis' manifest first: a table cut or edited after analyze wrote it is refused
    // naming it, not judged.
    for (const char* f : {"points.csv", "realizations.csv", "column.csv"})
      if (fs::exists(dir / f)) io::verify_listed(dir / f, "claims: analysis table");
    specs.push_back(r.substr(0, eq) + "=" + dir.string());
  }
  // --column LABEL=DIR: where each species sits, measured by another campaign at the same points.
  std::map<std::string, std::string> column_of;
  for (const auto& c : o.columns) {
    const auto eq = c.find('=');
    const std::string label = eq == std::string::npos ? "" : c.substr(0, eq);
    if (label.empty() || std::none_of(specs.begin(), specs.end(), [&](const std::string& s) {
          return s.compare(0, label.size() + 1, label + "=") == 0;
        }))
      throw core::InputError("claims: --column '" + c +
                             "': expected LABEL=RESULTS with LABEL one of the presets "
                             "given (e.g. --column literal=docs/campaigns/column)");
    const fs::path dir = analysis_holding(c.substr(eq + 1), "column.csv");
    if (fs::exists(dir / "column.csv")) io::verify_listed(dir / "column.csv", "claims: analysis table");
    column_of[label] = dir.string();
  }
  std::vector<analysis::claims::Preset> presets;
  for (const auto& spec : specs) {
    const auto eq = spec.find('=');
    const std::string label = spec.substr(0, eq);
    presets.push_back(analysis::claims::judge(label, spec.substr(eq + 1),
                                              column_of.count(label) ? column_of[label] : std::string()));
  }
  const fs::path out = o.out;
  fs::path table = out;
  table.replace_extension(".csv");
  if (table == out) table += ".csv";
  io::OutputLock lock(out);
  io::check_destination(out, o.force, "claims table", io::OutputKind::Csv,
                        "# The paper's seven claims against siloscope's results");
  io::check_destination(table, o.force, "claims table (CSV)", io::OutputKind::Csv,
                        analysis::claims::kCsvHeader);
  io::write_output(table, analysis::claims::csv(presets));
  io::write_output(out, analysis::claims::markdown(presets, io::version_string()));
  for (const auto& p : presets) std::printf("%s\n", analysis::claims::summary_line(p).c_str());
  std::printf("claims per comparison in %s\n", table.c_str());
  std::printf("claims table in %s\n", out.c_str());
  return 0;
}
}  // namespace

void define_claims_command(CLI::App& command, Action& action) {
  auto o = std::make_shared<ClaimsOptions>();
  CLI::App* cmd = &command;
  cmd->add_option("results", o->results,
                  "LABEL=RESULTS (a campaign's results or analysis directory), one per preset")
      ->required();
  cmd->add_option("--out", o->out, "the Markdown table, e.g. docs/campaigns/paper/claims.md")->required();
  cmd->add_option(
      "--column", o->columns,
      "LABEL=RESULTS: where each species sits in the column (C4.2) from another campaign at the same "
      "points whose runs kept trajectories (its analysis' column.csv); repeatable, one per preset");
  cmd->add_flag("--force", o->force, "replace an earlier claims table");
  cmd->callback([o, &action] { action = [o] { return claims(*o); }; });
}

void define_figures_command(CLI::App& command, Action& action) {
  auto o = std::make_shared<FiguresOptions>();
  CLI::App* cmd = &command;
  cmd->add_option("dir", o->dir, "a sweep's results directory, or an analysis directory (points.csv)")
      ->required();
  cmd->add_option("--out", o->out, "output directory (default: next to the analysis, figures/)");
  cmd->add_flag("--force", o->force, "replace an existing figures directory (only one siloscope made)");
  cmd->callback([o, &action] { action = [o] { return figures(*o); }; });
}

}  // namespace app
