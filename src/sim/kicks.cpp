#include "sim/kicks.h"

namespace sim {

void draw_kicks(core::Rng& rng, double j_max, bool global, int n, std::vector<core::Vec2>& out) {
  out.resize(n);
  // The shared impulse is drawn first so the individual draws do not depend on the global_kick switch.
  core::Vec2 shared = draw_kick(rng, j_max);
  if (!global) shared = {};
  for (int i = 0; i < n; ++i) out[i] = draw_kick(rng, j_max) + shared;
}

}  // namespace sim
