// The kick that breaks an arch: replays, copies and bisection (sim/breaking.h).
#include "sim/breaking.h"

#include <cmath>
#include <memory>

#include "core/error.h"
#include "core/forces.h"
#include "core/format.h"
#include "core/interrupt.h"
#include "sim/silo.h"

namespace sim {

namespace {

// The run replayed to the first step at which clog `c` is open, arrested and shows its arch (touching): the
// step count, or 0 when the clog never got there.
std::uint64_t arrested_step(const core::Model& model, const core::ClogEvent& c) {
  Silo s(model);
  const double dt = model.scene.dt;
  while (s.time() < c.end - dt / 2) {
    s.step();
    if (s.time() < c.start) continue;
    if (s.clog().open && s.clog().arrested && std::abs(s.clog().start - c.start) < dt / 2 &&
        !s.frame(false).arch.empty())
      return s.steps();
    if ((s.steps() & 1023) == 0) core::throw_if_interrupted();
  }
  return 0;
}

// A copy of the state at `step`, its drive and rule off, settled.
std::unique_ptr<Silo> copy_at(const core::Model& model, std::uint64_t step, const BreakOptions& o) {
  auto s = std::make_unique<Silo>(model);
  while (s->steps() < step) {
    s->step();
    if ((s->steps() & 1023) == 0) core::throw_if_interrupted();
  }
  s->set_kick_impulse_max(0);
  s->set_clog_rule(false);
  s->advance_to(s->time() + o.settle);
  return s;
}

}  // namespace

BreakResult break_clog(const core::Model& model, const core::ClogEvent& c, int number,
                       const BreakOptions& o) {
  if (model.setup.drive.vibrating())
    throw core::InputError(
        "the break test kicks a still container: this scene vibrates its container "
        "(vibration_amplitude or vibration_gamma)");
  BreakResult r;
  r.clog = number;
  const std::uint64_t step = arrested_step(model, c);
  if (step == 0) {
    r.outcome = "no arch";
    return r;
  }
  // The state every copy starts from: what it looks like, and what it carries.
  {
    auto s = copy_at(model, step, o);
    r.t = s->time();
    const size_t exits = s->events().exits.size();
    r.arch = s->frame(false).arch;
    if (r.arch.empty() || s->events().exits.size() != exits) {
      r.outcome = "unstable";
      return r;
    }
    r.shape = core::arch_descriptors(r.arch, s->positions(), s->radii());
    const core::ArchBalance b = core::arch_balance(s->contact_forces(), r.arch, s->weights());
    const core::Vec2 g = s->setup().gravity;
    const core::Vec2 down{g.x / core::length(g), g.y / core::length(g)};
    r.load_N = b.load(down);
    r.held_N = b.held(down);
  }
  // One try: the copy kicked by dv; broken when a grain leaves within the window.
  auto breaks = [&](double dv) {
    auto s = copy_at(model, step, o);
    const size_t exits = s->events().exits.size();
    s->kick_all(dv, o.random, model.scene.seed * 1000003u + static_cast<std::uint64_t>(number));
    // The window opens when a grain lifted by dv is back down (2 dv / g of flight).
    s->advance_to(s->time() + o.window + 2 * dv / core::length(model.setup.gravity));
    ++r.trials;
    return s->events().exits.size() > exits;
  };
  if (breaks(0)) {
    r.outcome = "unstable";
    return r;
  }
  double lo = 0, hi = o.dv_first;
  while (!breaks(hi)) {
    lo = hi;
    if (hi >= o.dv_max) {
      r.outcome = "held";
      r.dv_held = lo;
      r.dv_broke = NAN;
      return r;
    }
    hi = std::min(2 * hi, o.dv_max);
  }
  for (int k = 0; k < o.bisections; ++k) {
    const double mid = (lo + hi) / 2;
    (breaks(mid) ? hi : lo) = mid;
  }
  r.outcome = "broken";
  r.dv_held = lo;
  r.dv_broke = hi;
  return r;
}

}  // namespace sim
