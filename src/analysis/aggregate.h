// Aggregation across realizations: runs are grouped into points by the scene keys that a campaign varies
// (size_ratio, chi, mu, kick_impulse_max); every other key must agree across all runs, and a seed may appear
// once per point. Each point gets means and 95% confidence intervals of the measurements, its pooled survival
// function, and Q~/Q_p against the pure system (chi = 0) when one is present.
#pragma once

#include <string>
#include <vector>

#include "analysis/measure.h"
#include "analysis/stats.h"
#include "core/frame.h"
#include "core/scene.h"
#include "core/setup.h"

namespace analysis {

struct Run {
  std::string source;  // where it came from (a directory), for error messages
  core::Scene scene;
  core::Setup setup;  // the scene compiled where the run was read (core/model.h)
  core::Events events;
  Measurements m;
};

// A realization the health monitor refused (sweep's NAME.refused.toml): its scene, to find its point.
struct Refused {
  std::string source;
  core::Scene scene;
};

struct SpeciesEstimate {
  std::string name;
  long count = 0;          // grains of the species in the scene
  Estimate q;              // its exits per second
  Estimate exit_fraction;  // its share of all exits
  Estimate column_rank;    // its mean height rank in the column (analysis/column.h), over the runs measured
};

struct Point {
  core::Scene scene;  // seed of the first run
  core::Setup setup;  // its compiled setup (the species)
  // Keys the analysis was told to tell points apart by beyond the paper's (analyze --by), with their values.
  std::vector<std::pair<std::string, std::string>> extra;
  std::vector<SpeciesEstimate> species;
  std::vector<SurvivalStep> clog_survival;  // Kaplan-Meier, over every clog of the point's realizations
  long clogs_run_end = 0;                   // clogs still open when a run ended (censored)
  std::vector<const Run*> runs;
  Estimate q, q_tilde, chi_eff, long_arches_per_min, added_per_long_arch, fraction_broken_by_vibration;
  Estimate q_tilde_over_qp;  // NaN mean when no pure point exists
  Estimate q_p;              // Q of the pure point this point is compared with (same kick strength)
  Estimate airborne_fraction;
  Estimate avalanche_mean;  // of the realizations' mean avalanche sizes (disks between clogs)
  long clogs = 0, clogs_vibration = 0, clogs_rule = 0, clogs_spontaneous = 0, ballistic_runs = 0;
  long refused = 0;  // realizations of this point the health monitor refused: not in `runs`, so every
                     // estimate is of the realizations that finished (a selection when this is not 0)
};

// Runs are told apart by the paper's keys (size_ratio, chi, mu, kick_impulse_max) and the keys in `by` (any
// scene key, species.NAME.KEY included: what a campaign of one's own varies). Throws core::InputError when
// runs (or refused realizations) differ in any other key, naming it (and --by), or a seed repeats within a
// point.
std::vector<Point> aggregate(const std::vector<Run>& runs, const std::vector<Refused>& refused = {},
                             const std::vector<std::string>& by = {});

std::string realizations_csv(const std::vector<Run>& runs);
std::string points_csv(const std::vector<Point>& points);
std::string pooled_survival_csv(const std::vector<Point>& points);
// Per point and species: exits per second and share of the exits, with 95% intervals.
std::string species_points_csv(const std::vector<Point>& points);
// The drain protocol (scene drain = true), per point: realizations emptied, jammed and still draining at the
// end; the jamming probability J = jammed / (jammed + emptied) with its Wilson 95% interval (the unit: one
// realization); the mean number of grains out before the jam. Empty when no run drained.
std::string drain_csv(const std::vector<Point>& points);
// Per point, the Kaplan-Meier survival S(t) of the clogs' durations with its 95% band; clogs the rule removed
// or the run's end cut short are censored (clog_survival.csv). With the rule on, S stops at clog_timeout.
std::string clog_survival_csv(const std::vector<Point>& points);
// Per point and species, where the species sits in the column (analysis/column.h): its mean height rank (0
// the bottom, 1/2 spread evenly, 1 the top) with its 95% interval over the realizations that kept a
// trajectory (n_runs_measured of n_runs; the unit: one realization), and the frames measured. Empty when no
// run kept a trajectory (column.csv is then not written).
std::string column_csv(const std::vector<Point>& points);
// P(S >= s) of the avalanche sizes S (disks between two clogs) pooled over each point's realizations, at
// s = 1..10 and then about 20 sizes per decade up to the largest; `avalanches` is the number pooled.
std::string pooled_avalanches_csv(const std::vector<Point>& points);

}  // namespace analysis
