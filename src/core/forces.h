// What the contact forces say: each grain's Love-Weber stress, and an arch's force balance (the load it
// carries from the grains above against what the walls give back). Plain functions of a step's contact forces
// (core::ContactForce, from sim::Silo::contact_forces), positions and masses: no solver here.
#pragma once

#include <vector>

#include "core/frame.h"
#include "core/geometry.h"

namespace core {

// A grain's stress, N/m (two dimensions): sigma = (1/A) sum over its contacts c of (x_c - x) (x) f_c, f_c the
// force on the grain at contact point x_c, A its area. Compression gives a negative trace.
struct Stress {
  double xx = 0, xy = 0, yx = 0, yy = 0;
  double pressure() const { return -(xx + yy) / 2; }  // N/m, > 0 in compression
};
// Every grain's stress from the contacts (grain-grain and grain-wall), `centres` in the contacts' frame.
std::vector<Stress> love_weber(const std::vector<ContactForce>& forces, const std::vector<Vec2>& centres,
                               const std::vector<double>& areas);

// The forces on an arch's members as a body, N, in the contacts' frame: from grains that are not members (the
// load from above, with any push from below), from the walls, and the members' own weight. At rest they sum
// to nothing; `residual()` is what is left, to be compared with the load.
struct ArchBalance {
  Vec2 from_grains, from_walls, weight;
  Vec2 residual() const { return from_grains + from_walls + weight; }
  // Along gravity: the load the grains above put on the arch, and what the walls hold up (both >= 0 at rest).
  double load(Vec2 down) const { return from_grains.x * down.x + from_grains.y * down.y; }
  double held(Vec2 down) const { return -(from_walls.x * down.x + from_walls.y * down.y); }
};
// `weights`: each grain's weight vector (mass times gravity), N.
ArchBalance arch_balance(const std::vector<ContactForce>& forces, const std::vector<int>& members,
                         const std::vector<Vec2>& weights);

// A frame's contacts (grain-grain and wall) as ContactForces: empty when they carry no geometry (a frame
// without contacts, or a version-1 contacts file's).
std::vector<ContactForce> contact_forces(const Frame& f);
// Each grain's pressure from its Love-Weber stress, N/m (> 0 in compression; area pi r^2, r the equal-area
// radius): empty when the frame's contacts carry no geometry.
std::vector<double> pressures(const Frame& f);

// The same split member by member (in `members`' order; weights left 0): what each member takes from grains
// outside the arch and from the walls. Their sums are arch_balance's from_grains and from_walls.
std::vector<ArchBalance> member_balances(const std::vector<ContactForce>& forces,
                                         const std::vector<int>& members);

// The resultant of the forces the walls exert on the grains, N: at rest, minus their total weight.
Vec2 wall_reaction(const std::vector<ContactForce>& forces);

}  // namespace core
