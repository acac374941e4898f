#include "core/geometry.h"

#include <algorithm>

namespace core {

namespace {
double distance_to_segment(Vec2 p, const Segment& s) {
  Vec2 ab = s.b - s.a;
  double t = std::clamp(dot(p - s.a, ab) / dot(ab, ab), 0.0, 1.0);
  return length(p - (s.a + t * ab));
}
}  // namespace

Geometry make_geometry(const Scene& s) {
  Geometry g;
  g.half_width = 0.5 * s.silo_width;
  g.half_aperture = 0.5 * s.aperture;
  g.hopper_height = s.hopper_height;
  g.total_height = s.hopper_height + s.silo_height;
  g.grain_diameter = 2 * s.radius_original;
  const double w = g.half_width, a = g.half_aperture, h = g.hopper_height, top = g.total_height;
  g.walls[static_cast<int>(Wall::HopperLeft)] = {{-w, h}, {-a, 0}};
  g.walls[static_cast<int>(Wall::HopperRight)] = {{a, 0}, {w, h}};
  g.walls[static_cast<int>(Wall::SiloLeft)] = {{-w, top}, {-w, h}};
  g.walls[static_cast<int>(Wall::SiloRight)] = {{w, h}, {w, top}};
  g.walls[static_cast<int>(Wall::Top)] = {{-w, top}, {w, top}};
  g.walls[static_cast<int>(Wall::Lid)] = {{-a, 0}, {a, 0}};
  return g;
}

double Geometry::side_clearance(Vec2 p, double r) const {
  double d = std::min({distance_to_segment(p, walls[0]), distance_to_segment(p, walls[1]),
                       distance_to_segment(p, walls[2]), distance_to_segment(p, walls[3])});
  bool inside = std::abs(p.x) < half_width_at(p.y);
  return (inside ? d : -d) - r;
}

bool Geometry::contains(Vec2 p, double r) const {
  if (p.y - r < 0 || p.y + r > total_height) return false;
  return side_clearance(p, r) >= 0;
}

}  // namespace core
