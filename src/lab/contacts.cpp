// Contacts and the blocking arch from positions alone (lab/contacts.h).
#include "lab/contacts.h"

#include <algorithm>

namespace lab {

core::ContactGraph contacts_by_distance(const std::vector<core::Vec2>& pos, const std::vector<double>& radius,
                                        const std::vector<bool>& present, const core::Geometry& geo,
                                        double tolerance) {
  const int n = static_cast<int>(pos.size());
  core::ContactGraph g(n);
  const core::Segment& left = geo.walls[static_cast<int>(core::Wall::HopperLeft)];
  const core::Segment& right = geo.walls[static_cast<int>(core::Wall::HopperRight)];
  // Grains sorted by x: only neighbours within the largest reach are compared.
  std::vector<int> order;
  double rmax = 0;
  for (int i = 0; i < n; ++i)
    if (present[static_cast<size_t>(i)] &&
        pos[static_cast<size_t>(i)].y > -2 * radius[static_cast<size_t>(i)])
      order.push_back(i), rmax = std::max(rmax, radius[static_cast<size_t>(i)]);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return pos[a].x < pos[b].x; });
  const double reach_max = 2 * rmax * (1 + tolerance);
  for (size_t a = 0; a < order.size(); ++a) {
    const int i = order[a];
    const double ri = radius[static_cast<size_t>(i)];
    const double wall_gap = tolerance * 2 * ri;
    g.touches_left[i] = core::distance_to_segment(pos[i], left) <= ri + wall_gap;
    g.touches_right[i] = core::distance_to_segment(pos[i], right) <= ri + wall_gap;
    if (geo.obstacle.present() && geo.obstacle.gap(pos[i]) <= ri + wall_gap) g.on_obstacle.push_back(i);
    for (size_t b = a + 1; b < order.size(); ++b) {
      const int j = order[b];
      if (pos[j].x - pos[i].x > reach_max) break;
      const double rj = radius[static_cast<size_t>(j)];
      const double reach = ri + rj + tolerance * 2 * std::min(ri, rj);
      const core::Vec2 d = pos[i] - pos[j];
      if (core::dot(d, d) <= reach * reach) g.add_bond(i, j);
    }
  }
  return g;
}

std::vector<int> arch_by_distance(const std::vector<core::Vec2>& pos, const std::vector<double>& radius,
                                  const std::vector<bool>& present, const core::Model& model,
                                  double tolerance) {
  const core::Geometry& geo = model.setup.geo;
  std::vector<int> arch =
      core::find_arch(contacts_by_distance(pos, radius, present, geo, tolerance), pos,
                      model.scene.arch_wall_reach, geo.kind == core::ContainerKind::Hopper);
  if (!core::blocks_outlet(arch, pos, radius, geo.half_aperture)) arch.clear();
  return arch;
}

}  // namespace lab
