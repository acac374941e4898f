// The hopper's view of its own state for clog endings and health: whether the outlet is arrested, where the
// packed column ends, how many disks are in flight.
#include <algorithm>
#include <cmath>

#include "core/physics.h"
#include "sim/silo.h"

namespace sim {

bool Silo::outlet_arrested(const std::vector<int>& arch) const {
  if (hold_pos_.size() != bodies_.size()) return false;
  // Held up by an arch, and the arch and everything beneath it (the disks no farther from the outlet centre
  // than its farthest member) held still: disks higher in the column may rattle under strong kicks without
  // that changing whether the outlet is blocked.
  if (arch.empty()) return false;
  double reach = 0;
  for (int id : arch) reach = std::max(reach, core::length(pos(id)) + extent_[id]);
  for (int i = 0; i < particle_count(); ++i) {
    core::Vec2 p = pos(i);
    if (core::length(p) > reach) continue;
    const double limit = scene_.arrest_shift * radius_[i];
    core::Vec2 d = p - hold_pos_[i];
    if (core::dot(d, d) > limit * limit) return false;
  }
  return true;
}

double Silo::column_top(int except) const {
  if (setup_.tilt != 0) return column_top_tilted(except);
  const double slab = geo_.grain_diameter;  // the largest species' mean diameter (the shorthand: 2 r_o)
  const int n_slabs = static_cast<int>(std::ceil(geo_.total_height / slab)) + 1;
  std::vector<double> covered(static_cast<size_t>(n_slabs), 0.0), top_edge(static_cast<size_t>(n_slabs), 0.0);
  for (int j = 0; j < particle_count(); ++j) {
    if (j == except) continue;
    core::Vec2 p = pos(j);
    if (p.y < 0) continue;
    const int k = std::min(n_slabs - 1, static_cast<int>(p.y / slab));
    covered[k] += core::kPi * radius_[j] * radius_[j];
    top_edge[k] = std::max(top_edge[k], p.y + extent_[j]);
  }
  double top = 0;
  for (int k = 0; k < n_slabs; ++k) {
    const double mid = std::min((k + 0.5) * slab, geo_.total_height);
    const double area = geo_.width_at(mid) * slab;
    if (area > 0 && covered[k] >= 0.35 * area) top = std::max(top, top_edge[k]);
  }
  return top;
}

void Silo::sample_airborne() {
  // Heights along gravity (in a tilted container the free surface is level in the laboratory).
  const double top = column_top() + 2.0 * geo_.grain_diameter;
  int n = 0;
  for (int i = 0; i < particle_count(); ++i)
    if (up_height(pos(i)) - extent_[i] > top) ++n;
  const double f = static_cast<double>(n) / std::max(1, particle_count());
  airborne_.sum += f;
  airborne_.max = std::max(airborne_.max, f);
  ++airborne_.samples;
}

}  // namespace sim
