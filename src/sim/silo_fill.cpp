// Filling the silo: random sequential deposition of every grain with the aperture closed, settling, and
// opening the aperture (refused, with advice, while grains are still above the container).
#include <box2d/box2d.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/format.h"
#include "core/physics.h"
#include "core/portable_math.h"
#include "sim/silo.h"

namespace sim {

namespace {
// Placed grains binned on a grid, so that a candidate is tested against its neighbours only: the same test as
// against every grain placed so far (the deposition, and so the run, is the same), in time proportional to n
// instead of n^2.
class PlacedGrid {
 public:
  PlacedGrid(double x0, double x1, double y1, double cell) : x0_(x0), cell_(cell) {
    nx_ = static_cast<int>((x1 - x0) / cell) + 1;
    ny_ = static_cast<int>(y1 / cell) + 1;
    bins_.resize(static_cast<size_t>(nx_) * static_cast<size_t>(ny_));
  }
  bool free(core::Vec2 p, double r) const {
    const int cx = col(p.x), cy = row(p.y);
    for (int y = std::max(0, cy - 1); y <= std::min(ny_ - 1, cy + 1); ++y)
      for (int x = std::max(0, cx - 1); x <= std::min(nx_ - 1, cx + 1); ++x)
        for (const auto& q : bins_[static_cast<size_t>(y) * nx_ + x]) {
          const double rr = r + q.r;
          const core::Vec2 d = p - q.p;
          if (!(core::dot(d, d) >= rr * rr)) return false;
        }
    return true;
  }
  void add(core::Vec2 p, double r) {
    bins_[static_cast<size_t>(row(p.y)) * nx_ + col(p.x)].push_back({p, r});
  }

 private:
  struct Item {
    core::Vec2 p;
    double r;
  };
  int col(double x) const { return std::clamp(static_cast<int>((x - x0_) / cell_), 0, nx_ - 1); }
  int row(double y) const { return std::clamp(static_cast<int>(y / cell_), 0, ny_ - 1); }
  double x0_, cell_;
  int nx_ = 1, ny_ = 1;
  std::vector<std::vector<Item>> bins_;
};
}  // namespace

double Silo::draw_radius(const core::SpeciesDef& d) {
  switch (d.law) {
    case core::SizeLaw::Fixed:
      return d.radius;  // nothing drawn: the shorthand's runs stay bit for bit
    case core::SizeLaw::Uniform:
      return rng_shape_.uniform(d.radius_min, d.radius_max);
    case core::SizeLaw::Lognormal: {
      // ln r normal with the mean and spread asked for (Marsaglia's polar method, portable exp and log),
      // redrawn outside the truncation.
      const double s2 = core::portable::log(1.0 + d.spread * d.spread);
      const double mu = core::portable::log(d.radius) - 0.5 * s2, sigma = std::sqrt(s2);
      for (;;) {
        double u, v, q;
        do {
          u = rng_shape_.uniform(-1.0, 1.0);
          v = rng_shape_.uniform(-1.0, 1.0);
          q = u * u + v * v;
        } while (q >= 1.0 || q == 0.0);
        const double z = u * std::sqrt(-2.0 * core::portable::log(q) / q);
        const double r = core::portable::exp(mu + sigma * z);
        if (r >= d.radius_min && r <= d.radius_max) return r;
      }
    }
  }
  return d.radius;
}

double Silo::deposit_height() const {
  // Random sequential deposition jams near 55% coverage, so the grains are dropped from a column tall enough
  // for 30% coverage, which may reach above the container: the side walls reach that high, and the top wall
  // is only built when the aperture opens.
  double area = 0;
  for (double r : radius_) area += core::kPi * r * r;
  const double hopper_area = (geo_.half_width + geo_.half_aperture) * geo_.hopper_height;
  return std::max(geo_.total_height,
                  geo_.hopper_height + (area / 0.3 - hopper_area) / (2.0 * geo_.half_width));
}

void Silo::make_grains() {
  const int n = setup_.n_total;
  // Each grain's species, size and shape: radii drawn in id order, then polygon orientations, both from their
  // own stream (the shorthand's fixed-size disks draw nothing from it).
  angle_.assign(static_cast<size_t>(n), 0.0);
  for (const auto& d : setup_.species) {
    for (int k = 0; k < d.count; ++k) {
      const int id = d.first_id + k;
      species_.push_back(static_cast<core::Species>(setup_.species_of(id)));
      radius_.push_back(draw_radius(d));
      extent_.push_back(radius_.back() * d.extent_factor());
      sides_.push_back(static_cast<std::uint8_t>(d.sides));
      if (d.dipole > 0) dipole_ids_.push_back(id), dipole_moment_.push_back(d.dipole);
    }
  }
  for (int id = 0; id < n; ++id)
    if (sides_[static_cast<size_t>(id)] > 0)
      angle_[static_cast<size_t>(id)] = rng_shape_.uniform(0.0, 2.0 * core::kPi);
}

void Silo::deposit() {
  const int n = setup_.n_total;
  // Placement order: ids in order (species in list order: the shorthand's larger original disks first, so
  // the smaller ones fit into the gaps), or shuffled (Fisher-Yates on the deposition stream; the default
  // order draws nothing extra).
  std::vector<int> order(static_cast<size_t>(n));
  for (int id = 0; id < n; ++id) order[static_cast<size_t>(id)] = id;
  if (setup_.deposit_order == core::DepositOrder::Shuffled)
    for (int k = n - 1; k > 0; --k)
      std::swap(order[static_cast<size_t>(k)],
                order[static_cast<size_t>(rng_deposit_.uniform() * (k + 1)) % static_cast<size_t>(k + 1)]);
  std::vector<core::Vec2> at(static_cast<size_t>(n));
  PlacedGrid grid(geo_.x_left, geo_.x_right, deposit_height_, 2.0 * setup_.largest_extent());
  for (int id : order) {
    const double r = extent_[static_cast<size_t>(id)];
    // Random sequential deposition, no overlaps, aperture closed.
    core::Vec2 p;
    bool ok = false;
    for (int attempt = 0; attempt < 200000 && !ok; ++attempt) {
      p.y = rng_deposit_.uniform(r, deposit_height_ - r);
      const double lo = geo_.left_at(p.y) + r, hi = geo_.right_at(p.y) - r;
      if (hi - lo <= 0) continue;
      p.x = rng_deposit_.uniform(lo, hi);
      if (p.y - r < 0 || geo_.side_clearance(p, r) < 0) continue;
      ok = grid.free(p, r);
    }
    if (!ok)
      throw core::InputError("scene: could not deposit " + std::to_string(n) +
                             " grains without overlap; use fewer grains or raise silo_height");
    grid.add(p, r);
    at[static_cast<size_t>(id)] = p;
  }
  // Box2D keeps bodies and contacts in memory in the order they are made. Above kSpatialOrderAbove grains
  // neighbours in the packing are made next to each other (by height), so its contact and solver loops stay
  // in cache: 23% faster at 5000 grains (docs/bench_scaling.csv). Smaller scenes, the paper's among them,
  // keep id order, bit for bit the runs they always gave.
  std::vector<int> make(static_cast<size_t>(n));
  for (int id = 0; id < n; ++id) make[static_cast<size_t>(id)] = id;
  if (n > kSpatialOrderAbove)
    std::stable_sort(make.begin(), make.end(), [&](int a, int b) {
      return at[static_cast<size_t>(a)].y < at[static_cast<size_t>(b)].y;
    });
  bodies_.assign(static_cast<size_t>(n), nullptr);
  for (int id : make) add_grain(id, at[static_cast<size_t>(id)], angle_[static_cast<size_t>(id)]);
  angle_.clear();
  t_ = -static_cast<double>(open_step_) * scene_.dt;
}

void Silo::add_grain(int id, core::Vec2 p, double angle) {
  const core::SpeciesDef& d = setup_.species[static_cast<size_t>(species_[static_cast<size_t>(id)])];
  b2BodyDef bd;
  bd.type = b2_dynamicBody;
  bd.position.Set(static_cast<float>(p.x * L_), static_cast<float>(p.y * L_));
  bd.angle = static_cast<float>(angle);
  bd.allowSleep = false;
  b2Body* body = world_->CreateBody(&bd);
  b2CircleShape circle;
  b2PolygonShape polygon;
  b2FixtureDef fd;
  if (d.polygon()) {
    // A regular polygon whose area equals the disk of radius r: circumradius r * extent_factor. Vertices from
    // the portable sine and cosine (one run on every machine).
    b2Vec2 v[b2_maxPolygonVertices];
    const double R = extent_[static_cast<size_t>(id)] * L_;
    for (int k = 0; k < d.sides; ++k) {
      double sn = 0, cs = 0;
      core::portable::sincos(2.0 * core::kPi * k / d.sides, sn, cs);
      v[k].Set(static_cast<float>(R * cs), static_cast<float>(R * sn));
    }
    polygon.Set(v, d.sides);
    fd.shape = &polygon;
  } else {
    circle.m_radius = static_cast<float>(radius_[static_cast<size_t>(id)] * L_);
    fd.shape = &circle;
  }
  // Masses stay in kg: Box2D's area grows by L^2, so the density shrinks by L^2.
  fd.density = static_cast<float>(d.density / (L_ * L_));
  fd.friction = static_cast<float>(d.friction);
  fd.restitution = static_cast<float>(d.restitution);
  fd.restitutionThreshold = static_cast<float>(scene_.restitution_threshold * L_);
  fd.userData.pointer = static_cast<std::uintptr_t>(id) + 1;
  body->CreateFixture(&fd);
  bodies_[static_cast<size_t>(id)] = body;
}

void Silo::settle() {
  if (setup_.tilt != 0)
    settle_tilted();
  else
    while (step_ < open_step_) step();
  double vmax = 0;
  for (int i = 0; i < particle_count(); ++i) vmax = std::max(vmax, core::length(vel(i)));
  settle_max_speed_ = vmax;
}

void Silo::open_aperture() {
  for (int i = 0; i < particle_count(); ++i)
    if (pos(i).y + extent_[i] > geo_.total_height)
      throw core::InputError(
          "scene: after settle_time = " + core::format_g(scene_.settle_time, 4) + " s grain " +
          std::to_string(i) + " (" + setup_.species[static_cast<size_t>(species_[i])].name +
          ") is still above the top of the container at y = " + core::format_g(pos(i).y, 4) + " m; " +
          (setup_.drive.settle_kicks && setup_.drive.kick_impulse_max > 0
               ? std::string("the kicks during settling throw grains out: set settle_kicks = false")
               : std::string("raise settle_time or silo_height")) +
          (setup_.any_dipole() ? ", or lower the dipoles (repelling grains float on the column)" : ""));
  walls_->DestroyFixture(ceiling_);
  ceiling_ = nullptr;
  add_wall(static_cast<int>(core::Wall::Top));
  walls_->DestroyFixture(lid_);
  lid_ = nullptr;
  open_ = true;
  t_ = 0;
}

void Silo::set_outlet_open(bool open) {
  if (open && lid_) {
    walls_->DestroyFixture(lid_);
    lid_ = nullptr;
  } else if (!open && !lid_) {
    add_wall(static_cast<int>(core::Wall::Lid));
  }
}

}  // namespace sim
