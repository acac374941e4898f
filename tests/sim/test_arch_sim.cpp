// Arches in the simulation: a staged Box2D arch holds and is found, and the clog rule removes exactly it.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "fixtures.h"

using test::StagedArch;

TEST_CASE("a real Box2D arch of 3 disks holds under gravity and is detected", "[arch][sim]") {
  StagedArch s;
  s.hopper->advance_to(2.0);
  auto p = s.hopper->positions();
  CHECK(std::abs(p[1].y - s.y_top) < 1e-3);  // the keystone has not moved by a millimetre
  CHECK(s.hopper->events().exits.empty());
  CHECK(s.hopper->current_arch() == std::vector<int>{0, 1, 2});
  CHECK(s.hopper->frame(true).arch == std::vector<int>{0, 1, 2});
}

TEST_CASE("the clog rule fires at clog_timeout, removes exactly the arch and re-injects it", "[arch][sim]") {
  StagedArch s;
  auto& h = *s.hopper;
  while (h.events().arches.empty() && h.time() < 6.0) h.step();
  REQUIRE(h.events().arches.size() == 1);
  const auto& ev = h.events().arches[0];
  CHECK(ev.t == Approx(s.scene.clog_timeout).margin(s.scene.dt));
  CHECK(ev.clog_duration == Approx(5.0).margin(s.scene.dt));
  CHECK(ev.ids == std::vector<int>{0, 1, 2});
  CHECK(ev.method == core::ArchMethod::ContactPath);
  CHECK(ev.geometry.span > 0.3);
  auto p = h.positions();
  for (int id : {0, 1, 2}) CHECK(p[id].y > 0.4);  // re-injected above the (tiny) column
  for (int id : {3, 4}) CHECK(p[id].y < 0.4);     // the load stayed where it was
  h.finish();
  REQUIRE(h.events().clogs.size() >= 1);
  CHECK(h.events().clogs[0].ended_by == core::ClogEnd::Rule);
  CHECK(h.events().clogs[0].arrested);
}

TEST_CASE("arches shown agree with the clog rule's, and a flowing outlet shows none that blocks nothing",
          "[arch][sim]") {
  core::Scene s;  // the built-in default: the paper's hopper at the literal kick
  s.seed = 3;
  sim::Silo h(core::compile(s));
  const auto& geo = h.geometry();
  int shown = 0, frames = 0, agreed = 0;
  size_t rules = 0;
  std::vector<int> before_rule;
  while (h.time() < 40.0) {
    // The frame a picture would show just before the rule fires: the arch arches.csv records.
    const bool rule_next = s.clog_timeout - h.frame(false).since_last_exit < 1.5 * s.dt;
    if (rule_next) before_rule = h.frame(false).arch;
    h.step();
    if (h.events().arches.size() > rules) {
      rules = h.events().arches.size();
      agreed += before_rule == h.events().arches.back().ids;
    }
    if (h.steps() % 50 != 0) continue;
    const core::Frame f = h.frame(false);
    ++frames;
    if (f.arch.empty()) continue;
    ++shown;
    // Two or more grains, from left of the outlet's centre to right of it, in contact in order.
    CHECK(f.arch.size() >= 2);
    const auto p = h.positions();
    CHECK(p[static_cast<size_t>(f.arch.front())].x < 0);
    CHECK(p[static_cast<size_t>(f.arch.back())].x > 0);
    // No grain beneath the chain (below its lowest member) inside the opening.
    double lowest = INFINITY;
    for (int id : f.arch) lowest = std::min(lowest, p[static_cast<size_t>(id)].y);
    for (int i = 0; i < h.particle_count(); ++i) {
      if (std::find(f.arch.begin(), f.arch.end(), i) != f.arch.end()) continue;
      const auto q = p[static_cast<size_t>(i)];
      const double r = h.radii()[static_cast<size_t>(i)];
      if (std::abs(q.x) < geo.half_aperture - r && q.y > -r) CHECK(q.y > lowest);
    }
  }
  INFO(shown << " of " << frames << " frames show an arch; " << agreed << " of " << rules << " rule firings");
  REQUIRE(rules >= 3);
  CHECK(agreed == static_cast<int>(rules));
  CHECK(shown > 0);
  CHECK(shown < frames);
}
