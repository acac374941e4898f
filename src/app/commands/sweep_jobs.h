// A campaign's realizations as jobs (the command each runs), and their emission for GNU parallel and a SLURM
// array (`sweep --emit-jobs`): the list, the array's task length from the finished realizations' wall times.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "app/services/campaign.h"

namespace app {

struct SweepJob {
  size_t point;
  int index;
  std::string dir;                // relative to the results directory
  std::vector<std::string> argv;  // the command, run from the results directory (locally: no shell)
  std::string line;               // the same as one shell line, for jobs.txt (GNU parallel, SLURM)
};

// Wall time a finished realization took (settling + discharge), from its metadata; < 0 if not recorded.
double realization_wall_s(const std::filesystem::path& metadata);

// Writes RESULTS/jobs.txt (one shell line per job) and RESULTS/jobs.slurm (an array of tasks of about
// task_minutes each at the finished realizations' median wall time, at most max_array tasks), and prints how
// to submit them.
void emit_jobs(const Campaign& c, const std::filesystem::path& dir, const std::vector<SweepJob>& jobs,
               double task_minutes, int max_array);

}  // namespace app
