// A tilted container: heights along gravity (its free surface is level in the laboratory, not across the
// container), filling it upright and turning it before the outlet opens, and re-injecting exits onto its free
// surface. An upright container takes none of these paths (its runs stay bit for bit).
#include <box2d/box2d.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/physics.h"
#include "core/portable_math.h"
#include "sim/silo.h"

namespace sim {

double Silo::up_height(core::Vec2 p) const {
  return setup_.tilt == 0 ? p.y : core::dot(p, up_);
}

const std::vector<Silo::Level>& Silo::levels() const {
  // The container cut by lines across gravity, one grain diameter apart: where each line enters and leaves
  // the container (the first and last of 512 samples inside it along the line). Geometry only: made once.
  if (!levels_.empty()) return levels_;
  const core::Vec2 across{up_.y, -up_.x};
  const core::Vec2 corners[] = {{geo_.x_left, 0},
                                {geo_.x_right, 0},
                                {geo_.x_left, geo_.total_height},
                                {geo_.x_right, geo_.total_height},
                                {-geo_.half_aperture, 0},
                                {geo_.half_aperture, 0}};
  double h0 = INFINITY, h1 = -INFINITY, s0 = INFINITY, s1 = -INFINITY;
  for (const auto& c : corners) {
    h0 = std::min(h0, core::dot(c, up_)), h1 = std::max(h1, core::dot(c, up_));
    s0 = std::min(s0, core::dot(c, across)), s1 = std::max(s1, core::dot(c, across));
  }
  const double slab = geo_.grain_diameter;
  constexpr int kSamples = 512;
  for (double h = h0 + 0.5 * slab; h < h1 + slab; h += slab) {
    Level lv{h - 0.5 * slab, INFINITY, -INFINITY};
    for (int k = 0; k < kSamples; ++k) {
      const double s = s0 + (s1 - s0) * (k + 0.5) / kSamples;
      const core::Vec2 p = h * up_ + s * across;
      if (p.y < 0 || p.y > geo_.total_height || p.x < geo_.left_at(p.y) || p.x > geo_.right_at(p.y)) continue;
      lv.s_min = std::min(lv.s_min, s), lv.s_max = std::max(lv.s_max, s);
    }
    levels_.push_back(lv);
  }
  return levels_;
}

double Silo::column_top_tilted(int except) const {
  // As column_top, in slabs across gravity: a tilted container's free surface lies across gravity, not across
  // the container (heights along gravity's up direction, up_height).
  const std::vector<Level>& lv = levels();
  const double slab = geo_.grain_diameter, h0 = lv.front().h;
  const int n_slabs = static_cast<int>(lv.size());
  std::vector<double> covered(lv.size(), 0.0), top_edge(lv.size(), -INFINITY);
  for (int j = 0; j < particle_count(); ++j) {
    if (j == except) continue;
    const core::Vec2 p = pos(j);
    if (p.y < 0) continue;
    const double h = up_height(p);
    const int k = std::clamp(static_cast<int>((h - h0) / slab), 0, n_slabs - 1);
    covered[k] += core::kPi * radius_[j] * radius_[j];
    top_edge[k] = std::max(top_edge[k], h + extent_[j]);
  }
  double top = h0;
  for (int k = 0; k < n_slabs; ++k) {
    const double area = (lv[k].s_max - lv[k].s_min) * slab;
    if (area > 0 && covered[k] >= 0.35 * area) top = std::max(top, top_edge[k]);
  }
  return top;
}

void Silo::settle_tilted() {
  // Grains dropped into a container that already stands at 60 degrees come to rest in a chain up its lower
  // wall (each held by the friction of the next), metres above where a poured silo is full: so the container
  // is filled upright (gravity along its -y for the first half of settle_time), turned to its tilt over the
  // next quarter (eased, so the packing slides over rather than being thrown), and held tilted for the last
  // quarter, the outlet closed throughout.
  const double g = core::length(setup_.gravity);
  const std::uint64_t turn0 = open_step_ / 2, turn1 = open_step_ - open_step_ / 4;
  auto set_gravity = [&](double angle) {
    double sn = 0, cs = 0;
    core::portable::sincos(angle, sn, cs);
    world_->SetGravity(b2Vec2(static_cast<float>(-g * sn * L_), static_cast<float>(-g * cs * L_)));
  };
  while (step_ < open_step_) {
    double angle = setup_.tilt;
    if (step_ < turn0) {
      angle = 0;
    } else if (step_ < turn1) {
      const double u = static_cast<double>(step_ - turn0) / static_cast<double>(turn1 - turn0);
      angle = setup_.tilt * u * u * (3.0 - 2.0 * u);
    }
    set_gravity(angle);
    step();
  }
  world_->SetGravity(
      b2Vec2(static_cast<float>(setup_.gravity.x * L_), static_cast<float>(setup_.gravity.y * L_)));
}

void Silo::reinject_tilted(int id) {
  // As reinject: on level lines (across gravity) one diameter apart, from just above the free surface up to
  // the container's highest point, then below.
  const double r = extent_[id];
  const std::vector<Level>& lv = levels();
  const double slab = geo_.grain_diameter, h_bottom = lv.front().h, h_top = lv.back().h + slab;
  const core::Vec2 across{up_.y, -up_.x};
  const double h0 = column_top(id) + scene_.reinject_gap + r;
  std::vector<double> bands;
  for (double h = h0; h <= h_top; h += 2 * r) bands.push_back(h);
  for (double h = h0 - 2 * r; h >= h_bottom; h -= 2 * r) bands.push_back(h);
  const int n = static_cast<int>(lv.size());
  for (double h : bands) {
    const Level& level =
        lv[static_cast<size_t>(std::clamp(static_cast<int>((h - h_bottom) / slab), 0, n - 1))];
    const double lo = level.s_min + r, hi = level.s_max - r;
    if (hi <= lo) continue;
    for (int attempt = 0; attempt < 40; ++attempt) {
      const core::Vec2 p = h * up_ + rng_reinject_.uniform(lo, hi) * across;
      if (!geo_.contains(p, r + 1e-4) || !free_at(p, id)) continue;
      put_back(id, p);
      return;
    }
  }
  no_room_to_reinject(id);
}

}  // namespace sim
