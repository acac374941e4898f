// Arches in the simulation: a staged Box2D arch holds and is found, and the clog rule removes exactly it.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "core/scene.h"
#include "fixtures.h"
#include "sim/silo.h"

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
          "[arch][sim][heavy]") {
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

TEST_CASE(
    "every arch shown in every preset is a chain of touching grains, formed no later than it is confirmed",
    "[arch][sim][slow]") {
  // Each preset 20 s. Every 0.1 s the arch a frame shows is checked by geometry alone: consecutive members no
  // farther apart than their shapes allow (disks: centre distance at most the radii and 5% of the smaller
  // one; polygons: their circumradii), or both on the obstacle. At each clog's confirmation (the step it
  // opens) with an arch standing, its formation lies between the clog's start and now.
  for (const char* name : {"paper", "paper-vibrated", "vibrated-silo", "pentagons", "silo-obstacle",
                           "three-species", "tilted-silo", "pure"}) {
    INFO(name);
    core::Scene s = core::load_scene(std::string(SILOSCOPE_SOURCE_DIR) + "/assets/scenes/" + name + ".toml");
    s.duration = 20;
    sim::Silo h(core::compile(s));
    const core::Geometry geo = h.geometry();
    const double ob_reach =
        geo.obstacle.present() ? 0.5 * std::max(geo.obstacle.width, geo.obstacle.height) : 0;
    long shown = 0, confirmed_with_arch = 0;
    int last_number = 0;
    while (h.time() < s.duration) {
      h.advance_to(h.time() + s.dt);
      const core::ClogState& st = h.clog();
      if (st.open && st.number != last_number) {  // the step that confirmed it
        last_number = st.number;
        if (!st.arch.empty()) {
          ++confirmed_with_arch;
          CHECK(st.formed >= st.start - 1e-9);
          CHECK(st.formed <= h.time() + 1e-9);
          CHECK(st.arrival.size() == st.arch.size());
        }
      }
      if (h.steps() % 100 != 0) continue;
      const core::Frame f = h.frame(false);
      if (f.arch.empty()) continue;
      ++shown;
      for (size_t k = 1; k < f.arch.size(); ++k) {
        const core::Particle& a = f.particles[static_cast<size_t>(f.arch[k - 1])];
        const core::Particle& b = f.particles[static_cast<size_t>(f.arch[k])];
        auto reach_of = [](const core::Particle& p) { return p.sides ? 1.7 * p.radius : 1.0 * p.radius; };
        const double reach = reach_of(a) + reach_of(b) + 0.05 * std::min(a.radius, b.radius) + 1e-6;
        // Two grains on the obstacle are linked by it (centres within its reach and theirs).
        auto on_obstacle = [&](const core::Particle& p) {
          return ob_reach > 0 && std::hypot(p.x - geo.obstacle.centre.x - f.container_x,
                                            p.y - geo.obstacle.centre.y - f.container_y) <=
                                     1.5 * ob_reach + reach_of(p) + 0.05 * p.radius;
        };
        INFO("t = " << h.time() << " s, members " << f.arch[k - 1] << " and " << f.arch[k]);
        CHECK((std::hypot(a.x - b.x, a.y - b.y) <= reach || (on_obstacle(a) && on_obstacle(b))));
      }
    }
    h.finish();
    for (const core::ClogEvent& c : h.events().clogs)
      if (!std::isnan(c.formed)) CHECK((c.formed >= c.start - 1e-9 && c.formed <= c.end + 1e-9));
    INFO(shown << " frames with an arch, " << confirmed_with_arch << " clogs confirmed with one");
    CHECK(confirmed_with_arch > 0);
    CHECK(shown > 0);
  }
}
