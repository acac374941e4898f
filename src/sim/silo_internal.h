// What the Silo's own files share (silo.cpp, silo_fill.cpp, silo_health.cpp): how fixtures are
// tagged, the overlap bound, number formatting for messages. Not for use outside sim/.
#pragma once

#include <box2d/box2d.h>

#include <cstdint>
#include <string>

#include "core/format.h"

namespace sim::internal {

inline std::string fmt4(double v) {
  return core::format_g(v, 4);
}
// Fixture user data: particle id + 1, or kWallTag + wall index.
constexpr std::uintptr_t kWallTag = 1u << 30;
// Overlap (fraction of the smaller radius of a pair) past which the integration is considered broken.
constexpr double kMaxOverlapFraction = 0.5;

// Decode a fixture: particle id (>= 0), or -1 - wall index.
inline int decode(const b2Fixture* f) {
  std::uintptr_t u = const_cast<b2Fixture*>(f)->GetUserData().pointer;
  if (u >= kWallTag) return -1 - static_cast<int>(u - kWallTag);
  return static_cast<int>(u) - 1;
}

}  // namespace sim::internal
