#include "render/trails.h"

#include <algorithm>
#include <cmath>

namespace render {

void Trails::update(const core::Frame& f, const std::vector<int>& ids, double keep_s) {
  keep_s_ = keep_s;
  if (any_ && (f.t < last_t_ || f.t > last_t_ + keep_s)) at_.clear();
  any_ = true;
  last_t_ = f.t;
  for (auto it = at_.begin(); it != at_.end();)  // grains no longer tracked
    it = std::find(ids.begin(), ids.end(), it->first) == ids.end() ? at_.erase(it) : std::next(it);
  for (int id : ids) {
    if (id < 0 || static_cast<size_t>(id) >= f.particles.size()) continue;
    auto& q = at_[id];
    const auto& p = f.particles[static_cast<size_t>(id)];
    if (!q.empty() && q.back().t == f.t) continue;
    q.push_back({f.t, p.x, p.y});
    while (!q.empty() && q.front().t < f.t - keep_s) q.pop_front();
  }
}

void Trails::append(DrawList& list, const core::Frame& f, Rgba color) const {
  for (const auto& [id, q] : at_) {
    if (static_cast<size_t>(id) >= f.particles.size() || q.size() < 2) continue;
    const float r = f.particles[static_cast<size_t>(id)].radius;
    for (size_t k = 1; k < q.size(); ++k) {
      const Point &a = q[k - 1], &b = q[k];
      if (std::hypot(b.x - a.x, b.y - a.y) > 6 * r) continue;  // re-injected: no line across the silo
      const double age = f.t - b.t;
      const float alpha = static_cast<float>(std::clamp(1.0 - age / std::max(1e-9, keep_s_), 0.1, 1.0));
      SegmentInstance s{a.x, a.y, b.x, b.y, {color.r, color.g, color.b, color.a * alpha}, 0};
      list.trails.push_back(s);
      list.trail_width_m.push_back(r / 3);
    }
  }
}

size_t Trails::points(int id) const {
  auto it = at_.find(id);
  return it == at_.end() ? 0 : it->second.size();
}

}  // namespace render
