// sweep --emit-jobs: the job list and the SLURM array script (app/commands/sweep_jobs.h).
#include "app/commands/sweep_jobs.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <toml++/toml.h>

#include "core/median.h"
#include "io/output.h"
#include "io/run.h"

namespace app {

namespace fs = std::filesystem;
using Job = SweepJob;

// Wall time a finished realization took (settling + discharge), from its metadata; < 0 if not recorded.
double realization_wall_s(const fs::path& metadata) {
  try {
    toml::table t = toml::parse_file(metadata.string());
    auto settle = t["run"]["wall_time_settle_s"].value<double>();
    auto discharge = t["run"]["wall_time_discharge_s"].value<double>();
    if (settle && discharge) return *settle + *discharge;
  } catch (const toml::parse_error&) {
  }
  return -1;
}

namespace {
// The median wall time (s) of the campaign's finished realizations, 0 when none records one.
double median_wall_s(const Campaign& c, const fs::path& dir) {
  std::vector<double> walls;
  for (size_t p = 0; p < c.points.size(); ++p)
    for (int k = 0; k < c.realizations; ++k)
      if (double w = realization_wall_s(dir / "runs" / c.run_dir(p, k) / io::run_file::kMetadata); w > 0)
        walls.push_back(w);
  return walls.empty() ? 0.0 : core::median(walls);
}

// How many realizations one array task runs: as many as fill task_minutes at the measured median wall time
// (one when none is measured yet), and never so few that the tasks exceed max_array.
size_t realizations_per_task(size_t jobs, double median_s, double task_minutes, int max_array) {
  size_t k =
      median_s > 0 ? static_cast<size_t>(std::max(1.0, std::floor(60.0 * task_minutes / median_s))) : 1;
  const size_t least = (jobs + static_cast<size_t>(max_array) - 1) / static_cast<size_t>(max_array);
  return std::max<size_t>({k, least, 1});
}

}  // namespace

void emit_jobs(const Campaign& c, const fs::path& dir, const std::vector<Job>& jobs, double task_minutes,
               int max_array) {
  std::string list;
  for (const auto& j : jobs) list += j.line + "\n";
  io::write_file_atomic(dir / "jobs.txt", list);
  const double median = median_wall_s(c, dir);
  const size_t per = realizations_per_task(jobs.size(), median, task_minutes, max_array);
  const size_t tasks = (jobs.size() + per - 1) / per;
  const std::string n = std::to_string(tasks), k = std::to_string(per);
  std::string slurm =
      "#!/bin/bash\n"
      "# SLURM array for campaign " +
      c.name + ": " + std::to_string(jobs.size()) + " realizations, " + k + " per task (lines (i-1)*" + k +
      "+1 to i*" + k + " of jobs.txt in task i), " + n +
      " tasks. Submit from this directory:\n"
      "#   sbatch --array=1-" +
      n +
      " jobs.slurm\n"
      "# Throttle to K tasks at a time with --array=1-" +
      n +
      "%K. A task that is cancelled, pre-empted or\n"
      "# times out leaves nothing under the run directory it was writing; rerun `siloscope sweep CAMPAIGN\n"
      "# --emit-jobs --results THIS_DIR` and submit again: only missing realizations are listed "
      "(docs/cluster.md).\n"
      "#SBATCH --requeue\n"
      "#SBATCH --job-name=siloscope-" +
      c.name +
      "\n"
      "#SBATCH --cpus-per-task=1\n"
      "#SBATCH --output=logs/slurm-%A_%a.out\n"
      "set -uo pipefail\n"
      "cd \"${SLURM_SUBMIT_DIR:-.}\"\n"
      "mkdir -p logs\n"
      "per=" +
      k +
      "\n"
      "first=$(( (SLURM_ARRAY_TASK_ID - 1) * per + 1 ))\n"
      "last=$(( SLURM_ARRAY_TASK_ID * per ))\n"
      "status=0\n"
      "# Each realization in turn; one that fails does not stop the others (the task fails at the end).\n"
      "while IFS= read -r line; do\n"
      "  eval \"$line\" || status=1\n"
      "done < <(sed -n \"${first},${last}p\" jobs.txt)\n"
      "exit $status\n";
  io::write_file_atomic(dir / "jobs.slurm", slurm);
  std::printf("%zu jobs written to %s/jobs.txt (finished realizations left out)\n", jobs.size(), dir.c_str());
  if (median > 0)
    std::printf(
        "array:         %zu tasks of %zu realizations (about %.3g min each at the median %.3g s per "
        "realization of the finished ones; --task-minutes %g, --max-array %d)\n",
        tasks, per, per * median / 60.0, median, task_minutes, max_array);
  else
    std::printf(
        "array:         %zu tasks of %zu realizations (no finished realization measures a wall time "
        "yet: --task-minutes needs one; run `sweep --up-to 1` first; --max-array %d)\n",
        tasks, per, max_array);
  std::printf("GNU parallel:  cd %s && parallel --joblog logs/parallel.log -j $(nproc) < jobs.txt\n",
              dir.c_str());
  std::printf("SLURM:         cd %s && sbatch --array=1-%zu jobs.slurm\n", dir.c_str(), tasks);
  std::printf("then:          siloscope analyze %s/runs --out %s/analysis --force\n", dir.c_str(),
              dir.c_str());
}

}  // namespace app
