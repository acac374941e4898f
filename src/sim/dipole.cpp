#include "sim/dipole.h"

#include <algorithm>
#include <cmath>

namespace sim {

namespace {
// One pair: Newton's third law, each pair once.
inline void add_pair(const std::vector<core::Vec2>& pos, const std::vector<double>& moment, size_t i,
                     size_t j, double c2, std::vector<core::Vec2>& out, long& pairs) {
  const double dx = pos[i].x - pos[j].x, dy = pos[i].y - pos[j].y;
  const double r2 = dx * dx + dy * dy;
  if (r2 > c2) return;
  const double k = kDipolePrefactor * moment[i] * moment[j] / (r2 * r2 * std::sqrt(r2));
  out[i].x += k * dx;
  out[i].y += k * dy;
  out[j].x -= k * dx;
  out[j].y -= k * dy;
  ++pairs;
}
}  // namespace

long dipole_forces(const std::vector<core::Vec2>& pos, const std::vector<double>& moment, double cutoff,
                   std::vector<core::Vec2>& out, DipoleCells& cells) {
  const size_t n = pos.size();
  out.assign(n, core::Vec2{});
  long pairs = 0;
  if (cutoff <= 0) {
    for (size_t i = 0; i < n; ++i)
      for (size_t j = i + 1; j < n; ++j) add_pair(pos, moment, i, j, INFINITY, out, pairs);
    return pairs;
  }
  if (n < 2) return 0;
  // Cells at least `cutoff` wide over the bounding box: a pair within the cutoff lies in one cell or two
  // neighbouring ones. A grain flung far away would make the grid huge: the cells grow instead (still
  // correct), so there are never many more cells than grains.
  double x0 = pos[0].x, x1 = x0, y0 = pos[0].y, y1 = y0;
  for (const auto& p : pos)
    x0 = std::min(x0, p.x), x1 = std::max(x1, p.x), y0 = std::min(y0, p.y), y1 = std::max(y1, p.y);
  double size = cutoff;
  long nx = 0, ny = 0;
  for (;;) {
    nx = static_cast<long>((x1 - x0) / size) + 1;
    ny = static_cast<long>((y1 - y0) / size) + 1;
    if (nx * ny <= 4 * static_cast<long>(n) + 64) break;
    size *= 2;
  }
  const size_t ncell = static_cast<size_t>(nx * ny);
  cells.cell_of.resize(n);
  cells.start.assign(ncell + 1, 0);
  for (size_t i = 0; i < n; ++i) {
    const long cx = static_cast<long>((pos[i].x - x0) / size), cy = static_cast<long>((pos[i].y - y0) / size);
    cells.cell_of[i] = static_cast<int>(cy * nx + cx);
    ++cells.start[static_cast<size_t>(cells.cell_of[i]) + 1];
  }
  for (size_t c = 0; c < ncell; ++c) cells.start[c + 1] += cells.start[c];
  cells.order.resize(n);
  {
    std::vector<int> fill(cells.start.begin(), cells.start.end() - 1);
    for (size_t i = 0; i < n; ++i)
      cells.order[static_cast<size_t>(fill[static_cast<size_t>(cells.cell_of[i])]++)] = static_cast<int>(i);
  }
  const double c2 = cutoff * cutoff;
  const long dx[4] = {1, -1, 0, 1}, dy[4] = {0, 1, 1, 1};  // the forward neighbours: each pair of cells once
  for (long cy = 0; cy < ny; ++cy) {
    for (long cx = 0; cx < nx; ++cx) {
      const size_t c = static_cast<size_t>(cy * nx + cx);
      for (int a = cells.start[c]; a < cells.start[c + 1]; ++a) {
        const size_t i = static_cast<size_t>(cells.order[static_cast<size_t>(a)]);
        for (int b = a + 1; b < cells.start[c + 1]; ++b)
          add_pair(pos, moment, i, static_cast<size_t>(cells.order[static_cast<size_t>(b)]), c2, out, pairs);
        for (int k = 0; k < 4; ++k) {
          const long ox = cx + dx[k], oy = cy + dy[k];
          if (ox < 0 || ox >= nx || oy >= ny) continue;
          const size_t o = static_cast<size_t>(oy * nx + ox);
          for (int b = cells.start[o]; b < cells.start[o + 1]; ++b)
            add_pair(pos, moment, i, static_cast<size_t>(cells.order[static_cast<size_t>(b)]), c2, out,
                     pairs);
        }
      }
    }
  }
  return pairs;
}

long dipole_forces(const std::vector<core::Vec2>& pos, double mu, double cutoff,
                   std::vector<core::Vec2>& out) {
  out.assign(pos.size(), core::Vec2{});
  if (mu == 0.0) return 0;
  DipoleCells cells;
  return dipole_forces(pos, std::vector<double>(pos.size(), mu), cutoff, out, cells);
}

}  // namespace sim
