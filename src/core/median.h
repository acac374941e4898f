// The median of a sample, shared by every layer (analysis, benchmarks, the importer and the windows' redraw
// timing); the statistics of results (means, intervals, survival) are analysis/stats.h.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

namespace core {

// Median of a sample (mean of the middle two for an even count); NaN when empty.
inline double median(std::vector<double> v) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace core
