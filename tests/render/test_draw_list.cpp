// The draw list: what a frame becomes before any GL (render/draw_list.h).
#include <catch2/catch.hpp>

#include <cmath>

#include "core/geometry.h"
#include "core/setup.h"
#include "render/draw_list.h"
#include "render/grain_values.h"
#include "render/trails.h"

namespace {
core::Particle grain(float x, float y, float r, int species, int sides = 0) {
  core::Particle p{};
  p.x = x, p.y = y, p.radius = r, p.species = static_cast<core::Species>(species),
  p.sides = static_cast<std::uint8_t>(sides);
  return p;
}
}  // namespace

TEST_CASE(
    "the draw list: shapes with their colours, halos on arch members, bonds only between touching members",
    "[render]") {
  core::Scene s;
  core::apply_overrides(s, {"obstacle=disk", "obstacle_size=0.1", "obstacle_height=0.6"});
  const core::Geometry geo = core::make_geometry(s);
  core::Frame f;
  f.particles = {grain(-0.2f, 0.1f, 0.065f, 0), grain(-0.07f, 0.1f, 0.065f, 0),
                 grain(0.25f, 0.1f, 0.05f, 1, 5)};
  f.arch = {0, 1, 2};  // 0 and 1 touch; 1 and 2 are 0.32 m apart (an obstacle between them)
  f.since_last_exit = 2.0;
  render::Style style;
  const render::DrawList d = render::build_draw_list(f, geo, style);
  REQUIRE(d.shapes.size() == 4);  // three grains and the obstacle
  const render::Rgba red = render::species_color(style, core::Species::Original);
  CHECK(d.shapes[0].fill[0] == red.r);
  CHECK(d.shapes[0].halo[3] == 1.0f);  // clogged: the arch at full strength
  CHECK(d.shapes[2].shape[1] == 5.0f);
  CHECK(d.shapes[2].r == Approx(0.05 * core::polygon_extent(5)));  // the pentagon's circumradius
  CHECK(d.shapes[3].shape[1] == 0.0f);                             // the obstacle: a disk...
  CHECK(d.shapes[3].r == Approx(0.05));
  CHECK(d.shapes[3].halo[3] == 0.0f);  // ...without a halo
  REQUIRE(d.bonds.size() == 1);        // 0-1 only
  CHECK(d.bonds[0].ax == f.particles[0].x);
  CHECK(d.walls.size() == 5);
  // A scene's own colour wins over the palette's.
  style.species_colors = {{0.1f, 0.2f, 0.3f, 1}};
  CHECK(render::build_draw_list(f, geo, style).shapes[0].fill[2] == 0.3f);
  // Flowing: the arch is drawn faint.
  f.since_last_exit = 0.1;
  CHECK(render::build_draw_list(f, geo, style).shapes[0].halo[3] < 0.5f);
}

TEST_CASE("force chains: a segment per contact at or above the threshold, wider and brighter with the force",
          "[render]") {
  core::Scene s;
  const core::Geometry geo = core::make_geometry(s);
  core::Frame f;
  f.particles = {grain(-0.2f, 0.3f, 0.065f, 0), grain(-0.07f, 0.3f, 0.065f, 0), grain(0.06f, 0.3f, 0.065f, 0),
                 grain(0.19f, 0.3f, 0.065f, 0)};
  f.contacts = {{0, 1, 0.5f}, {1, 2, 5.0f}, {2, 3, 40.0f}};
  render::Style style;
  CHECK(render::build_draw_list(f, geo, style).chains.empty());  // off unless asked for
  style.chains = true;
  style.chain_min = 1.0;
  style.chain_max = 20.0;
  const render::DrawList d = render::build_draw_list(f, geo, style);
  REQUIRE(d.chains.size() == 2);  // 0.5 N is below the threshold
  REQUIRE(d.chain_width_m.size() == 2);
  CHECK(d.chains[0].ax == f.particles[1].x);
  CHECK(d.chains[1].bx == f.particles[3].x);
  CHECK(d.chain_width_m[1] > d.chain_width_m[0]);
  CHECK(d.chain_width_m[1] == Approx(0.065));  // at or above chain_max: the grain's radius
  // The colour map's top (yellow, viridis) at 40 N, its dark end near the threshold.
  CHECK(d.chains[1].color[0] > 0.8f);
  CHECK(d.chains[0].color[0] < 0.4f);
  // On grains coloured by force with viridis the chains take magma (they would vanish in the grains' own
  // map); a map asked for is used as it is.
  style.color = render::ColorMode::Force;
  CHECK(render::chain_colormap(style) == render::Colormap::Magma);
  const render::DrawList on_force = render::build_draw_list(f, geo, style);
  const render::Rgba magma_top = render::chain_color(style, 1.0), viridis_top = render::colormap(style, 1.0);
  CHECK(on_force.chains[1].color[2] == Approx(magma_top.b));
  CHECK(std::abs(magma_top.b - viridis_top.b) > 0.3f);
  style.chain_colormap = render::Colormap::Cividis;
  CHECK(render::chain_colormap(style) == render::Colormap::Cividis);
  style.chain_colormap.reset();
  style.colormap = render::Colormap::Inferno;
  CHECK(render::chain_colormap(style) == render::Colormap::Inferno);
}

TEST_CASE(
    "tracked grains: a ring of their own colour, a trail that fades, breaks at re-injection, restarts on "
    "a jump back",
    "[render]") {
  core::Scene s;
  const core::Geometry geo = core::make_geometry(s);
  render::Style style;
  style.tracked = {1};
  core::Frame f;
  f.particles = {grain(-0.2f, 0.5f, 0.065f, 0), grain(0.0f, 0.5f, 0.065f, 0)};
  const render::DrawList d = render::build_draw_list(f, geo, style);
  CHECK(d.shapes[1].halo[3] == 1.0f);  // the tracked grain's ring
  CHECK(d.shapes[1].halo[1] == render::tracked_color(style).g);
  CHECK(d.shapes[0].halo[3] == 0.0f);
  render::Trails trails;
  for (int k = 0; k < 5; ++k) {  // falling 2 cm per frame
    f.t = 0.1 * k;
    f.particles[1].y = 0.5f - 0.02f * static_cast<float>(k);
    trails.update(f, style.tracked, 1.0);
  }
  render::DrawList list;
  trails.append(list, f, render::tracked_color(style));
  REQUIRE(list.trails.size() == 4);
  REQUIRE(list.trail_width_m.size() == 4);
  CHECK(list.trails.front().color[3] < list.trails.back().color[3]);  // older: fainter
  CHECK(list.trails.back().by == Approx(0.42));
  // Re-injected at the top: no segment across the silo.
  f.t = 0.5;
  f.particles[1].y = 3.0f;
  trails.update(f, style.tracked, 1.0);
  render::DrawList after;
  trails.append(after, f, render::tracked_color(style));
  CHECK(after.trails.size() == 4);
  // A jump back in time (the inspector): the trail starts afresh.
  f.t = 0.05;
  trails.update(f, style.tracked, 1.0);
  CHECK(trails.points(1) == 1);
}

TEST_CASE("colour by coordination: solver contacts when the frame has them, touching disks when it has not",
          "[render]") {
  core::Frame f;
  // Three disks in a row, 0-1 and 1-2 touching (within 2% of the radii), 3 far off; 4 just out of reach of 2.
  f.particles = {grain(0, 0, 0.05f, 0), grain(0.1f, 0, 0.05f, 0), grain(0.2005f, 0, 0.05f, 1),
                 grain(2, 2, 0.05f, 0), grain(0.3035f, 0, 0.05f, 0)};
  const std::vector<float> z = render::coordination(f);
  CHECK(z == std::vector<float>{1, 2, 1, 0, 0});
  f.contacts = {{0, 3, 1.0f}, {0, 1, 0.0f}};  // the solver's word wins, touching with no force included
  CHECK(render::coordination(f) == std::vector<float>{2, 1, 0, 1, 0});
  // On the colour map from color_min to coordination_max: 2 of 0-4 is the middle of the map.
  render::Style style;
  style.color = render::ColorMode::Coordination;
  style.coordination_max = 4;
  style.colormap = render::Colormap::Magma;
  render::GrainValues values;
  const std::vector<float>& v = values.update(f, style);
  const render::DrawList d =
      render::build_draw_list(f, core::make_geometry(core::Scene{}), style, {}, &v, style.coordination_max);
  const render::Rgba mid = render::colormap(style, 0.5), top = render::colormap(style, 1.0);
  CHECK(d.shapes[0].fill[0] == mid.r);
  CHECK(d.shapes[0].fill[2] == mid.b);
  CHECK(d.shapes[2].fill[0] != mid.r);
  CHECK(top.r > 0.9f);  // magma ends light
  CHECK(values.largest() == 2);
}

TEST_CASE("colour by displacement: from the reference frame on, re-injected grains without a value",
          "[render]") {
  render::Style style;
  style.color = render::ColorMode::Displacement;
  style.displacement_from = 1.0;
  render::GrainValues values;
  core::Frame f;
  f.t = 0.5;
  f.particles = {grain(0, 1, 0.05f, 0), grain(0.3f, 1, 0.05f, 0)};
  CHECK(values.update(f, style) == std::vector<float>{0, 0});  // before the reference time: none moved
  f.t = 1.0;                                                   // the reference
  values.update(f, style);
  f.t = 2.0;
  f.particles[0].x = 0.3f, f.particles[0].y = 0.6f;  // moved 0.5 m
  f.particles[1].y = 3.0f;                           // re-injected at the top
  const std::vector<float> v = values.update(f, style);
  CHECK(v[0] == Approx(0.5f));
  CHECK(std::isnan(v[1]));
  CHECK(values.largest() == Approx(0.5));
  const render::Rgba grey = render::value_color(style, v[1], 1.0);
  CHECK(grey.r == grey.g);
  // A jump back before the reference starts afresh: nothing has moved since the new reference.
  f.t = 0.2;
  values.update(f, style);
  f.t = 1.5;
  CHECK(values.update(f, style) == std::vector<float>{0, 0});
}

TEST_CASE("colour by id: neighbouring ids get distinguishable colours", "[render]") {
  for (int id = 0; id < 500; ++id) {
    const render::Rgba a = render::id_color(id), b = render::id_color(id + 1);
    const double d = std::fabs(a.r - b.r) + std::fabs(a.g - b.g) + std::fabs(a.b - b.b);
    CHECK(d > 0.25);
  }
}

TEST_CASE("colour options: every bad value names what is allowed", "[render]") {
  CHECK_THROWS_WITH(render::parse_color_mode("pressure"),
                    Catch::Contains("displacement, coordination, stress or id"));
  CHECK_THROWS_WITH(render::parse_colormap("jet"), Catch::Contains("viridis, magma, inferno or cividis"));
  render::Style s;
  s.color = render::ColorMode::Coordination;
  CHECK_THROWS_WITH(render::set_color_range(s, "auto"), Catch::Contains("for displacement"));
  CHECK_THROWS_WITH(render::set_color_range(s, "5:2"), Catch::Contains("0 <= MIN < MAX"));
  CHECK_THROWS_WITH(render::set_color_range(s, "x"), Catch::Contains("MIN:MAX"));
  render::set_color_range(s, "2:5");
  CHECK(s.color_min == 2);
  CHECK(s.coordination_max == 5);
  s.color = render::ColorMode::Id;
  CHECK_THROWS_WITH(render::set_color_range(s, "5"), Catch::Contains("not id"));
  s.color = render::ColorMode::Displacement;
  render::set_color_range(s, "auto");
  CHECK(s.displacement_max == 0);
}

TEST_CASE(
    "arch force arrows: one per force from outside the arch, ending at its contact point, scaled to the "
    "largest",
    "[render][forces]") {
  core::Scene s;
  const core::Geometry geo = core::make_geometry(s);
  core::Frame f;
  f.particles = {grain(-0.05f, 0.1f, 0.05f, 0), grain(0.05f, 0.1f, 0.05f, 0), grain(0.0f, 0.19f, 0.05f, 0)};
  f.arch = {0, 1};
  f.clog_open = true;
  auto contact = [](int a, int b, float fn, float ft, float px, float py, float nx, float ny) {
    core::Contact c{a, b, fn};
    c.ft = ft, c.px = px, c.py = py, c.nx = nx, c.ny = ny;
    return c;
  };
  // Member 0 and 1 press on each other (inside the arch: no arrow); grain 2 loads member 0 from above with
  // 5 N; the left wall pushes member 0 with 10 N to the right (normal from the wall, a = -1) and 2 N of
  // friction.
  f.contacts = {contact(0, 1, 7, 0, 0, 0.1f, 1, 0), contact(2, 0, 5, 0, -0.025f, 0.145f, 0, -1)};
  f.wall_contacts = {contact(-1, 0, 10, 2, -0.1f, 0.1f, 1, 0)};
  render::Style style;
  CHECK(render::build_draw_list(f, geo, style).chains.empty());  // off by default
  style.arch_forces = true;
  const render::DrawList d = render::build_draw_list(f, geo, style);
  REQUIRE(d.chains.size() == 6);  // two arrows: a shaft and two barbs each
  CHECK(render::largest_arch_force(f) == Approx(std::hypot(10.0, 2.0)));
  // The shafts end at the contact points; the largest is a member's diameter (0.1 m) long, the other in
  // proportion, each along its force on the member (the wall's: 10 along +x, friction 2 along (ny, -nx)).
  const auto& load = d.chains[0];
  CHECK(load.bx == Approx(-0.025f));
  CHECK(load.by == Approx(0.145f));
  CHECK(std::hypot(load.bx - load.ax, load.by - load.ay) == Approx(0.1 * 5 / std::hypot(10.0, 2.0)));
  CHECK(load.by < load.ay);  // pressed down
  const auto& wall = d.chains[3];
  CHECK(wall.bx == Approx(-0.1f));
  CHECK(std::hypot(wall.bx - wall.ax, wall.by - wall.ay) == Approx(0.1));
  CHECK((wall.bx - wall.ax) / (wall.by - wall.ay) == Approx(10.0 / -2.0));
  // Without the contacts' geometry (a version-1 file), or without a shown arch, none.
  core::Frame old = f;
  for (auto* list : {&old.contacts, &old.wall_contacts})
    for (auto& c : *list) c.nx = c.ny = 0;
  CHECK(render::build_draw_list(old, geo, style).chains.empty());
  style.show_arch = false;
  CHECK(render::build_draw_list(f, geo, style).chains.empty());
}
