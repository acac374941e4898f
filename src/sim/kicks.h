// The vibration: every kick_period each disk gets its own impulse (direction uniform in [0, 2 pi), magnitude
// uniform in [0, J_max]) plus, if global_kick, one shared impulse drawn from the same law.
#pragma once

#include <vector>

#include "core/geometry.h"
#include "core/rng.h"

namespace sim {

// One impulse of the kick law, N*s.
inline core::Vec2 draw_kick(core::Rng& rng, double j_max) {
  double mag = rng.uniform(0.0, j_max);
  double ang = rng.uniform(0.0, 2.0 * 3.14159265358979323846);
  return {mag * std::cos(ang), mag * std::sin(ang)};
}

// The impulses of one kick for n disks: individual + shared. `out` is resized.
void draw_kicks(core::Rng& rng, double j_max, bool global, int n, std::vector<core::Vec2>& out);

}  // namespace sim
