// Filling the hopper: random sequential deposition of every disk with the aperture closed, settling, and
// opening the aperture (refused, with advice, while disks are still above the container).
#include <box2d/box2d.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/format.h"
#include "core/physics.h"
#include "sim/hopper.h"

namespace sim {

double Hopper::deposit_height() const {
  const int n_o = static_cast<int>(scene_.n_original()), n = static_cast<int>(scene_.n_total);
  // Random sequential deposition jams near 55% coverage, so the disks are dropped from a column tall enough
  // for 30% coverage, which may reach above the container: the side walls reach that high, and the top wall
  // is only built when the aperture opens.
  double area = 0;
  for (int id = 0; id < n; ++id) {
    double r = id < n_o ? scene_.radius_original : scene_.radius_added();
    area += core::kPi * r * r;
  }
  const double hopper_area = (geo_.half_width + geo_.half_aperture) * geo_.hopper_height;
  return std::max(geo_.total_height,
                  geo_.hopper_height + (area / 0.3 - hopper_area) / (2.0 * geo_.half_width));
}

void Hopper::deposit() {
  const int n_o = static_cast<int>(scene_.n_original()), n = static_cast<int>(scene_.n_total);
  auto species_of = [&](int id) { return id < n_o ? core::Species::Original : core::Species::Added; };
  auto radius_of = [&](int id) {
    return species_of(id) == core::Species::Original ? scene_.radius_original : scene_.radius_added();
  };
  // Placement order: ids in order (the larger original disks first, so the smaller ones fit into the gaps),
  // or shuffled (Fisher-Yates on the deposition stream; the default order draws nothing extra).
  std::vector<int> order(static_cast<size_t>(n));
  for (int id = 0; id < n; ++id) order[static_cast<size_t>(id)] = id;
  if (scene_.deposit_order == "shuffled")
    for (int k = n - 1; k > 0; --k)
      std::swap(order[static_cast<size_t>(k)],
                order[static_cast<size_t>(rng_deposit_.uniform() * (k + 1)) % static_cast<size_t>(k + 1)]);
  std::vector<core::Vec2> at(static_cast<size_t>(n));
  std::vector<core::Vec2> placed;
  std::vector<double> placed_r;
  for (int id : order) {
    const double r = radius_of(id);
    // Random sequential deposition, no overlaps, aperture closed.
    core::Vec2 p;
    bool ok = false;
    for (int attempt = 0; attempt < 200000 && !ok; ++attempt) {
      p.y = rng_deposit_.uniform(r, deposit_height_ - r);
      double hw = geo_.half_width_at(p.y) - r;
      if (hw <= 0) continue;
      p.x = rng_deposit_.uniform(-hw, hw);
      if (p.y - r < 0 || geo_.side_clearance(p, r) < 0) continue;
      ok = true;
      for (size_t j = 0; j < placed.size() && ok; ++j) {
        double rr = r + placed_r[j];
        core::Vec2 d = p - placed[j];
        ok = core::dot(d, d) >= rr * rr;
      }
    }
    if (!ok)
      throw core::InputError("scene: could not deposit " + std::to_string(n) +
                             " disks without overlap; lower n_total or raise silo_height");
    placed.push_back(p);
    placed_r.push_back(r);
    at[static_cast<size_t>(id)] = p;
  }
  for (int id = 0; id < n; ++id) {
    const core::Species sp = species_of(id);
    const double r = radius_of(id);
    const core::Vec2 p = at[static_cast<size_t>(id)];
    radius_.push_back(r);
    species_.push_back(sp);
    if (sp == core::Species::Added) added_ids_.push_back(id);

    b2BodyDef bd;
    bd.type = b2_dynamicBody;
    bd.position.Set(static_cast<float>(p.x * L_), static_cast<float>(p.y * L_));
    bd.allowSleep = false;
    b2Body* body = world_->CreateBody(&bd);
    b2CircleShape circle;
    circle.m_radius = static_cast<float>(r * L_);
    b2FixtureDef fd;
    fd.shape = &circle;
    // Masses stay in kg: Box2D's area grows by L^2, so the density shrinks by L^2.
    fd.density = static_cast<float>(scene_.density / (L_ * L_));
    fd.friction = static_cast<float>(scene_.friction);
    fd.restitution = static_cast<float>(scene_.restitution);
    fd.restitutionThreshold = static_cast<float>(scene_.restitution_threshold * L_);
    fd.userData.pointer = static_cast<std::uintptr_t>(id) + 1;
    body->CreateFixture(&fd);
    bodies_.push_back(body);
  }
  t_ = -static_cast<double>(open_step_) * scene_.dt;
}

void Hopper::settle() {
  while (step_ < open_step_) step();
  double vmax = 0;
  for (int i = 0; i < particle_count(); ++i) vmax = std::max(vmax, core::length(vel(i)));
  settle_max_speed_ = vmax;
}

void Hopper::open_aperture() {
  for (int i = 0; i < particle_count(); ++i)
    if (pos(i).y + radius_[i] > geo_.total_height)
      throw core::InputError(
          "scene: after settle_time = " + core::format_g(scene_.settle_time, 4) + " s particle " +
          std::to_string(i) + " (" + core::species_name(species_[i]) +
          ") is still above the top of the container at y = " + core::format_g(pos(i).y, 4) + " m; " +
          (scene_.settle_kicks && scene_.kick_impulse_max > 0
               ? std::string("the kicks during settling throw disks out: set settle_kicks = false")
               : std::string("raise settle_time or silo_height")) +
          (scene_.mu > 0 ? ", or lower mu (repelling disks float on the column)" : ""));
  walls_->DestroyFixture(ceiling_);
  ceiling_ = nullptr;
  add_wall(static_cast<int>(core::Wall::Top));
  walls_->DestroyFixture(lid_);
  lid_ = nullptr;
  open_ = true;
  t_ = 0;
}

}  // namespace sim
