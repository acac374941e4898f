// Arch detection (Goldberg, Carlevaro and Pugnaloni, J. Stat. Mech. 2018, 113201).
//
// On the contact graph of touching disks: the arch is the path with the fewest particles between a disk
// touching the left hopper wall near the aperture and one touching the right hopper wall; ties go to the
// path whose particles sit lowest (smallest sum of heights). It is then trimmed: starting from the member
// nearest the aperture centre, members are kept while x keeps moving outwards on each side.
//
// Pure functions on plain data, no Box2D: the simulation feeds them Box2D's contacts, the inspector feeds
// them contacts rebuilt from stored positions.
#pragma once

#include <vector>

#include "core/frame.h"
#include "core/geometry.h"

namespace core {

struct ContactGraph {
  std::vector<std::vector<int>> neighbours;  // per particle id, ids of touching disks
  std::vector<bool> touches_left;            // touches the left hopper wall
  std::vector<bool> touches_right;           // touches the right hopper wall
  // Grains touching an obstacle: it supports an arch as a wall does, so a path may pass through it (from any
  // grain touching it to any other) without counting it as a grain.
  std::vector<int> on_obstacle;

  explicit ContactGraph(int n = 0) : neighbours(n), touches_left(n, false), touches_right(n, false) {}
  int size() const { return static_cast<int>(neighbours.size()); }
  void add_bond(int a, int b) {
    neighbours[a].push_back(b);
    neighbours[b].push_back(a);
  }
};

// The untrimmed fewest-particles path from the left wall to the right wall, left to right, considering only
// wall contacts of disks whose centre is below wall_reach (m). Empty if no such path exists.
std::vector<int> shortest_wall_path(const ContactGraph& g, const std::vector<Vec2>& pos, double wall_reach);

// Trim a left-to-right path around the member nearest `centre` (see above).
std::vector<int> trim_arch(const std::vector<int>& path, const std::vector<Vec2>& pos, Vec2 centre = {0, 0});

// Both steps: the blocking arch, members left to right, or empty. `trim` is the paper's rule for a hopper;
// over a flat floor the fewest-grains path already runs from a grain resting on the floor left of the outlet
// to one resting right of it, and trimming around the member nearest the outlet's centre would start at such
// a floor grain (nearer than the arch's crown) and keep it alone: flat silos use the path as it is.
std::vector<int> find_arch(const ContactGraph& g, const std::vector<Vec2>& pos, double wall_reach,
                           bool trim = true);

// Whether a found arch (members left to right) is one a picture or an export may show: at least two grains,
// the first centred left of the outlet's centre and the last right of it (it spans the outlet), and no other
// grain lying between the chain and the outlet inside the opening (a chain with grains falling beneath it
// blocks nothing). Positions in the container's frame (the outlet centred at x = 0, its line at y = 0). The
// clog rule's removal is not filtered by this (the paper's events stay as they are); at a clog the two agree.
bool blocks_outlet(const std::vector<int>& arch, const std::vector<Vec2>& pos,
                   const std::vector<double>& radius, double half_aperture);

// The descriptors of the arch literature, from the members' centres (left to right) and radii:
//   grains; span (outer edge to outer edge, m); rise: the highest member centre above the line through the
//   two end members' centres (m); aspect ratio rise / (span / 2) (Garcimartin et al., PRE 82, 031306, 2010)
//   and its inverse (span / 2) / rise (To, Lai and Pak, PRL 86, 71, 2001, use the span over the height); the
//   bead angle at each interior member, between the bonds to its two neighbours measured below the arch (180
//   deg: flat); its largest value theta_max; defects: bead angles above 180 deg (a member poking down towards
//   the outlet; Lozano et al., PRL 109, 068001, 2012, relate theta_max to an arch's resistance to vibration);
//   and the standard deviation of the bead angles.
// The bead angle (deg) at each interior member of an arch (members left to right): entry k - 1 for member k.
std::vector<double> bead_angles_deg(const std::vector<int>& ids, const std::vector<Vec2>& pos);

struct ArchDescriptors {
  int grains = 0;
  double span = 0, rise = 0, aspect = 0, inverse_aspect = 0;  // m, m, 1, 1 (inf/nan for a flat pair)
  double theta_max_deg = 0, angle_sd_deg = 0;
  int defects = 0;
};
ArchDescriptors arch_descriptors(const std::vector<int>& ids, const std::vector<Vec2>& pos,
                                 const std::vector<double>& radius);

// Whether two arches are the same arch: the same set of grains, in any order (their left-to-right order can
// change as they rattle).
bool same_grains(std::vector<int> a, std::vector<int> b);

// Span, height and largest angle of an arch (members left to right).
ArchGeometry arch_geometry(const std::vector<int>& ids, const std::vector<Vec2>& pos,
                           const std::vector<double>& radius);

// The alternative unclogging set: every disk within `range` of the aperture centre whose straight segment to
// the centre crosses no other disk; sorted left to right.
std::vector<int> visible_from_aperture(const std::vector<Vec2>& pos, const std::vector<double>& radius,
                                       double range);

// Contacts rebuilt from positions: disks closer than the sum of their radii plus `tolerance` (m) touch, and
// so do disks within `tolerance` of a hopper wall. Only disks below `max_height` are considered.
ContactGraph contacts_from_positions(const std::vector<Vec2>& pos, const std::vector<double>& radius,
                                     const Geometry& geo, double tolerance, double max_height);

}  // namespace core
