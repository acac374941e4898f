// siloscope analyze DIR... --out DIR: aggregate runs (from any machine) into tidy CSV with 95% intervals.
#include <cstdio>
#include <filesystem>

#include "analysis/aggregate.h"
#include "app/common.h"
#include "core/error.h"
#include "io/events_csv.h"
#include "io/metadata.h"
#include "io/output.h"

namespace app {

namespace {
namespace fs = std::filesystem;

struct AnalyzeOptions {
  std::vector<std::string> inputs;
  std::string out;
  bool force = false;
};

// Run directories (holding metadata.toml and exits.csv) at or below `root`, sorted.
void find_runs(const fs::path& root, std::vector<fs::path>& out) {
  std::error_code ec;
  if (!fs::is_directory(root, ec)) throw core::InputError("analyze: " + root.string() + " is not a directory");
  if (fs::exists(root / "metadata.toml") && fs::exists(root / "exits.csv")) {
    out.push_back(root);
    return;
  }
  std::vector<fs::path> children;
  for (const auto& e : fs::directory_iterator(root, ec))
    if (e.is_directory() && e.path().filename().string().find(".partial-") == std::string::npos)
      children.push_back(e.path());
  std::sort(children.begin(), children.end());
  for (const auto& c : children) find_runs(c, out);
}

}  // namespace

int analyze_runs(const std::vector<std::string>& inputs, const std::string& out_dir, bool force, bool quiet) {
  AnalyzeOptions o{inputs, out_dir, force};
  std::vector<fs::path> dirs;
  for (const auto& in : o.inputs) {
    size_t before = dirs.size();
    find_runs(in, dirs);
    if (dirs.size() == before)
      throw core::InputError("analyze: no runs under " + in + " (a run directory holds metadata.toml and exits.csv)");
  }
  io::OutputDir out(o.out, o.force);
  std::vector<analysis::Run> runs;
  runs.reserve(dirs.size());
  for (const auto& d : dirs) {
    analysis::Run r;
    r.source = d.string();
    r.scene = core::load_scene((d / "metadata.toml").string());
    core::validate(r.scene);
    r.events = io::read_events(d);
    r.m = analysis::measure(r.events, r.scene.duration);
    runs.push_back(std::move(r));
  }
  auto points = analysis::aggregate(runs);
  io::write_file_atomic(out.file("realizations.csv"), analysis::realizations_csv(runs));
  io::write_file_atomic(out.file("points.csv"), analysis::points_csv(points));
  io::write_file_atomic(out.file("survival.csv"), analysis::pooled_survival_csv(points));
  io::RunInfo info{command_line(), {{"runs", std::to_string(runs.size())}, {"points", std::to_string(points.size())}}};
  io::write_file_atomic(out.file("metadata.toml"), io::metadata_toml(runs.front().scene, info));
  out.commit();
  if (quiet) return 0;
  std::printf("%zu runs, %zu points -> %s/{points,realizations,survival}.csv\n", runs.size(), points.size(),
              o.out.c_str());
  std::printf("%-32s %4s %18s %18s %14s\n", "point (r, chi, mu, kick)", "runs", "Q~ [1/s]", "Q~/Q_p", "chi_eff");
  for (const auto& p : points) {
    char label[64];
    std::snprintf(label, sizeof label, "%g, %g, %g, %g", p.scene.size_ratio, p.scene.chi, p.scene.mu,
                  p.scene.kick_impulse_max);
    std::printf("%-32s %4zu %9.3f +- %5.3f %9.3f +- %5.3f %7.3f\n", label, p.runs.size(), p.q_tilde.mean,
                p.q_tilde.half_width, p.q_tilde_over_qp.mean, p.q_tilde_over_qp.half_width, p.chi_eff.mean);
  }
  return 0;
}

void add_analyze_command(CLI::App& app, Action& action) {
  auto opts = std::make_shared<AnalyzeOptions>();
  auto* cmd = app.add_subcommand("analyze", "aggregate run directories into tidy CSV with 95% confidence intervals");
  cmd->set_version_flag("--version", io::version_string());
  cmd->add_option("dirs", opts->inputs, "run directories, or directories holding them")->required();
  cmd->add_option("--out", opts->out, "output directory")->required();
  cmd->add_flag("--force", opts->force, "replace an existing output directory");
  cmd->callback([opts, &action] { action = [opts] { return analyze_runs(opts->inputs, opts->out, opts->force, false); }; });
}

}  // namespace app
