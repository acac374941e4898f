// The container's geometry, derived from a scene: shared by the simulation, the renderer and the tests,
// so the walls are defined once. Coordinates in metres; the aperture is centred at (0, 0), y points up.
#pragma once

#include <array>
#include <cmath>

#include "core/scene.h"

namespace core {

struct Vec2 {
  double x = 0, y = 0;
};
inline Vec2 operator+(Vec2 a, Vec2 b) {
  return {a.x + b.x, a.y + b.y};
}
inline Vec2 operator-(Vec2 a, Vec2 b) {
  return {a.x - b.x, a.y - b.y};
}
inline Vec2 operator*(double k, Vec2 a) {
  return {k * a.x, k * a.y};
}
inline double dot(Vec2 a, Vec2 b) {
  return a.x * b.x + a.y * b.y;
}
inline double length(Vec2 a) {
  return std::sqrt(dot(a, a));
}

struct Segment {
  Vec2 a, b;
};

// Wall identifiers, used by contact graphs and the renderer.
enum class Wall : int { HopperLeft = 0, HopperRight, SiloLeft, SiloRight, Top, Lid, Count };

struct Geometry {
  double half_width;      // W/2, m
  double half_aperture;   // D/2, m
  double hopper_height;   // H_t, m
  double total_height;    // H_t + H_s, m
  double grain_diameter;  // 2 r_o, m: what cameras are sized by
  // The walls in order of Wall (Lid is the closed aperture during deposition).
  std::array<Segment, static_cast<int>(Wall::Count)> walls;

  // Angle of each hopper wall from the vertical, radians.
  double wall_angle_from_vertical() const { return std::atan((half_width - half_aperture) / hopper_height); }
  // Inner half-width of the container at height y (m): the hopper narrows linearly below H_t.
  double half_width_at(double y) const {
    if (y >= hopper_height) return half_width;
    if (y <= 0) return half_aperture;
    return half_aperture + (half_width - half_aperture) * y / hopper_height;
  }
  // Signed clearance of a disk at p with radius r from the side walls (negative: it pokes through).
  double side_clearance(Vec2 p, double r) const;
  // True if a disk of radius r at p lies inside the container (above the aperture line, below the top).
  bool contains(Vec2 p, double r) const;
};

Geometry make_geometry(const Scene& s);

}  // namespace core
