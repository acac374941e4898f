// A grain's species from its measured size alone: the species most likely to have that size, from each
// species' size law in the scene (fixed, uniform or lognormal), blurred by the measurement's own spread, and
// its share of the grains. Where two laws overlap (a lognormal's tail inside a uniform interval) no rule can
// tell every grain apart; this one errs least, and says how often it must err.
#pragma once

#include <vector>

#include "core/setup.h"

namespace lab {

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

}  // namespace lab
