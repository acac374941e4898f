#include "sim/dipole.h"

#include <cmath>

namespace sim {

long dipole_forces(const std::vector<core::Vec2>& pos, double mu, double cutoff,
                   std::vector<core::Vec2>& out) {
  const size_t n = pos.size();
  out.assign(n, core::Vec2{});
  if (mu == 0.0) return 0;
  const double c2 = cutoff > 0 ? cutoff * cutoff : INFINITY;
  const double pre = kDipolePrefactor * mu * mu;
  long pairs = 0;
  // Newton's third law: each pair once.
  for (size_t i = 0; i < n; ++i) {
    for (size_t j = i + 1; j < n; ++j) {
      double dx = pos[i].x - pos[j].x, dy = pos[i].y - pos[j].y;
      double r2 = dx * dx + dy * dy;
      if (r2 > c2) continue;
      double k = pre / (r2 * r2 * std::sqrt(r2));
      out[i].x += k * dx;
      out[i].y += k * dy;
      out[j].x -= k * dx;
      out[j].y -= k * dy;
      ++pairs;
    }
  }
  return pairs;
}

}  // namespace sim
