// Love-Weber stress and arch force balance from a step's contact forces (core/forces.h).
#include "core/forces.h"

#include <algorithm>

#include "core/physics.h"

namespace core {

namespace {
Vec2 minus(Vec2 v) {
  return {-v.x, -v.y};
}
}  // namespace

std::vector<Stress> love_weber(const std::vector<ContactForce>& forces, const std::vector<Vec2>& centres,
                               const std::vector<double>& areas) {
  std::vector<Stress> s(centres.size());
  auto add = [&](int i, Vec2 point, Vec2 f) {
    if (i < 0 || static_cast<size_t>(i) >= centres.size()) return;
    const Vec2 r{point.x - centres[i].x, point.y - centres[i].y};
    s[i].xx += r.x * f.x, s[i].xy += r.x * f.y, s[i].yx += r.y * f.x, s[i].yy += r.y * f.y;
  };
  for (const ContactForce& c : forces) {
    const Vec2 f = c.on_b();
    add(c.b, c.point, f);
    add(c.a, c.point, minus(f));
  }
  for (size_t i = 0; i < s.size(); ++i) {
    const double a = i < areas.size() && areas[i] > 0 ? areas[i] : 0;
    if (a == 0) {
      s[i] = {};
      continue;
    }
    s[i].xx /= a, s[i].xy /= a, s[i].yx /= a, s[i].yy /= a;
  }
  return s;
}

ArchBalance arch_balance(const std::vector<ContactForce>& forces, const std::vector<int>& members,
                         const std::vector<Vec2>& weights) {
  auto member = [&](int i) {
    return i >= 0 && std::find(members.begin(), members.end(), i) != members.end();
  };
  ArchBalance b;
  for (const ContactForce& c : forces) {
    const bool in_a = member(c.a), in_b = member(c.b);
    if (in_a == in_b) continue;  // inside the arch, or not touching it
    const Vec2 on_member = in_b ? c.on_b() : minus(c.on_b());
    const int other = in_b ? c.a : c.b;
    Vec2& sum = other < 0 ? b.from_walls : b.from_grains;
    sum = sum + on_member;
  }
  for (int i : members)
    if (i >= 0 && static_cast<size_t>(i) < weights.size()) b.weight = b.weight + weights[i];
  return b;
}

std::vector<ArchBalance> member_balances(const std::vector<ContactForce>& forces,
                                         const std::vector<int>& members) {
  auto index = [&](int i) -> long {
    const auto it = i >= 0 ? std::find(members.begin(), members.end(), i) : members.end();
    return it == members.end() ? -1 : it - members.begin();
  };
  std::vector<ArchBalance> out(members.size());
  for (const ContactForce& c : forces) {
    const long ka = index(c.a), kb = index(c.b);
    if ((ka >= 0) == (kb >= 0)) continue;  // inside the arch, or not touching it
    const Vec2 on_member = kb >= 0 ? c.on_b() : minus(c.on_b());
    ArchBalance& m = out[static_cast<size_t>(kb >= 0 ? kb : ka)];
    Vec2& sum = (kb >= 0 ? c.a : c.b) < 0 ? m.from_walls : m.from_grains;
    sum = sum + on_member;
  }
  return out;
}

Vec2 wall_reaction(const std::vector<ContactForce>& forces) {
  Vec2 sum;
  for (const ContactForce& c : forces)
    if (c.a < 0) sum = sum + c.on_b();
  return sum;
}

std::vector<ContactForce> contact_forces(const Frame& f) {
  std::vector<ContactForce> out;
  for (const auto* list : {&f.contacts, &f.wall_contacts})
    for (const Contact& c : *list) {
      if (!c.has_geometry()) return {};
      ContactForce k;
      k.a = c.a, k.b = c.b;
      k.point = {c.px, c.py};
      k.normal = {c.nx, c.ny};
      k.fn = c.force, k.ft = c.ft;
      out.push_back(k);
    }
  return out;
}

std::vector<double> pressures(const Frame& f) {
  const std::vector<ContactForce> forces = contact_forces(f);
  if (forces.empty()) return {};
  std::vector<Vec2> centres(f.particles.size());
  std::vector<double> areas(f.particles.size());
  for (size_t i = 0; i < f.particles.size(); ++i) {
    const Particle& p = f.particles[i];
    centres[i] = {p.x, p.y};
    areas[i] = kPi * static_cast<double>(p.radius) * p.radius;
  }
  const std::vector<Stress> s = love_weber(forces, centres, areas);
  std::vector<double> out(s.size());
  for (size_t i = 0; i < s.size(); ++i) out[i] = s[i].pressure();
  return out;
}

}  // namespace core
