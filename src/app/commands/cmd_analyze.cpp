// siloscope analyze DIR... --out DIR: aggregate runs (from any machine) into tidy CSV with 95% intervals.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "analysis/aggregate.h"
#include "analysis/column.h"
#include "app/services/cli.h"
#include "app/services/process.h"
#include "app/services/run_outputs.h"
#include "app/services/terminal.h"
#include "core/error.h"
#include "core/format.h"
#include "core/interrupt.h"
#include "core/physics.h"
#include "core/setup.h"
#include "io/manifest.h"
#include "io/metadata.h"
#include "io/output.h"
#include "io/run.h"

namespace app {

namespace {
namespace fs = std::filesystem;

struct AnalyzeOptions {
  std::vector<std::string> inputs;
  std::vector<std::string> by;
  std::string out;
  bool force = false;
  bool include_interrupted = false, include_unhealthy = false;
  std::string avalanche_end = "auto";
};

// Run directories (holding metadata.toml and exits.csv) at or below `root`, sorted; and the records of
// realizations the health monitor refused (NAME.refused.toml, written by sweep).
void find_runs(const fs::path& root, std::vector<fs::path>& out, std::vector<fs::path>& refused) {
  std::error_code ec;
  if (!fs::is_directory(root, ec))
    throw core::InputError("analyze: " + root.string() + " is not a directory");
  if (io::is_run_directory(root)) {
    out.push_back(root);
    return;
  }
  std::vector<fs::path> children;
  for (const auto& e : fs::directory_iterator(root, ec)) {
    const std::string name = e.path().filename().string();
    if (e.is_directory() && name.find(".partial-") == std::string::npos) children.push_back(e.path());
    const std::string suffix = ".refused.toml";
    if (e.is_regular_file() && name.size() > suffix.size() &&
        name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0)
      refused.push_back(e.path());
  }
  std::sort(children.begin(), children.end());
  for (const auto& c : children) find_runs(c, out, refused);
}

// A run under a campaign's RESULTS/runs/pPPP/rRRR must be the realization sweep made there: its command line
// runs scenes/pPPP.toml into runs/pPPP/rRRR. A run copied in by hand (another seed, scene or campaign) would
// otherwise be counted as one of the campaign's realizations.
void check_campaign_member(const fs::path& d, const io::RunRecord& rec) {
  const fs::path point = d.parent_path(), runs = point.parent_path();
  if (runs.filename() != "runs" || !fs::exists(runs.parent_path() / "campaign.toml")) return;
  const std::string rel = "runs/" + point.filename().string() + "/" + d.filename().string();
  const std::string cmd = rec.command + " ";
  if (cmd.find(" --out " + rel + " ") == std::string::npos ||
      cmd.find(" scenes/" + point.filename().string() + ".toml ") == std::string::npos)
    throw core::InputError(
        "analyze: " + d.string() + " is not the campaign's realization " + rel + ": its command line (" +
        (rec.command.empty() ? "none" : rec.command) + ") does not run scenes/" + point.filename().string() +
        ".toml into " + rel +
        " (a run copied in by hand?); move it out of the campaign's runs/ to analyse the campaign");
}

// Where each species sits in the column, from the run's trajectory when it kept one (run --trajectory-fps,
// record, or a campaign's trajectory_fps); checked against the run's manifest like its other files.
void measure_column(const io::Run& run, analysis::Run& r) {
  if (!run.has_trajectory()) return;
  const io::Trajectory& traj = run.trajectory();
  analysis::ColumnMeter meter(r.scene.tilt * core::kPi / 180.0, static_cast<int>(r.setup.species.size()));
  for (long k = 0; k < traj.size(); ++k) {
    const core::Frame f = traj.frame(k);
    if (f.t > r.m.duration) break;
    meter.add(f);
  }
  r.m.column_rank = meter.ranks();
  r.m.column_frames = meter.frames();
}

// Run `d` opened once (its manifest checked, its scene compiled, its events read) and measured into `r`;
// false (with the reason in `left_out`) when it is left out: interrupted or unhealthy, unless included.
bool read_run(const fs::path& d, const AnalyzeOptions& o, analysis::Run& r,
              std::vector<std::string>& left_out) {
  r.source = d.string();
  // Each run opened once, here: its manifest checked, its scene compiled, its events read.
  const io::Run run = io::Run::open(d, "analyze", io::Run::kEvents);
  r.scene = run.model().scene;
  r.setup = run.model().setup;
  const core::Setup& setup = r.setup;
  const io::RunRecord& rec = run.record();
  check_campaign_member(d, rec);
  r.events = run.events();
  // A run counts for the discharge time it covered, not the time it planned.
  double covered = rec.covered_s >= 0 ? std::min(rec.covered_s, r.scene.duration) : r.scene.duration;
  if (covered <= 0)
    throw core::InputError("analyze: " + r.source + " was stopped before the aperture opened (" +
                           core::format_g(rec.covered_s) + " s of discharge); remove it or rerun it");
  if (rec.interrupted && !o.include_interrupted) {
    left_out.push_back(r.source + ": interrupted after " + core::format_g(covered, 4) + " of " +
                       core::format_g(r.scene.duration, 4) +
                       " s (--include-interrupted counts it for that time)");
    return false;
  }
  if (rec.health_warnings > 0 && !o.include_unhealthy) {
    left_out.push_back(r.source + ": unhealthy, " + std::to_string(rec.health_warnings) +
                       " --unsafe warnings (--include-unhealthy counts it)");
    return false;
  }
  const analysis::AvalancheEnd end = o.avalanche_end == "auto"   ? analysis::avalanche_end_for(r.scene)
                                     : o.avalanche_end == "held" ? analysis::AvalancheEnd::Held
                                                                 : analysis::AvalancheEnd::Gaps;
  r.m =
      analysis::measure(r.events, covered, r.scene.clog_min_gap, static_cast<int>(setup.species.size()), end);
  r.m.health_warnings = rec.health_warnings;
  r.m.ballistic = rec.ballistic;
  r.m.airborne_fraction = rec.airborne_fraction;
  r.m.drain_outcome = rec.drain_outcome;
  r.m.drain_end_s = rec.drain_end_s;
  r.m.drain_remaining = static_cast<int>(rec.drain_remaining);
  measure_column(run, r);
  return true;
}

// The table analyze prints: each point's runs and its Q~ (or Q and each species' flow for scenes of their
// own species), a mean and its interval in 18 columns, never "nan": what is missing is said instead.
void print_points(const std::vector<analysis::Run>& runs, const std::vector<analysis::Point>& points,
                  const std::string& out, bool drain, bool column) {
  auto pm = [](const analysis::Estimate& e, const char* missing) {
    char b[64];
    if (!std::isfinite(e.mean))
      std::snprintf(b, sizeof b, "%18s", missing);
    else if (!std::isfinite(e.half_width))
      std::snprintf(b, sizeof b, "%9.3f (1 run)   ", e.mean);
    else
      std::snprintf(b, sizeof b, "%9.3f +- %5.3f", e.mean, e.half_width);
    return std::string(b);
  };
  if (!runs.front().scene.shorthand()) {
    // A scene of its own species: the --by keys, Q and each species' flow.
    std::printf("%-32s %4s %18s   %s\n", "point", "runs", "Q [1/s]", "per species [1/s]");
    for (const auto& p : points) {
      std::string label;
      for (const auto& [k, v] : p.extra) label += (label.empty() ? "" : ", ") + k + " = " + v;
      if (label.empty()) label = "(one point)";
      std::string per;
      for (const auto& e : p.species) per += e.name + " " + core::format_g(e.q.mean, 4) + "  ";
      std::printf("%-32s %4zu %s   %s\n", label.c_str(), p.runs.size(), pm(p.q, "no flow").c_str(),
                  per.c_str());
    }
    if (drain) std::printf("drain outcomes and the jamming probability J: %s/drain.csv\n", out.c_str());
    if (column)
      std::printf("where each species sits in the column (from the trajectories): %s/column.csv\n",
                  out.c_str());
    return;
  }
  std::printf("%-32s %4s %18s %18s %14s\n", "point (r, chi, mu, kick)", "runs", "Q~ [1/s]", "Q~/Q_p",
              "chi_eff");
  for (const auto& p : points) {
    char label[64];
    std::snprintf(label, sizeof label, "%g, %g, %g, %g", p.scene.size_ratio, p.scene.chi, p.scene.mu,
                  p.scene.kick_impulse_max);
    const std::string chi_eff =
        std::isfinite(p.chi_eff.mean) ? core::format_g(p.chi_eff.mean, 3) : std::string("no exits");
    std::printf("%-32s %4zu %s %s %14s\n", label, p.runs.size(), pm(p.q_tilde, "no exits").c_str(),
                pm(p.q_tilde_over_qp, "no pure point").c_str(), chi_eff.c_str());
  }
  if (column)
    std::printf("where each species sits in the column (from the trajectories): %s/column.csv\n",
                out.c_str());
}

}  // namespace

int analyze_runs(const std::vector<std::string>& inputs, const std::string& out_dir, bool force, bool quiet,
                 bool include_interrupted, bool include_unhealthy, const std::vector<std::string>& by,
                 const std::string& avalanche_end) {
  AnalyzeOptions o{inputs, by, out_dir, force, include_interrupted, include_unhealthy, avalanche_end};
  if (o.avalanche_end != "auto" && o.avalanche_end != "gaps" && o.avalanche_end != "held")
    throw core::InputError("--avalanche-end " + o.avalanche_end +
                           ": expected auto (held without a drive, gaps with one), gaps or held");
  std::vector<fs::path> dirs, refused_files;
  for (const auto& in : o.inputs) {
    size_t before = dirs.size();
    find_runs(in, dirs, refused_files);
    if (dirs.size() == before)
      throw core::InputError("analyze: no runs under " + in +
                             " (a run directory holds metadata.toml and exits.csv)");
  }
  std::vector<fs::path> input_paths(o.inputs.begin(), o.inputs.end());
  io::check_not_input(io::output_path(o.out), input_paths, "analysis directory");
  io::OutputDir out(o.out, o.force, io::DirKind::Analysis);
  std::vector<analysis::Run> runs;
  runs.reserve(dirs.size());
  std::vector<std::string> left_out;
  for (const auto& d : dirs) {
    core::throw_if_interrupted();
    analysis::Run r;
    if (read_run(d, o, r, left_out)) runs.push_back(std::move(r));
  }
  for (const auto& l : left_out) std::fprintf(stderr, "siloscope: analyze leaves out %s\n", l.c_str());
  if (runs.empty())
    throw core::InputError("analyze: every run was left out (see above); nothing to aggregate");
  std::sort(refused_files.begin(), refused_files.end());
  std::vector<analysis::Refused> refused;
  for (const auto& f : refused_files) {
    core::Scene s = core::load_scene(f.string());
    core::validate(s);
    refused.push_back({f.string(), s});
  }
  auto points = analysis::aggregate(runs, refused, o.by);
  long refused_counted = 0;
  for (const auto& p : points) refused_counted += p.refused;
  if (refused_counted < static_cast<long>(refused.size()))
    std::fprintf(stderr,
                 "siloscope: analyze: %ld refused realizations belong to points with no finished run; they "
                 "appear in no row\n",
                 static_cast<long>(refused.size()) - refused_counted);
  io::write_file_atomic(out.file("realizations.csv"), analysis::realizations_csv(runs));
  io::write_file_atomic(out.file("points.csv"), analysis::points_csv(points));
  io::write_file_atomic(out.file("survival.csv"), analysis::pooled_survival_csv(points));
  io::write_file_atomic(out.file("avalanches.csv"), analysis::pooled_avalanches_csv(points));
  io::write_file_atomic(out.file("species.csv"), analysis::species_points_csv(points));
  io::write_file_atomic(out.file("clog_survival.csv"), analysis::clog_survival_csv(points));
  const std::string drain = analysis::drain_csv(points);
  if (!drain.empty()) io::write_file_atomic(out.file("drain.csv"), drain);
  const std::string column = analysis::column_csv(points);
  if (!column.empty()) io::write_file_atomic(out.file("column.csv"), column);
  io::RunInfo info{command_line(),
                   {{"runs", runs.size()},
                    {"by", o.by},
                    {"points", points.size()},
                    {"runs_left_out", left_out.size()},
                    {"avalanche_end", o.avalanche_end},
                    {"runs_refused", refused.size()},
                    {"ballistic_runs", std::count_if(runs.begin(), runs.end(),
                                                     [](const analysis::Run& r) { return r.m.ballistic; })}},
                   {},
                   {}};
  io::write_file_atomic(out.file(io::kMetadataFile),
                        io::metadata_toml({runs.front().scene, runs.front().setup}, info));
  out.commit();
  if (quiet) return 0;
  std::printf(
      "%zu runs, %zu points -> %s/{points,realizations,survival,avalanches,species,clog_survival}.csv\n",
      runs.size(), points.size(), o.out.c_str());
  print_points(runs, points, o.out, !drain.empty(), !column.empty());
  return 0;
}

void define_analyze_command(CLI::App& command, Action& action) {
  auto opts = std::make_shared<AnalyzeOptions>();
  CLI::App* cmd = &command;
  cmd->add_option("dirs", opts->inputs, "run directories, or directories holding them")->required();
  cmd->add_option("--out", opts->out, "output directory")->required();
  cmd->add_option("--by", opts->by,
                  "also tell points apart by this scene key (repeatable; e.g. aperture, obstacle_height, "
                  "species.grains.sides): what a campaign of your own varies");
  cmd->add_option(
         "--avalanche-end", opts->avalanche_end,
         "what ends an avalanche: gaps (every clog, an exit gap >= clog_min_gap), held (only a clog the "
         "outlet held until the rule, the drive or the run's end ended it; stops that resumed by "
         "themselves are transient), auto (held without a drive, gaps with one)")
      ->capture_default_str();
  cmd->add_flag("--force", opts->force, "replace an existing output directory");
  cmd->add_flag("--include-interrupted", opts->include_interrupted,
                "count interrupted recordings, for the discharge time each covered");
  cmd->add_flag("--include-unhealthy", opts->include_unhealthy,
                "count runs that went on past --unsafe warnings");
  cmd->callback([opts, &action] {
    action = [opts] {
      return analyze_runs(opts->inputs, opts->out, opts->force, false, opts->include_interrupted,
                          opts->include_unhealthy, opts->by, opts->avalanche_end);
    };
  });
}

}  // namespace app
