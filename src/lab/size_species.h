// A grain's species from its measured size alone: the species most likely to have that size, from each
// species' size law in the scene (fixed, uniform or lognormal), blurred by the measurement's own spread, and
// its share of the grains. Where two laws overlap (a lognormal's tail inside a uniform interval) no rule can
// tell every grain apart; this one errs least, and says how often it must err.
#pragma once

#include <vector>

#include "core/setup.h"

namespace lab {

// The spread in log size assumed where nothing measures it (sizes within about 2%), and the least taken (a
// measured spread of 0 would make every size a point).
constexpr double kAssumedSizeSpread = 0.02, kLeastSizeSpread = 0.005;

class SizeSpecies {
 public:
  // `sigma`: the measurement's spread in log size (0.01: sizes within about 1%); sizes are measured in the
  // units the classifier is asked in, log size = log radius + `log_scale`.
  SizeSpecies(const std::vector<core::SpeciesDef>& species, double log_scale, double sigma);

  // The species index for a measured size (> 0).
  int species(double size) const;
  // The mean of log radius under species k's law (m): what a group of its grains' log sizes centres on,
  // less the log scale.
  double mean_log_radius(int k) const;
  // The share of all grains a rule that errs least still gives another species than their own.
  double error_rate() const { return error_rate_; }

 private:
  double lo_ = 0, step_ = 0;  // the grid of log radius the densities are kept on
  double log_scale_ = 0;
  std::vector<std::vector<double>> density_;  // per species, its share times its blurred density of log r
  std::vector<double> mean_log_;
  std::vector<int> best_;  // per grid cell, the most likely species
  double error_rate_ = 0;
};

// A classifier for sizes measured at about `log_scale` (log size = log radius + log_scale, from a
// calibration), refined on the sizes themselves: the sizes nearest a species of one fixed size give the scale
// (the median of their log ratios to its radius: a blurred or outlined picture's bias) and the spread (1.4826
// times their median deviation from it, at least kLeastSizeSpread). Without such a species, or with fewer
// than 5 sizes near one, the scale as given and kAssumedSizeSpread. `spread` (if given) receives the spread
// taken.
SizeSpecies fit_size_species(const std::vector<core::SpeciesDef>& species, std::vector<double> sizes,
                             double log_scale, double* spread = nullptr);

// Tracks' species from their sizes: each track's median size over its frames (one frame's size of a disk
// pressed among others can read a pixel or two off; a track's median does not, and a track keeps one
// species), classified by fit_size_species.
class TrackSizes {
 public:
  // A size of the track's; `measured` false: a stand-in (a band's radius where a rim was not fitted), taken
  // only for a track with no measured size.
  void add(long track, double size, bool measured = true);
  // Each track's species, indexed by its id (an id never added: 0); `log_scale` as fit_size_species takes it.
  // Frees the sizes kept.
  std::vector<int> species(const std::vector<core::SpeciesDef>& species, double log_scale,
                           double* spread = nullptr, double* error_rate = nullptr);

 private:
  std::vector<std::vector<float>> sizes_;  // per track id; a stand-in as its negative
};

}  // namespace lab
