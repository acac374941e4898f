#include "core/arch.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace core {

namespace {
constexpr double kPi = 3.14159265358979323846;

double distance_to_segment(Vec2 p, Vec2 a, Vec2 b) {
  Vec2 ab = b - a;
  double len2 = dot(ab, ab);
  double t = len2 > 0 ? std::clamp(dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
  return length(p - (a + t * ab));
}
}  // namespace

std::vector<int> shortest_wall_path(const ContactGraph& g, const std::vector<Vec2>& pos, double wall_reach) {
  const int n = g.size();
  // Breadth-first search by layers from every low left-wall disk. Within a layer (same particle count) each
  // disk keeps the predecessor that minimises the sum of heights: this is the lexicographic optimum of
  // (particle count, sum of heights), i.e. fewest particles, ties to the lowest.
  std::vector<int> layer_of(n, -1), prev(n, -1);
  std::vector<double> sum_y(n, std::numeric_limits<double>::infinity());
  std::vector<int> frontier;
  for (int i = 0; i < n; ++i) {
    if (g.touches_left[i] && pos[i].y <= wall_reach) {
      layer_of[i] = 0;
      sum_y[i] = pos[i].y;
      frontier.push_back(i);
    }
  }
  for (int layer = 0; !frontier.empty(); ++layer) {
    // Is any disk of this layer on the right wall? Take the lowest such path.
    int best = -1;
    for (int i : frontier)
      if (g.touches_right[i] && pos[i].y <= wall_reach && (best < 0 || sum_y[i] < sum_y[best])) best = i;
    if (best >= 0) {
      std::vector<int> path;
      for (int i = best; i >= 0; i = prev[i]) path.push_back(i);
      std::reverse(path.begin(), path.end());
      return path;
    }
    std::vector<int> next;
    // The obstacle links every grain touching it (a support, not a grain): those are neighbours of each
    // other.
    std::vector<char> at_obstacle;
    if (!g.on_obstacle.empty()) {
      at_obstacle.assign(static_cast<size_t>(n), 0);
      for (int i : g.on_obstacle) at_obstacle[static_cast<size_t>(i)] = 1;
    }
    for (int u : frontier) {
      std::vector<int> reach = g.neighbours[u];
      if (!at_obstacle.empty() && at_obstacle[static_cast<size_t>(u)])
        for (int o : g.on_obstacle)
          if (o != u) reach.push_back(o);
      for (int v : reach) {
        if (layer_of[v] >= 0 && layer_of[v] <= layer) continue;
        double s = sum_y[u] + pos[v].y;
        if (layer_of[v] < 0) {
          layer_of[v] = layer + 1;
          next.push_back(v);
        }
        if (s < sum_y[v]) {
          sum_y[v] = s;
          prev[v] = u;
        }
      }
    }
    frontier.swap(next);
  }
  return {};
}

std::vector<int> trim_arch(const std::vector<int>& path, const std::vector<Vec2>& pos, Vec2 centre) {
  if (path.empty()) return {};
  const int m = static_cast<int>(path.size());
  int c = 0;
  for (int k = 1; k < m; ++k)
    if (length(pos[path[k]] - centre) < length(pos[path[c]] - centre)) c = k;
  int lo = c, hi = c;
  while (lo > 0 && pos[path[lo - 1]].x < pos[path[lo]].x) --lo;
  while (hi < m - 1 && pos[path[hi + 1]].x > pos[path[hi]].x) ++hi;
  return std::vector<int>(path.begin() + lo, path.begin() + hi + 1);
}

std::vector<int> find_arch(const ContactGraph& g, const std::vector<Vec2>& pos, double wall_reach,
                           bool trim) {
  std::vector<int> path = shortest_wall_path(g, pos, wall_reach);
  return trim ? trim_arch(path, pos) : path;
}

bool blocks_outlet(const std::vector<int>& arch, const std::vector<Vec2>& pos,
                   const std::vector<double>& radius, double half_aperture) {
  if (arch.size() < 2) return false;
  if (!(pos[arch.front()].x < 0 && pos[arch.back()].x > 0)) return false;
  std::vector<char> member(pos.size(), 0);
  for (int id : arch) member[static_cast<size_t>(id)] = 1;
  // The chain's height at x: linear between consecutive members' centres (members run left to right).
  auto chain_y = [&](double x) {
    for (size_t k = 0; k + 1 < arch.size(); ++k) {
      const Vec2 a = pos[arch[k]], b = pos[arch[k + 1]];
      if (x >= std::min(a.x, b.x) && x <= std::max(a.x, b.x))
        return b.x == a.x ? std::min(a.y, b.y) : a.y + (b.y - a.y) * (x - a.x) / (b.x - a.x);
    }
    return -std::numeric_limits<double>::infinity();
  };
  for (size_t i = 0; i < pos.size(); ++i) {
    if (member[i]) continue;
    const Vec2 p = pos[i];
    // Wholly inside the opening's span and not yet through it: a grain on its way out.
    if (std::abs(p.x) > half_aperture - radius[i] || p.y < -radius[i]) continue;
    if (p.y < chain_y(p.x)) return false;
  }
  return true;
}

std::vector<double> bead_angles_deg(const std::vector<int>& ids, const std::vector<Vec2>& pos) {
  // From the bond to the left neighbour, counter-clockwise through "down", to the bond to the right
  // neighbour: 180 deg is flat, below 180 a dome, above 180 a defect pointing at the outlet.
  std::vector<double> angles;
  for (size_t k = 1; k + 1 < ids.size(); ++k) {
    const Vec2 u = pos[ids[k - 1]] - pos[ids[k]], v = pos[ids[k + 1]] - pos[ids[k]];
    double ang = std::atan2(v.y, v.x) - std::atan2(u.y, u.x);
    while (ang < 0) ang += 2 * kPi;
    while (ang >= 2 * kPi) ang -= 2 * kPi;
    angles.push_back(ang * 180.0 / kPi);
  }
  return angles;
}

ArchDescriptors arch_descriptors(const std::vector<int>& ids, const std::vector<Vec2>& pos,
                                 const std::vector<double>& radius) {
  ArchDescriptors d;
  d.grains = static_cast<int>(ids.size());
  if (ids.empty()) return d;
  const Vec2 a = pos[ids.front()], b = pos[ids.back()];
  d.span = (b.x + radius[ids.back()]) - (a.x - radius[ids.front()]);
  // The rise above the chord joining the end members' centres.
  for (int i : ids) {
    const double base = b.x == a.x ? std::max(a.y, b.y) : a.y + (b.y - a.y) * (pos[i].x - a.x) / (b.x - a.x);
    d.rise = std::max(d.rise, pos[i].y - base);
  }
  const double half = 0.5 * d.span;
  d.aspect = half > 0 ? d.rise / half : std::numeric_limits<double>::quiet_NaN();
  d.inverse_aspect = d.rise > 0 ? half / d.rise : std::numeric_limits<double>::infinity();
  const std::vector<double> angles = bead_angles_deg(ids, pos);
  double sum = 0;
  for (double x : angles) {
    d.theta_max_deg = std::max(d.theta_max_deg, x);
    d.defects += x > 180.0;
    sum += x;
  }
  if (angles.size() > 1) {
    const double mean = sum / static_cast<double>(angles.size());
    double ss = 0;
    for (double x : angles) ss += (x - mean) * (x - mean);
    d.angle_sd_deg = std::sqrt(ss / static_cast<double>(angles.size() - 1));
  }
  return d;
}

ArchGeometry arch_geometry(const std::vector<int>& ids, const std::vector<Vec2>& pos,
                           const std::vector<double>& radius) {
  ArchGeometry a;
  if (ids.empty()) return a;
  a.span = (pos[ids.back()].x + radius[ids.back()]) - (pos[ids.front()].x - radius[ids.front()]);
  for (int i : ids) a.height = std::max(a.height, pos[i].y);
  for (double ang : bead_angles_deg(ids, pos)) a.max_angle_deg = std::max(a.max_angle_deg, ang);
  return a;
}

std::vector<int> visible_from_aperture(const std::vector<Vec2>& pos, const std::vector<double>& radius,
                                       double range) {
  const Vec2 centre{0, 0};
  std::vector<int> near;
  for (int i = 0; i < static_cast<int>(pos.size()); ++i)
    if (length(pos[i] - centre) <= range) near.push_back(i);
  std::vector<int> out;
  for (int i : near) {
    bool blocked = false;
    for (int j : near) {
      if (j == i) continue;
      if (distance_to_segment(pos[j], pos[i], centre) < radius[j]) {
        blocked = true;
        break;
      }
    }
    if (!blocked) out.push_back(i);
  }
  std::sort(out.begin(), out.end(), [&](int a, int b) { return pos[a].x < pos[b].x; });
  return out;
}

ContactGraph contacts_from_positions(const std::vector<Vec2>& pos, const std::vector<double>& radius,
                                     const Geometry& geo, double tolerance, double max_height) {
  const int n = static_cast<int>(pos.size());
  ContactGraph g(n);
  std::vector<int> low;
  for (int i = 0; i < n; ++i)
    if (pos[i].y <= max_height) low.push_back(i);
  const Segment& left = geo.walls[static_cast<int>(Wall::HopperLeft)];
  const Segment& right = geo.walls[static_cast<int>(Wall::HopperRight)];
  for (size_t a = 0; a < low.size(); ++a) {
    int i = low[a];
    g.touches_left[i] = distance_to_segment(pos[i], left.a, left.b) <= radius[i] + tolerance;
    g.touches_right[i] = distance_to_segment(pos[i], right.a, right.b) <= radius[i] + tolerance;
    for (size_t b = a + 1; b < low.size(); ++b) {
      int j = low[b];
      double reach = radius[i] + radius[j] + tolerance;
      Vec2 d = pos[i] - pos[j];
      if (dot(d, d) <= reach * reach) g.add_bond(i, j);
    }
  }
  return g;
}

bool same_grains(std::vector<int> a, std::vector<int> b) {
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  return a == b;
}

}  // namespace core
