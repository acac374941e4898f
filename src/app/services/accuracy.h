// Speed versus accuracy: run a scene at a numerical setting (time step, iterations, internal length unit,
// continuous collision, dipole cutoff) over several realizations and measure what the setting costs and buys.
#pragma once

#include "analysis/stats.h"

#include <string>
#include <vector>

#include "analysis/measure.h"
#include "core/scene.h"

namespace app {

using analysis::ks_critical_95;
using analysis::ks_distance;

struct NumericSetting {
  std::string name;
  double dt = 1e-3;
  int velocity_iterations = 8, position_iterations = 3;
  double length_scale = 10;
  bool continuous = false;
  double dipole_cutoff_fraction = 0;  // > 0: cut dipole pairs whose force is below this fraction of a weight
  int arrest_skip = 0;                // the arrested-state shortcut (scene key arrest_skip); 0: off
  double arrest_skip_shift = 0.01;
  void apply(core::Scene& s) const;
};

struct SettingResult {
  double sim_seconds = 0, cpu_seconds = 0;  // simulated, and the discharges' CPU time
  std::vector<analysis::Measurements> runs;
  std::vector<double> clog_durations;  // every clog's duration, pooled over realizations
  std::vector<double>
      avalanche_sizes;                // disks per avalanche between clogs, pooled (analysis::avalanche_sizes)
  std::vector<double> original_gaps;  // s between consecutive original exits, pooled
  double overlap_mean = 0, overlap_max = 0;   // fraction of the smaller radius
  long clogs_ended = 0, clogs_vibration = 0;  // clogs that ended before the run's end, and those a kick broke
  double skipped_seconds = 0;                 // simulated s the shortcut did not integrate, summed
  int failures = 0;
  std::string failure;  // the first health-monitor message
};

// Run `realizations` seeds (1..n) of `scene` at `setting`, `threads` at a time.
SettingResult run_setting(const core::Scene& scene, const NumericSetting& setting, int realizations,
                          int threads);

// Relative energy drift |E(T) - E(0)| / E(0) of two added disks repelling each other in free space (no
// gravity, no kicks) over `seconds` or until a disk nears a wall, integrated at `setting`; the dipole sets
// the energy.
double pair_energy_drift(const core::Scene& scene, const NumericSetting& setting, double seconds);

}  // namespace app
