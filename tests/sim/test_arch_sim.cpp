// Arches in the simulation: a staged Box2D arch holds and is found, and the clog rule removes exactly it.
#include <catch2/catch.hpp>

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
