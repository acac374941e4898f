#include "core/frame.h"

#include <cmath>

#include "core/portable_math.h"

namespace core {

std::string species_name(Species s) {
  if (s == Species::Original) return "original";
  if (s == Species::Added) return "added";
  return "species " + std::to_string(species_index(s));
}

double polygon_extent(int sides) {
  if (sides < 3) return 1.0;
  double sn = 0, cs = 0;
  portable::sincos(2 * 3.14159265358979323846 / sides, sn, cs);
  return std::sqrt(2 * 3.14159265358979323846 / (sides * sn));
}

bool within_reach(const Particle& a, const Particle& b) {
  const double reach = 1.1 * (a.radius * polygon_extent(a.sides) + b.radius * polygon_extent(b.sides));
  return std::hypot(static_cast<double>(a.x) - b.x, static_cast<double>(a.y) - b.y) <= reach;
}

const char* clog_end_name(ClogEnd e) {
  switch (e) {
    case ClogEnd::Spontaneous:
      return "spontaneous";
    case ClogEnd::Vibration:
      return "vibration";
    case ClogEnd::Rule:
      return "rule";
    case ClogEnd::RunEnd:
      return "run_end";
  }
  return "unknown";
}

}  // namespace core
