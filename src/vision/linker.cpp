// Frame-to-frame linking (vision/linker.h).
#include "vision/linker.h"

#include <algorithm>
#include <cmath>

namespace vision {

std::vector<long> Linker::link(const std::vector<Circle>& found) {
  struct Pair {
    double d;
    size_t live, now;
  };
  double rmax = 0;
  for (const Circle& c : found) rmax = std::max(rmax, c.r);
  for (const Live& l : live_) rmax = std::max(rmax, l.r);
  std::vector<long> ids(found.size(), -1);
  std::vector<bool> used(live_.size(), false);
  // Nearest pairs first, within `widen` times the reach: max_step of the largest radius of the prediction,
  // and half the predicted move more (a falling grain gathers speed between frames).
  auto round = [&](double widen) {
    std::vector<Pair> pairs;
    for (size_t a = 0; a < live_.size(); ++a) {
      if (used[a]) continue;
      const Live& l = live_[a];
      const double steps = l.missed + 1;
      const double px = l.x + l.vx * steps, py = l.y + l.vy * steps;
      const double reach = widen * (max_step_ * rmax + 0.5 * std::hypot(l.vx, l.vy) * steps);
      const double size = l.size();
      for (size_t b = 0; b < found.size(); ++b) {
        if (ids[b] >= 0) continue;
        if (found[b].band != l.band && !same_size(found[b], size, l.seen > 0)) continue;
        const double d = std::hypot(found[b].x - px, found[b].y - py);
        if (d <= reach) pairs.push_back({d, a, b});
      }
    }
    std::sort(pairs.begin(), pairs.end(), [](const Pair& p, const Pair& q) { return p.d < q.d; });
    for (const Pair& p : pairs) {
      if (used[p.live] || ids[p.now] >= 0) continue;
      used[p.live] = true;
      Live& l = live_[p.live];
      const Circle& c = found[p.now];
      const double steps = l.missed + 1;
      l.vx = (c.x - l.x) / steps, l.vy = (c.y - l.y) / steps;
      l.x = c.x, l.y = c.y, l.r = c.r, l.band = c.band, l.missed = 0;
      if (c.fitted) l.add_size(c.r);
      ids[p.now] = l.id;
    }
  };
  round(1);
  // The disks and tracks left over, twice as far: a grain starting to fall through the outlet moves more in
  // a frame than a resting grain's track reaches, and its last move says little yet (a new track has none).
  round(2);
  std::vector<Live> next;
  for (size_t a = 0; a < live_.size(); ++a) {
    if (!used[a]) ++live_[a].missed;
    if (live_[a].missed <= memory_) next.push_back(live_[a]);
  }
  for (size_t b = 0; b < found.size(); ++b)
    if (ids[b] < 0) {
      ids[b] = next_id_++;
      next.push_back({ids[b], found[b].x, found[b].y, 0, 0, found[b].r, found[b].band, 0});
      if (found[b].fitted) next.back().add_size(found[b].r);
    }
  live_ = std::move(next);
  return ids;
}

bool Linker::same_size(const Circle& c, double size, bool size_measured) const {
  if (c.fitted && size_measured) {
    const double ratio = c.r / size;
    return ratio <= 1 + size_band_ && ratio * (1 + size_band_) >= 1;
  }
  // A band's radius (a rim not fitted) says only that the size lies within the band around it.
  const double nominal = c.fitted ? size : c.r, other = c.fitted ? c.r : size;
  return std::fabs(other / nominal - 1) <= size_band_;
}

double Linker::Live::size() const {
  if (seen == 0) return r;
  std::array<float, kSizes> s = sizes;
  const int n = std::min(seen, kSizes);
  std::nth_element(s.begin(), s.begin() + n / 2, s.begin() + n);
  return s[static_cast<size_t>(n / 2)];
}

}  // namespace vision
