#include <catch2/catch.hpp>

#include <cmath>

#include "core/arch.h"
#include "sim/silo.h"

namespace {
// A hand-built contact graph: nodes at positions, bonds, wall contacts.
struct Graph {
  std::vector<core::Vec2> pos;
  core::ContactGraph g{0};
  int node(double x, double y, bool left = false, bool right = false) {
    pos.push_back({x, y});
    g.neighbours.emplace_back();
    g.touches_left.push_back(left);
    g.touches_right.push_back(right);
    return static_cast<int>(pos.size()) - 1;
  }
  void chain(std::initializer_list<int> ids) {
    const int* prev = nullptr;
    for (const int& i : ids) {
      if (prev) g.add_bond(*prev, i);
      prev = &i;
    }
  }
  std::vector<int> arch(double reach = 1.36) const { return core::find_arch(g, pos, reach); }
};
}  // namespace

TEST_CASE("wall-to-wall arches of 3, 4 and 5 disks are found, left to right", "[arch]") {
  for (int n : {3, 4, 5}) {
    Graph t;
    std::vector<int> ids;
    for (int k = 0; k < n; ++k) {
      double x = -0.12 + 0.24 * k / (n - 1);
      ids.push_back(t.node(x, 0.1 + 0.04 * std::sin(M_PI * k / (n - 1)), k == 0, k == n - 1));
    }
    for (int k = 0; k + 1 < n; ++k) t.g.add_bond(ids[k], ids[k + 1]);
    // Disks resting on the arch, bonded to it and to each other: they must not join it.
    int a = t.node(-0.06, 0.25), b = t.node(0.06, 0.25);
    t.chain({ids[1], a, b, ids[n - 2]});
    CAPTURE(n);
    CHECK(t.arch() == ids);
  }
}

TEST_CASE("fewest particles first, ties go to the lowest path", "[arch]") {
  Graph t;
  int l = t.node(-0.12, 0.10, true), r = t.node(0.12, 0.10, false, true);
  int high = t.node(0.0, 0.22), low = t.node(0.0, 0.16);
  t.chain({l, high, r});
  t.chain({l, low, r});
  CHECK(t.arch() == std::vector<int>{l, low, r});
  // A lower path with more particles loses to a higher one with fewer.
  Graph u;
  int l2 = u.node(-0.12, 0.10, true), r2 = u.node(0.12, 0.10, false, true);
  int m1 = u.node(-0.05, 0.05), m2 = u.node(0.05, 0.05), top = u.node(0.0, 0.3);
  u.chain({l2, m1, m2, r2});
  u.chain({l2, top, r2});
  CHECK(u.arch() == std::vector<int>{l2, top, r2});
}

TEST_CASE("mixed species: small added disks are arch members like any other", "[arch]") {
  Graph t;
  int l = t.node(-0.12, 0.1, true), small = t.node(-0.03, 0.14), mid = t.node(0.04, 0.15),
      r = t.node(0.12, 0.1, false, true);
  t.chain({l, small, mid, r});
  std::vector<double> radius = {0.065, 0.026, 0.065, 0.065};
  auto arch = t.arch();
  REQUIRE(arch == std::vector<int>{l, small, mid, r});
  auto geo = core::arch_geometry(arch, t.pos, radius);
  CHECK(geo.span == Approx(0.24 + 2 * 0.065));
  CHECK(geo.height == Approx(0.15));
}

TEST_CASE("no spanning path, or wall contacts only above the reach: no arch", "[arch]") {
  Graph t;
  int l = t.node(-0.12, 0.1, true), a = t.node(-0.02, 0.12), b = t.node(0.05, 0.12),
      r = t.node(0.12, 0.1, false, true);
  t.chain({l, a});
  t.chain({b, r});
  CHECK(t.arch().empty());
  t.g.add_bond(a, b);
  CHECK(t.arch().size() == 4);
  CHECK(t.arch(0.05).empty());  // wall contacts at y = 0.1 are above a 5 cm reach
}

TEST_CASE("trimming keeps members while x keeps moving outwards from the centre", "[arch]") {
  Graph t;
  // The path climbs back inwards at its left end (lw is left of centre but right of p1): lw is cut off.
  int lw = t.node(-0.12, 0.30, true), p1 = t.node(-0.14, 0.12), p2 = t.node(-0.02, 0.08),
      p3 = t.node(0.1, 0.12), r = t.node(0.16, 0.2, false, true);
  t.chain({lw, p1, p2, p3, r});
  auto path = core::shortest_wall_path(t.g, t.pos, 1.36);
  CHECK(path == std::vector<int>{lw, p1, p2, p3, r});
  CHECK(t.arch() == std::vector<int>{p1, p2, p3, r});
}

TEST_CASE("arch angles: 180 deg is flat, below a dome, above a defect", "[arch]") {
  std::vector<double> radius(3, 0.065);
  std::vector<core::Vec2> flat = {{-0.13, 0.1}, {0, 0.1}, {0.13, 0.1}};
  CHECK(core::arch_geometry({0, 1, 2}, flat, radius).max_angle_deg == Approx(180));
  std::vector<core::Vec2> dome = {{-0.1, 0.1}, {0, 0.2}, {0.1, 0.1}};
  CHECK(core::arch_geometry({0, 1, 2}, dome, radius).max_angle_deg == Approx(90));
  std::vector<core::Vec2> vee = {{-0.1, 0.2}, {0, 0.1}, {0.1, 0.2}};
  CHECK(core::arch_geometry({0, 1, 2}, vee, radius).max_angle_deg == Approx(270));
}

TEST_CASE("contacts rebuilt from positions match the geometry", "[arch]") {
  core::Scene s;
  core::Geometry geo = core::make_geometry(s);
  const double r = 0.065;
  // A disk touching the left hopper wall at y = 0.12, one touching it, one apart.
  double x0 = -(geo.right_at(0.12) - r / std::cos(geo.wall_angle_from_vertical()));
  std::vector<core::Vec2> pos = {{x0, 0.12}, {x0 + 2 * r, 0.12}, {x0 + 4 * r + 0.01, 0.12}};
  std::vector<double> radius(3, r);
  auto g = core::contacts_from_positions(pos, radius, geo, 1e-3, 1.0);
  CHECK(g.touches_left[0]);
  CHECK_FALSE(g.touches_left[1]);
  CHECK(g.neighbours[0] == std::vector<int>{1});
  CHECK(g.neighbours[2].empty());
}

TEST_CASE("an obstacle supports an arch: a path may pass through it without counting it as a grain",
          "[arch]") {
  // Left wall - 0 - 1 | obstacle | 2 - 3 - right wall; 1 and 2 touch the obstacle, not each other. Above, a
  // longer chain 0 - 4 - 5 - 6 - 7 - 3 spans without it.
  core::ContactGraph g(8);
  std::vector<core::Vec2> pos = {{-0.3, 0.05}, {-0.15, 0.2}, {0.15, 0.2}, {0.3, 0.05},
                                 {-0.25, 0.6}, {-0.1, 0.7},  {0.1, 0.7},  {0.25, 0.6}};
  g.touches_left[0] = true;
  g.touches_right[3] = true;
  g.add_bond(0, 1);
  g.add_bond(2, 3);
  g.add_bond(0, 4), g.add_bond(4, 5), g.add_bond(5, 6), g.add_bond(6, 7), g.add_bond(7, 3);
  CHECK(core::shortest_wall_path(g, pos, 1.0) == std::vector<int>{0, 4, 5, 6, 7, 3});  // no obstacle yet
  g.on_obstacle = {1, 2};
  CHECK(core::shortest_wall_path(g, pos, 1.0) == std::vector<int>{0, 1, 2, 3});
}

TEST_CASE("an arch is shown only where it blocks: two or more grains spanning the outlet, nothing beneath",
          "[arch]") {
  const double half = 0.15, r = 0.065;
  const std::vector<double> radius(4, r);
  // Two grains straddling the outlet's centre, nothing beneath: an arch.
  std::vector<core::Vec2> pos = {{-0.07, 0.1}, {0.07, 0.1}, {0.0, 0.5}, {0.3, 0.4}};
  CHECK(core::blocks_outlet({0, 1}, pos, radius, half));
  // One grain (the "one-disk arch" touching one wall): never.
  CHECK_FALSE(core::blocks_outlet({0}, pos, radius, half));
  // Both grains left of the centre: they span nothing.
  CHECK_FALSE(core::blocks_outlet({0, 1}, {{-0.3, 0.2}, {-0.17, 0.2}, {0.0, 0.5}, {0.3, 0.4}}, radius, half));
  // A grain falling through the opening beneath the chain: the chain blocks nothing.
  pos[2] = {0.0, 0.02};
  CHECK_FALSE(core::blocks_outlet({0, 1}, pos, radius, half));
  // ... once it is through (below the outlet line by its radius), the chain blocks again.
  pos[2] = {0.0, -0.07};
  CHECK(core::blocks_outlet({0, 1}, pos, radius, half));
}

TEST_CASE("arch descriptors: rise, both aspect ratios, theta_max, defects and the spread of bead angles",
          "[arch]") {
  const double r = 0.05;
  // A symmetric dome of three: ends at y = 0, crown 0.04 m higher, 0.16 m between end centres.
  std::vector<core::Vec2> pos = {{-0.08, 0.0}, {0.0, 0.04}, {0.08, 0.0}};
  const std::vector<double> radius(3, r);
  core::ArchDescriptors d = core::arch_descriptors({0, 1, 2}, pos, radius);
  CHECK(d.grains == 3);
  CHECK(d.span == Approx(0.26));
  CHECK(d.rise == Approx(0.04));
  CHECK(d.aspect == Approx(0.04 / 0.13));
  CHECK(d.inverse_aspect == Approx(0.13 / 0.04));
  // The crown's bead angle: 180 - 2 atan(0.04 / 0.08), below 180 (a dome), no defect.
  CHECK(d.theta_max_deg == Approx(180 - 2 * std::atan(0.5) * 180 / 3.14159265358979));
  CHECK(d.defects == 0);
  CHECK(d.angle_sd_deg == 0);  // one bead angle: no spread
  // A V (the middle member pokes down): one defect, the angle above 180.
  pos[1].y = -0.04;
  d = core::arch_descriptors({0, 1, 2}, pos, radius);
  CHECK(d.defects == 1);
  CHECK(d.theta_max_deg > 180);
  CHECK(d.rise == Approx(0.0));
  // Four members, two bead angles: their standard deviation.
  pos = {{-0.15, 0.0}, {-0.05, 0.05}, {0.05, 0.05}, {0.15, 0.0}};
  d = core::arch_descriptors({0, 1, 2, 3}, std::vector<core::Vec2>(pos), std::vector<double>(4, r));
  CHECK(d.angle_sd_deg == Approx(0.0).margin(1e-9));  // symmetric: equal angles
}
