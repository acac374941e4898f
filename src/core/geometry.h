// The container's geometry, derived from a scene: shared by the simulation, the renderer and the tests,
// so the walls are defined once. Coordinates in metres, in the container's own frame: the outlet is centred
// at (0, 0) and y points up (a tilted or vibrating container moves this frame; see core/setup.h).
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
// Distance from p to the segment s, m.
double distance_to_segment(Vec2 p, const Segment& s);

// Wall identifiers, used by contact graphs and the renderer. HopperLeft and HopperRight are the walls the
// outlet opens between: the sloped hopper walls, or the two halves of a flat floor.
enum class Wall : int { HopperLeft = 0, HopperRight, SiloLeft, SiloRight, Top, Lid, Obstacle, Count };

enum class ContainerKind { Hopper, Flat };

// An obstacle above the outlet: a disk (width = height = its diameter) or a horizontal bar.
struct Obstacle {
  enum class Kind { None, Disk, Bar } kind = Kind::None;
  Vec2 centre;        // m
  double width = 0;   // m: the disk's diameter, the bar's width
  double height = 0;  // m: the disk's diameter, the bar's thickness
  bool present() const { return kind != Kind::None; }
  // Signed distance from p to the obstacle's surface (negative inside), m.
  double gap(Vec2 p) const;
};

struct Geometry {
  ContainerKind kind = ContainerKind::Hopper;
  double half_width;       // W/2, m
  double x_left, x_right;  // the silo's side walls, m (-W/2 and W/2 shifted by -outlet_x)
  double half_aperture;    // D/2, m
  double hopper_height;    // H_t, m (0 for a flat silo)
  double total_height;     // H_t + H_s, m
  double grain_diameter;   // the largest species' mean diameter, m: what cameras and slabs are sized by
  // The walls in order of Wall (Lid is the closed aperture during deposition; Obstacle is unused here: see
  // `obstacle`).
  std::array<Segment, static_cast<int>(Wall::Count)> walls;
  Obstacle obstacle;
  double tilt = 0;  // rad: the container stands turned counter-clockwise by this (gravity at an angle)

  // Angle of each bottom wall from the vertical, radians (90 degrees for a flat floor).
  double left_wall_angle() const;
  double right_wall_angle() const;
  // The mean of the two (the paper's hopper: 14.45 degrees).
  double wall_angle_from_vertical() const { return 0.5 * (left_wall_angle() + right_wall_angle()); }
  // Inner side walls at height y (m): the hopper narrows linearly below H_t to the outlet's edges.
  double left_at(double y) const {
    if (y >= hopper_height) return x_left;
    if (y <= 0) return -half_aperture;
    return -half_aperture + (x_left + half_aperture) * y / hopper_height;
  }
  double right_at(double y) const {
    if (y >= hopper_height) return x_right;
    if (y <= 0) return half_aperture;
    return half_aperture + (x_right - half_aperture) * y / hopper_height;
  }
  double width_at(double y) const { return right_at(y) - left_at(y); }
  // Signed clearance of a disk at p with radius r from the side walls, the floor and the obstacle (negative:
  // it pokes through).
  double side_clearance(Vec2 p, double r) const;
  // True if a disk of radius r at p lies inside the container (above the aperture line, below the top).
  bool contains(Vec2 p, double r) const;
  // The container's area below the top (m^2), the obstacle left out.
  double area() const;
};

Geometry make_geometry(const Scene& s);

}  // namespace core
