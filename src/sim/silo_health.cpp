// The health monitor: every grain every step (finite, inside the container, not absurdly fast) and every
// contact at every kick (overlap), so an integration that breaks its bounds stops with its cause instead of
// producing garbage; with --unsafe it warns instead (the first few, then a count).
#include <box2d/box2d.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "core/error.h"
#include "core/format.h"
#include "sim/silo.h"
#include "sim/silo_internal.h"

namespace sim {

using internal::decode;
using internal::fmt4;
using internal::kMaxOverlapFraction;

void Silo::check_health() {
  for (int i = 0; i < particle_count(); ++i) check_health_fast(i, pos(i), vel(i));
  check_overlaps();
}

void Silo::check_health_fast(int id, core::Vec2 p, core::Vec2 v) const {
  const char* cause = nullptr;
  if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(v.x) || !std::isfinite(v.y))
    cause = "a non-finite position or velocity";
  else if (p.y > (open_ ? geo_.total_height : deposit_height_) + extent_[id] ||
           (p.y > 0 && (p.x < geo_.left_at(p.y) - extent_[id] || p.x > geo_.right_at(p.y) + extent_[id])))
    cause = "a grain outside the container";
  else if (core::length(v) > 10.0 * (std::sqrt(2.0 * scene_.gravity * geo_.total_height) + 1.0 +
                                     setup_.drive.amplitude * setup_.drive.omega))
    cause = "a grain faster than 10x (the free-fall speed from the top + 1 m/s)";
  if (!cause) return;
  std::ostringstream o;
  o << "unstable integration at t = " << fmt4(t_) << " s: " << cause << " (particle " << id
    << " at x = " << fmt4(p.x) << " m, y = " << fmt4(p.y) << " m, speed " << fmt4(core::length(v))
    << " m/s); try dt <= " << fmt4(0.5 * scene_.dt) << " s (now " << fmt4(scene_.dt)
    << " s), more iterations, or continuous = true";
  if (scene_.unsafe && std::isfinite(p.x) && std::isfinite(p.y)) {
    warn_unsafe(o.str());
    return;
  }
  throw core::Unstable(o.str());
}

void Silo::check_overlaps() {
  double worst = 0;
  int wa = -1, wb = -1;
  for (const b2Contact* c = world_->GetContactList(); c; c = c->GetNext()) {
    if (!c->IsTouching()) continue;
    int a = decode(c->GetFixtureA()), b = decode(c->GetFixtureB());
    if (a < 0 || b < 0) continue;
    double overlap;
    if (sides_[a] == 0 && sides_[b] == 0) {
      core::Vec2 d = pos(a) - pos(b);
      overlap = std::max(0.0, (radius_[a] + radius_[b] - core::length(d)) / std::min(radius_[a], radius_[b]));
    } else {
      // Polygons: the deepest penetration of the pair now (the contact's own manifold is from the last step,
      // and a grain re-injected since then would seem to overlap where it was).
      const b2Fixture *fa = c->GetFixtureA(), *fb = c->GetFixtureB();
      const b2Transform &xa = fa->GetBody()->GetTransform(), &xb = fb->GetBody()->GetTransform();
      b2Manifold m;
      const_cast<b2Contact*>(c)->Evaluate(&m, xa, xb);
      b2WorldManifold wm;
      wm.Initialize(&m, xa, fa->GetShape()->m_radius, xb, fb->GetShape()->m_radius);
      double deepest = 0;
      for (int k = 0; k < m.pointCount; ++k)
        deepest = std::min(deepest, static_cast<double>(wm.separations[k]));
      overlap = -deepest / L_ / std::min(radius_[a], radius_[b]);
    }
    overlaps_.sum += overlap;
    ++overlaps_.samples;
    if (overlap > worst) worst = overlap, wa = a, wb = b;
  }
  overlaps_.max = std::max(overlaps_.max, worst);
  if (worst <= kMaxOverlapFraction) return;
  std::ostringstream o;
  o << "unstable integration at t = " << fmt4(t_) << " s: grains " << wa << " and " << wb << " overlap by "
    << fmt4(100 * worst) << "% of the smaller radius (bound " << fmt4(100 * kMaxOverlapFraction)
    << "%); try dt <= " << fmt4(0.5 * scene_.dt) << " s (now " << fmt4(scene_.dt) << " s) or more iterations";
  if (scene_.unsafe) {
    warn_unsafe(o.str());
    return;
  }
  throw core::Unstable(o.str());
}

void Silo::warn_unsafe(const std::string& msg) const {
  // Loudly, but not thousands of times: the first three, then a count at the end of the run's metadata.
  if (health_warnings_++ < 3) std::fprintf(stderr, "siloscope: WARNING (--unsafe): %s\n", msg.c_str());
}

}  // namespace sim
