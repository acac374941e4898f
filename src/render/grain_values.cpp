#include "render/grain_values.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "core/forces.h"

namespace render {

std::vector<float> coordination(const core::Frame& f) {
  const size_t n = f.particles.size();
  std::vector<float> z(n, 0.0f);
  if (!f.contacts.empty()) {
    for (const auto& c : f.contacts)
      if (c.a >= 0 && c.b >= 0 && static_cast<size_t>(c.a) < n && static_cast<size_t>(c.b) < n) {
        z[static_cast<size_t>(c.a)] += 1;
        z[static_cast<size_t>(c.b)] += 1;
      }
    return z;
  }
  // A cell list of the largest reach: each pair is looked at once, in neighbouring cells.
  double rmax = 0;
  for (const auto& p : f.particles) rmax = std::max(rmax, static_cast<double>(p.radius));
  if (n == 0 || !(rmax > 0)) return z;
  const double cell = 2 * rmax * (1 + kCoordinationGap);
  auto key = [](long long i, long long j) { return (i << 32) ^ (j & 0xffffffffLL); };
  std::unordered_map<long long, std::vector<int>> cells;
  for (size_t i = 0; i < n; ++i)
    cells[key(static_cast<long long>(std::floor(f.particles[i].x / cell)),
              static_cast<long long>(std::floor(f.particles[i].y / cell)))]
        .push_back(static_cast<int>(i));
  for (size_t i = 0; i < n; ++i) {
    const auto& a = f.particles[i];
    const long long ci = static_cast<long long>(std::floor(a.x / cell)),
                    cj = static_cast<long long>(std::floor(a.y / cell));
    for (long long di = -1; di <= 1; ++di)
      for (long long dj = -1; dj <= 1; ++dj) {
        auto it = cells.find(key(ci + di, cj + dj));
        if (it == cells.end()) continue;
        for (int j : it->second) {
          if (static_cast<size_t>(j) <= i) continue;
          const auto& b = f.particles[static_cast<size_t>(j)];
          const double reach = (static_cast<double>(a.radius) + b.radius) * (1 + kCoordinationGap);
          const double dx = a.x - b.x, dy = a.y - b.y;
          if (dx * dx + dy * dy <= reach * reach) z[i] += 1, z[static_cast<size_t>(j)] += 1;
        }
      }
  }
  return z;
}

const std::vector<float>& GrainValues::update(const core::Frame& f, const Style& style,
                                              const core::Frame* reference) {
  values_.clear();
  largest_ = 0;
  if (style.color == ColorMode::Coordination) {
    values_ = coordination(f);
  } else if (style.color == ColorMode::Stress) {
    const std::vector<double> p = core::pressures(f);
    values_.assign(f.particles.size(), NAN);
    for (size_t i = 0; i < p.size() && i < values_.size(); ++i) values_[i] = static_cast<float>(p[i]);
  } else if (style.color == ColorMode::Displacement) {
    if (have_ref_ && (f.t < ref_t_ || ref_x_.size() != f.particles.size())) have_ref_ = false;
    const core::Frame* r =
        reference && reference->particles.size() == f.particles.size() ? reference : nullptr;
    if (r && r->t <= f.t) {
      have_ref_ = false;  // the caller's reference, every time
    } else if (!have_ref_ && f.t >= style.displacement_from) {
      r = &f;
    } else {
      r = nullptr;
    }
    if (r) {
      ref_x_.resize(r->particles.size());
      ref_y_.resize(r->particles.size());
      for (size_t i = 0; i < r->particles.size(); ++i)
        ref_x_[i] = r->particles[i].x, ref_y_[i] = r->particles[i].y;
      ref_t_ = r->t;
      have_ref_ = true;
    }
    values_.assign(f.particles.size(), 0.0f);
    if (have_ref_)
      for (size_t i = 0; i < f.particles.size(); ++i) {
        const auto& p = f.particles[i];
        const double dy = p.y - ref_y_[i];
        values_[i] = dy > 4 * p.radius ? NAN : static_cast<float>(std::hypot(p.x - ref_x_[i], dy));
      }
  } else {
    return values_;
  }
  for (float v : values_)
    if (std::isfinite(v)) largest_ = std::max(largest_, static_cast<double>(v));
  return values_;
}

void GrainValues::settle_scale(Style& style) const {
  if (style.color == ColorMode::Displacement && !(style.displacement_max > 0))
    style.displacement_max = std::max(largest_, style.color_min + 1e-6);
}

}  // namespace render
