// sim::Silo's contact forces as the solver applied them in the last step (normal and tangential impulses over
// dt), and the weights they balance: what core/forces.h turns into stresses and an arch's force balance.
#include <box2d/box2d.h>

#include <cmath>

#include "core/forces.h"
#include "sim/kicks.h"
#include "sim/silo.h"
#include "sim/silo_internal.h"

namespace sim {

std::vector<core::ContactForce> Silo::contact_forces() const {
  std::vector<core::ContactForce> out;
  // Box2D's impulses are in its units (mass in kg, lengths times L): impulse / L is N*s.
  const double to_newton = 1.0 / (L_ * scene_.dt);
  for (b2Contact* c = world_->GetContactList(); c; c = c->GetNext()) {
    if (!c->IsTouching()) continue;
    const b2Manifold* m = c->GetManifold();
    if (m->pointCount == 0) continue;
    b2WorldManifold wm;
    c->GetWorldManifold(&wm);
    core::ContactForce f;
    f.a = internal::decode(c->GetFixtureA());
    f.b = internal::decode(c->GetFixtureB());
    double px = 0, py = 0, ni = 0, ti = 0;
    for (int k = 0; k < m->pointCount; ++k) {
      px += wm.points[k].x, py += wm.points[k].y;
      ni += m->points[k].normalImpulse, ti += m->points[k].tangentImpulse;
    }
    f.point = {px / m->pointCount / L_, py / m->pointCount / L_};
    f.normal = {wm.normal.x, wm.normal.y};
    f.fn = ni * to_newton;
    f.ft = ti * to_newton;
    // b is a grain: a wall goes first, its normal turned round (fn and ft keep their values: the tangent
    // turns with the normal).
    if (f.b < 0) {
      std::swap(f.a, f.b);
      f.normal = {-f.normal.x, -f.normal.y};
    }
    if (f.b < 0)
      continue;  // two walls (the moving container's parts) never touch, but a reader should not care
    out.push_back(f);
  }
  return out;
}

namespace {
std::uint64_t pair_key(int a, int b) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
}
}  // namespace

void Silo::average_forces(bool on) {
  averaging_ = on;
  restart_force_average();
}

void Silo::restart_force_average() {
  impulse_sums_.clear();
  averaged_steps_ = 0;
}

void Silo::accumulate_impulses() {
  ++averaged_steps_;
  for (const b2Contact* c = world_->GetContactList(); c; c = c->GetNext()) {
    if (!c->IsTouching()) continue;
    const b2Manifold* m = c->GetManifold();
    Impulses sum;
    for (int k = 0; k < m->pointCount; ++k)
      sum.normal += m->points[k].normalImpulse, sum.tangent += m->points[k].tangentImpulse;
    Impulses& acc =
        impulse_sums_[pair_key(internal::decode(c->GetFixtureA()), internal::decode(c->GetFixtureB()))];
    acc.normal += sum.normal, acc.tangent += sum.tangent;
  }
}

Silo::Impulses Silo::impulses(const b2Contact* c, int a, int b) const {
  Impulses out;
  if (averaging_ && averaged_steps_ > 0) {
    const auto it = impulse_sums_.find(pair_key(a, b));
    if (it != impulse_sums_.end())
      out = {it->second.normal / static_cast<double>(averaged_steps_),
             it->second.tangent / static_cast<double>(averaged_steps_)};
    return out;
  }
  const b2Manifold* m = c->GetManifold();
  for (int k = 0; k < m->pointCount; ++k)
    out.normal += m->points[k].normalImpulse, out.tangent += m->points[k].tangentImpulse;
  return out;
}

std::vector<core::Vec2> Silo::weights() const {
  std::vector<core::Vec2> w(bodies_.size());
  for (size_t i = 0; i < bodies_.size(); ++i) {
    const double m = bodies_[i]->GetMass();  // kg (densities are scaled by 1/L^2)
    w[i] = {m * setup_.gravity.x, m * setup_.gravity.y};
  }
  return w;
}

void Silo::kick_all(double dv, bool random, std::uint64_t seed) {
  const double g = core::length(setup_.gravity);
  if (g == 0 || dv == 0) return;
  std::vector<core::Vec2> change(bodies_.size(), {-setup_.gravity.x / g * dv, -setup_.gravity.y / g * dv});
  if (random) {
    core::Rng rng(seed, 7);
    draw_kicks(rng, dv, true, particle_count(), change);
  }
  for (size_t i = 0; i < bodies_.size(); ++i)
    if (parked_.empty() || !parked_[i])
      bodies_[i]->SetLinearVelocity(
          bodies_[i]->GetLinearVelocity() +
          b2Vec2(static_cast<float>(change[i].x * L_), static_cast<float>(change[i].y * L_)));
}

void Silo::record_arch_forces(core::ArchEvent& ev) const {
  if (ev.ids.empty()) return;
  const std::vector<core::Vec2> w = weights();
  const core::ArchBalance b = core::arch_balance(contact_forces(), ev.ids, w);
  const double g = core::length(setup_.gravity);
  if (g == 0) return;
  const core::Vec2 down{setup_.gravity.x / g, setup_.gravity.y / g};
  ev.load_N = b.load(down);
  ev.held_N = b.held(down);
  ev.weight_N = core::length(b.weight);
  ev.imbalance = ev.held_N > 0 ? core::length(b.residual()) / ev.held_N : NAN;
}

}  // namespace sim
