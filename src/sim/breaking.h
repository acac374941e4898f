// The kick that breaks an arch (issue 51; Lozano, Lumay, Zuriguel, Hidalgo and Garcimartin, PRL 109, 068001,
// 2012): an arrested clog of a run is rebuilt by replaying the run (the same model, the same steps: the same
// state bit for bit), its drive and clog rule are switched off and it settles; then every grain is given the
// same upward velocity dv at once (the container dropped away from under the packing), or the paper's kick
// law with velocity changes up to dv, and the clog is broken when a grain leaves within the window after the
// lifted packing is back down. Copies of the state try amplitudes, doubling until one breaks it and
// bisecting between the last that held and the first that broke.
#pragma once

#include <string>
#include <vector>

#include "core/arch.h"
#include "core/events.h"
#include "core/model.h"

namespace sim {

struct BreakOptions {
  double settle = 0.2;     // s with no drive before the kick (the drive's own kicks die away)
  double window = 0.5;     // s in which an exit means the clog broke, from when the lifted packing is back
                           // down (2 dv / g after the kick)
  double dv_first = 0.02;  // m/s, the first amplitude tried (doubled until one breaks)
  double dv_max = 2.56;    // m/s, the largest tried
  int bisections = 8;      // halvings of the bracket once one broke
  // The kick: every grain lifted by dv at once (false), or the scene's kick law as velocity changes of size
  // up to dv, each grain its own plus one shared (true), drawn from the run's seed and the clog's row.
  bool random = false;
};

struct BreakResult {
  int clog = 0;           // row of clogs.csv, from 1
  double t = 0;           // s, when the kick was given
  std::string outcome;    // "broken", "held" (up to dv_max), "unstable" (broke with no kick), "no arch"
  std::vector<int> arch;  // members, left to right
  core::ArchDescriptors shape;
  double load_N = 0, held_N = 0;     // the arch's load from above and its walls' reaction, along gravity
  double dv_held = 0, dv_broke = 0;  // m/s: the largest amplitude that held, the smallest that broke
  int trials = 0;
};

// Every test of clog `c` (row `number`) of the run of `model`; `c` must be an arrested clog of that run.
// Throws core::InputError when the replay does not find the clog where the run had it (another build).
BreakResult break_clog(const core::Model& model, const core::ClogEvent& c, int number, const BreakOptions& o);

}  // namespace sim
