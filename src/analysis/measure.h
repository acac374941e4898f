// The paper's measurements of one realization, from its event streams.
#pragma once

#include <vector>

#include "core/frame.h"
#include "core/scene.h"

namespace analysis {

// Where an avalanche ends (analyze --avalanche-end):
//   Gaps: at every clog, an exit gap of at least clog_min_gap (the paper's reading, with its kicks);
//   Held: only at a clog the outlet held until something outside it ended it (the clog rule, the drive, or
//         the run's end): a stop that resumed by itself is a transient stop, its avalanche goes on. Without a
//         drive this is the avalanche of the silo literature (Zuriguel et al., PRL 107, 278001, 2011: an
//         avalanche ends when the outlet is arrested).
// avalanche_end_for: Held for a scene without a drive (no kicks, no vibration), Gaps with one.
enum class AvalancheEnd { Gaps, Held };
AvalancheEnd avalanche_end_for(const core::Scene& s);
const char* avalanche_end_name(AvalancheEnd e);

// For a scene with its own species list, "original" means the first species and "added" every other one
// (Q~ is the first species' flow); exits_by_species has each species' own count.
struct Measurements {
  double duration = 0;  // s of discharge analysed
  long exits = 0, exits_original = 0, exits_added = 0;
  std::vector<long> exits_by_species;  // per species index
  double q = 0;                        // exits per second (all species)
  double q_tilde = 0;                  // exits of original disks per second
  double chi_eff = 0;                  // fraction of added disks among the exits (NaN without exits)
  long long_arches = 0;                // clog_timeout rule firings
  double long_arches_per_minute = 0;
  double added_per_long_arch = 0;    // mean number of added disks per long-lasting arch (NaN without arches)
  double members_per_long_arch = 0;  // mean arch size (NaN without arches)
  long clogs = 0;                    // exit gaps >= clog_min_gap, any ending
  long clogs_spontaneous = 0, clogs_vibration = 0, clogs_rule = 0, clogs_run_end = 0;
  double fraction_broken_by_vibration = 0;  // among clogs that ended by vibration or the rule (NaN if none)
  AvalancheEnd avalanche_end = AvalancheEnd::Gaps;  // what ends the avalanches below
  long avalanches = 0;        // complete avalanches between clogs (avalanche_sizes), within `duration`
  double avalanche_mean = 0;  // mean disks (both species) per complete avalanche (NaN if none)
  // Time lapses between consecutive exits of original disks (original_gaps), and how many last at least 1 s
  // and 2 s: per realization, so that the survival P(lapse >= tau) pooled over a point can be resampled by
  // realization (claims, C6).
  long lapses = 0, lapses_ge_1s = 0, lapses_ge_2s = 0;
  // Health, from the run's metadata (not from the events): set by the caller.
  long health_warnings = 0;      // --unsafe warnings
  double airborne_fraction = 0;  // mean fraction of disks in flight above the column
  bool ballistic = false;        // airborne_fraction above the ballistic threshold
  // The drain protocol (scene drain = true): "draining", "emptied" or "jammed" (empty: not a drain), when it
  // ended (s) and the grains left in the container.
  std::string drain_outcome;
  double drain_end_s = 0;
  int drain_remaining = 0;
  // Where each species sits in the column (analysis/column.h), from the run's trajectory: each species' mean
  // height rank and the frames measured; empty when the run kept no trajectory. Set by the caller.
  std::vector<double> column_rank;
  long column_frames = 0;
};

// `clog_min_gap`: the scene's shortest exit gap that counts as a clog, which delimits avalanches;
// `n_species`: how many species the scene has.
Measurements measure(const core::Events& ev, double duration, double clog_min_gap, int n_species = 2,
                     AvalancheEnd end = AvalancheEnd::Gaps);

// Gaps between consecutive exits of original disks, s (added disks may exit in between).
std::vector<double> original_gaps(const std::vector<core::ExitEvent>& exits);

// Avalanche sizes: the number of disks (both species) that exit between two clogs, a clog being an exit gap
// of at least `min_gap` s. The last avalanche is left out (the end of the run cuts it short); a run that
// never clogs gives none. Many samples per run, so it tells numerical settings apart where Q~ per run cannot.
std::vector<double> avalanche_sizes(const std::vector<core::ExitEvent>& exits, double min_gap);
// The same, ended only at the clogs that `end` counts (AvalancheEnd): with Gaps, avalanche_sizes; with Held,
// the exits up to the start of each clog not ended spontaneously (the avalanche the run's end cuts short left
// out).
std::vector<double> avalanche_sizes(const std::vector<core::ExitEvent>& exits,
                                    const std::vector<core::ClogEvent>& clogs, double min_gap,
                                    AvalancheEnd end);

// Survival function P(dt >= tau) of `gaps` at each tau.
std::vector<double> survival(std::vector<double> gaps, const std::vector<double>& taus);

}  // namespace analysis
