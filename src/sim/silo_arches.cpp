// sim::Silo's arches: the contact graph Box2D holds, the arch found in it, and whether an arch's members
// still touch (the shapes' own distance, not the contact list, which lags a step behind).
#include <box2d/b2_distance.h>
#include <box2d/box2d.h>

#include <algorithm>

#include "sim/silo.h"
#include "sim/silo_internal.h"

namespace sim {

using internal::decode;

core::ContactGraph Silo::contact_graph() const {
  core::ContactGraph g(particle_count());
  for (const b2Contact* c = world_->GetContactList(); c; c = c->GetNext()) {
    if (!c->IsTouching()) continue;
    int a = decode(c->GetFixtureA()), b = decode(c->GetFixtureB());
    if (a >= 0 && b >= 0) {
      g.add_bond(a, b);
      continue;
    }
    int particle = a >= 0 ? a : b, wall = -1 - (a >= 0 ? b : a);
    if (particle < 0) continue;
    // The walls the outlet opens between anchor arches (the hopper's, or a flat floor's two halves).
    if (wall == static_cast<int>(core::Wall::HopperLeft)) g.touches_left[particle] = true;
    if (wall == static_cast<int>(core::Wall::HopperRight)) g.touches_right[particle] = true;
    if (wall == static_cast<int>(core::Wall::Obstacle)) g.on_obstacle.push_back(particle);
  }
  return g;
}

std::vector<int> Silo::current_arch() const {
  return core::find_arch(contact_graph(), positions(), scene_.arch_wall_reach,
                         geo_.kind == core::ContainerKind::Hopper);
}

std::vector<int> Silo::blocking_arch() const {
  std::vector<int> arch = current_arch();
  if (!core::blocks_outlet(arch, positions(), radius_, geo_.half_aperture) || !chain_touches(arch))
    arch.clear();
  return arch;
}

double Silo::gap_to(int i, const b2Fixture* other) const {
  const b2Body* a = bodies_[static_cast<size_t>(i)];
  b2DistanceInput in;
  in.proxyA.Set(a->GetFixtureList()->GetShape(), 0);
  in.proxyB.Set(other->GetShape(), 0);
  in.transformA = a->GetTransform();
  in.transformB = other->GetBody()->GetTransform();
  in.useRadii = true;
  b2SimplexCache cache;
  cache.count = 0;
  b2DistanceOutput out;
  b2Distance(&out, &cache, &in);
  return out.distance;
}

bool Silo::chain_touches(const std::vector<int>& arch) const {
  // Box2D's contact list lags a step behind the positions (and keeps a manifold for a pair the solver has
  // just pushed apart): the shapes' own distance decides, within kArchContactGap of the smaller radius.
  auto near = [&](int i, double gap, double r) { return gap / L_ <= kArchContactGap * r; };
  for (size_t k = 1; k < arch.size(); ++k) {
    const int i = arch[k - 1], j = arch[k];
    const double r = std::min(radius_[static_cast<size_t>(i)], radius_[static_cast<size_t>(j)]);
    if (near(i, gap_to(i, bodies_[static_cast<size_t>(j)]->GetFixtureList()), r)) continue;
    if (obstacle_ && near(i, gap_to(i, obstacle_), radius_[static_cast<size_t>(i)]) &&
        near(j, gap_to(j, obstacle_), radius_[static_cast<size_t>(j)]))
      continue;
    return false;
  }
  return true;
}

}  // namespace sim
