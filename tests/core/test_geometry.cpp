#include <catch2/catch.hpp>

#include "core/geometry.h"

TEST_CASE("hopper geometry matches model.md", "[sim][geometry]") {
  core::Scene s;
  core::Geometry g = core::make_geometry(s);
  using core::Wall;
  const auto& left = g.walls[static_cast<int>(Wall::HopperLeft)];
  const auto& right = g.walls[static_cast<int>(Wall::HopperRight)];
  // Aperture: from -D/2 to +D/2 at y = 0, D = 4.6 r_o.
  CHECK(right.a.x - left.b.x == Approx(0.299));
  CHECK(s.aperture / s.radius_original == Approx(4.6));
  CHECK(left.b.y == 0.0);
  CHECK(right.a.y == 0.0);
  // Hopper walls rise to (+-W/2, H_t); total height H_t + H_s = 6.36 m.
  CHECK(left.a.x == Approx(-0.5));
  CHECK(left.a.y == Approx(1.36));
  CHECK(right.b.x == Approx(0.5));
  CHECK(g.total_height == Approx(6.36));
  // Each wall 14.45 deg from the vertical; the two make 28.9 deg (~ pi/6) with each other.
  CHECK(g.wall_angle_from_vertical() * 180 / M_PI == Approx(14.45).margin(0.01));
  CHECK(2 * g.wall_angle_from_vertical() == Approx(M_PI / 6).epsilon(0.04));
  CHECK(g.right_at(0.68) == Approx(0.5 * (0.1495 + 0.5)));
  CHECK(g.left_at(0.68) == Approx(-0.5 * (0.1495 + 0.5)));
  CHECK(g.contains({0, 1.0}, 0.065));
  CHECK_FALSE(g.contains({0.45, 0.1}, 0.065));  // through the hopper wall
  CHECK_FALSE(g.contains({0, 6.34}, 0.065));    // through the top
}
