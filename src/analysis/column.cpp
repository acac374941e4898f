#include "analysis/column.h"

#include <algorithm>
#include <cmath>

namespace analysis {

ColumnMeter::ColumnMeter(double tilt, int n_species)
    : up_x_(std::sin(tilt)),
      up_y_(std::cos(tilt)),
      sum_(static_cast<size_t>(std::max(n_species, 1)), 0.0),
      seen_(sum_.size(), 0) {}

void ColumnMeter::add(const core::Frame& f) {
  if (f.t < 0) return;
  order_.clear();
  for (const auto& p : f.particles) {
    // Heights from the outlet, which moves with a vibrating container.
    const double h = (p.x - f.container_x) * up_x_ + (p.y - f.container_y) * up_y_;
    const int s = core::species_index(p.species);
    if (h > 0 && s >= 0 && static_cast<size_t>(s) < sum_.size()) order_.push_back({h, s});
  }
  if (order_.empty()) return;
  std::sort(order_.begin(), order_.end());
  std::vector<double> rank(sum_.size(), 0.0);
  std::vector<long> count(sum_.size(), 0);
  const double n = static_cast<double>(order_.size());
  for (size_t i = 0; i < order_.size(); ++i) {
    const auto s = static_cast<size_t>(order_[i].second);
    rank[s] += (static_cast<double>(i) + 0.5) / n;
    ++count[s];
  }
  for (size_t s = 0; s < sum_.size(); ++s)
    if (count[s] > 0) sum_[s] += rank[s] / static_cast<double>(count[s]), ++seen_[s];
  ++frames_;
}

std::vector<double> ColumnMeter::ranks() const {
  std::vector<double> out(sum_.size(), NAN);
  for (size_t s = 0; s < sum_.size(); ++s)
    if (seen_[s] > 0) out[s] = sum_[s] / static_cast<double>(seen_[s]);
  return out;
}

}  // namespace analysis
