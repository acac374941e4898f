#include "core/geometry.h"

#include <algorithm>

#include "core/physics.h"
#include "core/setup.h"

namespace core {

double distance_to_segment(Vec2 p, const Segment& s) {
  Vec2 ab = s.b - s.a;
  const double len2 = dot(ab, ab);
  double t = len2 > 0 ? std::clamp(dot(p - s.a, ab) / len2, 0.0, 1.0) : 0.0;
  return length(p - (s.a + t * ab));
}

double Obstacle::gap(Vec2 p) const {
  switch (kind) {
    case Kind::None:
      return INFINITY;
    case Kind::Disk:
      return length(p - centre) - 0.5 * width;
    case Kind::Bar: {
      // Signed distance to an axis-aligned box.
      const double dx = std::abs(p.x - centre.x) - 0.5 * width, dy = std::abs(p.y - centre.y) - 0.5 * height;
      const double outside = length({std::max(dx, 0.0), std::max(dy, 0.0)});
      return outside + std::min(std::max(dx, dy), 0.0);
    }
  }
  return INFINITY;
}

Geometry make_geometry(const Scene& s) {
  Geometry g;
  g.kind = s.container == "flat" ? ContainerKind::Flat : ContainerKind::Hopper;
  g.half_width = 0.5 * s.silo_width;
  g.x_left = -g.half_width - s.outlet_x;
  g.x_right = g.half_width - s.outlet_x;
  g.half_aperture = 0.5 * s.aperture;
  g.hopper_height = g.kind == ContainerKind::Flat ? 0.0 : hopper_height_of(s);
  g.total_height = g.hopper_height + s.silo_height;
  g.grain_diameter = 2 * reference_radius(s);
  g.tilt = s.tilt * kPi / 180.0;
  const double a = g.half_aperture, h = g.hopper_height, top = g.total_height;
  const double xl = g.x_left, xr = g.x_right;
  g.walls[static_cast<int>(Wall::HopperLeft)] = {{xl, h}, {-a, 0}};
  g.walls[static_cast<int>(Wall::HopperRight)] = {{a, 0}, {xr, h}};
  g.walls[static_cast<int>(Wall::SiloLeft)] = {{xl, top}, {xl, h}};
  g.walls[static_cast<int>(Wall::SiloRight)] = {{xr, h}, {xr, top}};
  g.walls[static_cast<int>(Wall::Top)] = {{xl, top}, {xr, top}};
  g.walls[static_cast<int>(Wall::Lid)] = {{-a, 0}, {a, 0}};
  g.walls[static_cast<int>(Wall::Obstacle)] = {};
  if (s.obstacle != "none") {
    g.obstacle.kind = s.obstacle == "disk" ? Obstacle::Kind::Disk : Obstacle::Kind::Bar;
    g.obstacle.centre = {s.obstacle_x, s.obstacle_height};
    g.obstacle.width = s.obstacle_size;
    g.obstacle.height = s.obstacle == "disk" ? s.obstacle_size : s.obstacle_thickness;
  }
  return g;
}

double Geometry::left_wall_angle() const {
  if (hopper_height <= 0) return 0.5 * kPi;
  return std::atan((-half_aperture - x_left) / hopper_height);
}
double Geometry::right_wall_angle() const {
  if (hopper_height <= 0) return 0.5 * kPi;
  return std::atan((x_right - half_aperture) / hopper_height);
}

double Geometry::side_clearance(Vec2 p, double r) const {
  double d = std::min({distance_to_segment(p, walls[0]), distance_to_segment(p, walls[1]),
                       distance_to_segment(p, walls[2]), distance_to_segment(p, walls[3])});
  bool inside = p.x > left_at(p.y) && p.x < right_at(p.y);
  if (kind == ContainerKind::Flat && p.y < 0) inside = false;
  double c = (inside ? d : -d) - r;
  if (obstacle.present()) c = std::min(c, obstacle.gap(p) - r);
  return c;
}

bool Geometry::contains(Vec2 p, double r) const {
  if (p.y - r < 0 || p.y + r > total_height) return false;
  return side_clearance(p, r) >= 0;
}

double Geometry::area() const {
  return (x_right - x_left) * (total_height - hopper_height) +
         0.5 * ((x_right - x_left) + 2 * half_aperture) * hopper_height;
}

}  // namespace core
