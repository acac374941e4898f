// The simulation of scenes beyond the paper's hopper: flat silos, polygons, obstacles, a vibrating or tilted
// container, size distributions, dipoles on any species, the clog rule off.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/format.h"
#include "core/scene.h"
#include "core/setup.h"
#include "sim/dipole.h"
#include "sim/silo.h"

namespace {
// A small flat silo: `extra` keys on top (n grains of one species "g").
core::Scene flat_silo(std::vector<std::string> extra, int n = 80) {
  core::Scene s = core::parse_scene(
      "container = \"flat\"\nsilo_width = 0.8\nsilo_height = 1.5\naperture = 0.3\nkick_impulse_max = 0.0\n"
      "settle_time = 1.5\nclog_timeout = 1.0\narch_wall_reach = 0.4\n[[species]]\nname = \"g\"\ncount = " +
          std::to_string(n) + "\nsize = \"uniform\"\nradius_min = 0.04\nradius_max = 0.05\n",
      "flat");
  core::apply_overrides(s, extra);
  return s;
}
}  // namespace

TEST_CASE("a flat silo discharges through its floor, its arches from floor to floor", "[sim][scenes]") {
  sim::Silo h(core::compile(flat_silo({})));
  const auto& g = h.geometry();
  // Settled above the floor, inside the walls.
  for (auto p : h.positions()) {
    CHECK(p.y > 0.0);
    CHECK(p.x > g.x_left);
    CHECK(p.x < g.x_right);
  }
  long arches_checked = 0;
  while (h.time() < 12.0) {
    h.step();
    if (h.steps() % 100 != 0) continue;
    const auto arch = h.current_arch();
    if (arch.empty()) continue;
    // At least two grains, the first touching the left floor and the last the right floor.
    const auto cg = h.contact_graph();
    CHECK(arch.size() >= 2);
    CHECK(cg.touches_left[arch.front()]);
    CHECK(cg.touches_right[arch.back()]);
    ++arches_checked;
  }
  CHECK(h.events().exits.size() > 20);
  CHECK(arches_checked > 0);
}

TEST_CASE("polygons: Box2D polygons of equal area, at random orientations, drawn by their sides",
          "[sim][scenes]") {
  sim::Silo h(core::compile(flat_silo({"species.g.sides=5", "seed=3"})));
  const core::Frame f = h.frame(false);
  std::vector<double> angles;
  for (const auto& p : f.particles) {
    CHECK(p.sides == 5);
    angles.push_back(std::fmod(std::fmod(p.angle, 2 * M_PI / 5) + 2 * M_PI / 5, 2 * M_PI / 5));
  }
  // Orientations spread over the pentagon's symmetry (not all alike).
  const auto [lo, hi] = std::minmax_element(angles.begin(), angles.end());
  CHECK(*hi - *lo > 0.8 * 2 * M_PI / 5);
  h.advance_to(8.0);
  CHECK(h.events().exits.size() > 5);
  CHECK(h.overlaps().max < 0.5);  // the health monitor judged polygon overlaps, and found them sound
}

TEST_CASE("the obstacle stands where the scene says and no grain enters it", "[sim][scenes]") {
  sim::Silo h(core::compile(flat_silo({"obstacle=disk", "obstacle_size=0.2", "obstacle_height=0.45"})));
  const auto& ob = h.geometry().obstacle;
  REQUIRE(ob.present());
  double deepest = 0;
  for (int k = 0; k < 40; ++k) {
    h.advance_to(0.1 * (k + 1));
    const auto pos = h.positions();
    const auto r = h.radii();
    for (size_t i = 0; i < pos.size(); ++i) deepest = std::min(deepest, ob.gap(pos[i]) - r[i]);
  }
  CHECK(deepest > -0.005);  // at most Box2D's slop
}

TEST_CASE("a vibrating container follows A sin(omega t) and lifts the grains at Gamma > 1", "[sim][scenes]") {
  sim::Silo h(core::compile(flat_silo({"vibration_gamma=3", "vibration_frequency=10", "clog_timeout=0"})));
  const core::Setup& st = h.setup();
  REQUIRE(st.drive.vibrating());
  double worst = 0;
  std::vector<double> lowest;
  for (int k = 1; k <= 400; ++k) {
    h.step();
    worst = std::max(worst, std::abs(h.container_offset().y - core::container_offset(st, h.time()).y));
    if (k % 10 == 0) {
      const auto f = h.frame(false);
      CHECK(f.container_y == h.container_offset().y);
    }
  }
  CHECK(worst < 1e-6);  // metres: float rounding only, never accumulating
  CHECK(h.container_offset().x == 0.0);
  // The clog rule is off: no arch is ever removed.
  CHECK(h.events().arches.empty());
}

TEST_CASE("a tilted container: gravity at the tilt in its frame", "[sim][scenes]") {
  core::Scene s = flat_silo({"tilt=30"}, 1);
  core::apply_overrides(s, {"settle_time=0"});
  sim::Silo h(core::compile(s));
  // One grain dropped from rest, away from the walls: after 0.1 s of free fall it has moved along gravity.
  h.place(0, {0.0, 1.2});
  const core::Vec2 p0 = h.positions()[0];
  h.advance_to(0.1);
  const core::Vec2 d = h.positions()[0] - p0;
  CHECK(std::atan2(-d.x, -d.y) * 180 / M_PI == Approx(30).margin(0.5));
  CHECK(core::length(d) == Approx(0.5 * 9.8 * 0.01).epsilon(0.05));
}

TEST_CASE(
    "the shipped flat silo tilted up to 60 degrees fills as it stands and measures its surface along gravity",
    "[sim][scenes][heavy]") {
  // The shipped scene at its own height (3.5 m): dropped into the standing tilted container, the grains used
  // to rest in a chain up its lower wall above the top ("still above the top of the container" at any
  // settle time until the silo was twice as tall).
  for (double tilt : {30.0, -45.0, 60.0}) {
    CAPTURE(tilt);
    core::Scene s = core::load_scene(std::string(SILOSCOPE_SOURCE_DIR) + "/assets/scenes/silo-obstacle.toml");
    core::apply_overrides(s, {"tilt=" + core::format_shortest(tilt), "obstacle=\"none\""});
    sim::Silo h(core::compile(s));
    const auto& g = h.geometry();
    const core::Vec2 up{std::sin(tilt * M_PI / 180), std::cos(tilt * M_PI / 180)};
    double highest = -1e9, highest_y = -1e9;
    for (auto p : h.positions()) {
      CHECK(g.contains(p, 0.0));
      highest = std::max(highest, core::dot(p, up));
      highest_y = std::max(highest_y, p.y);
    }
    // The free surface is measured along gravity: the packing's highest grain lies within a diameter of it,
    // where the container's own y would put the column's top a metre or more off at 60 degrees.
    const double top = h.column_top();
    CHECK(std::abs(highest - top) < 2 * g.grain_diameter);
    CHECK(h.up_height(h.positions()[0]) == Approx(core::dot(h.positions()[0], up)));
    // Discharging with re-injection: exits come back onto the free surface (no grain in flight), and none
    // leaves the container.
    h.advance_to(6.0);
    CHECK(h.events().exits.size() > 20);
    CHECK(h.airborne().samples > 0);
    CHECK(h.airborne().mean() < 0.002);
    for (auto p : h.positions()) CHECK((p.y < 0 || g.contains(p, 0.0)));
  }
}

TEST_CASE("the drain protocol: exits leave for good, and a drain ends emptied or jammed", "[sim][scenes]") {
  auto drain = [](double aperture) {
    core::Scene s = core::load_scene(std::string(SILOSCOPE_SOURCE_DIR) + "/assets/scenes/hopper-drain.toml");
    core::apply_overrides(
        s, {"species.disks.count=120", "silo_height=1.5", "aperture=" + core::format_shortest(aperture)});
    return s;
  };
  {
    // A wide outlet: every grain leaves once, and none comes back.
    sim::Silo h(core::compile(drain(0.6)));
    h.advance_to(20.0);
    CHECK(h.drain().outcome == "emptied");
    CHECK(h.drain().remaining == 0);
    CHECK(h.drain().end_s > 0);
    CHECK(h.drain().end_s < 20);
    std::vector<int> ids;
    for (const auto& e : h.events().exits) ids.push_back(e.id);
    std::sort(ids.begin(), ids.end());
    CHECK(ids.size() == 120);
    CHECK(std::unique(ids.begin(), ids.end()) == ids.end());
  }
  {
    // An outlet of two grains: a clog that lasts clog_timeout is the jam; its arch stays and nothing moves.
    sim::Silo h(core::compile(drain(0.2)));
    h.advance_to(5.0);
    REQUIRE(h.drain().outcome == "jammed");
    CHECK(h.drain().remaining + static_cast<int>(h.events().exits.size()) == 120);
    CHECK(h.events().arches.empty());  // the rule removed nothing
    const auto before = h.positions();
    h.advance_to(6.0);
    const auto after = h.positions();
    for (size_t i = 0; i < before.size(); ++i) CHECK(core::length(after[i] - before[i]) == 0.0);
    CHECK(h.time() == Approx(6.0).margin(1e-3));
  }
}

TEST_CASE("size distributions: radii within their law, reproducible by seed", "[sim][scenes]") {
  core::Scene s = core::parse_scene(
      "[[species]]\nname = \"u\"\ncount = 100\nsize = \"uniform\"\nradius_min = 0.02\nradius_max = 0.03\n"
      "[[species]]\nname = \"l\"\ncount = 150\nsize = \"lognormal\"\nradius = 0.04\nspread = 0.2\n",
      "dist");
  core::apply_overrides(s, {"settle_time=0"});
  sim::Silo a(core::compile(s)), b(core::compile(s));
  const auto r = a.radii();
  CHECK(r == b.radii());
  const core::Setup& st = a.setup();
  double mean_l = 0;
  for (int i = 0; i < 250; ++i) {
    const auto& d = st.species[static_cast<size_t>(st.species_of(i))];
    CHECK(r[static_cast<size_t>(i)] >= d.radius_min);
    CHECK(r[static_cast<size_t>(i)] <= d.radius_max);
    if (i >= 100) mean_l += r[static_cast<size_t>(i)] / 150;
  }
  CHECK(mean_l == Approx(0.04).epsilon(0.05));  // the lognormal's mean, within sampling
  CHECK(*std::max_element(r.begin(), r.begin() + 100) > 0.029);
  CHECK(*std::min_element(r.begin(), r.begin() + 100) < 0.021);
}

TEST_CASE("dipoles: the cell list gives the all-pairs forces, moments multiply pair by pair",
          "[sim][dipole]") {
  std::vector<core::Vec2> pos;
  std::vector<double> mu;
  core::Rng rng(7);
  for (int i = 0; i < 300; ++i) {
    pos.push_back({rng.uniform(-0.5, 0.5), rng.uniform(0.0, 3.0)});
    mu.push_back(i % 3 == 0 ? 0.0 : rng.uniform(0.1, 1.0));
  }
  std::vector<core::Vec2> all, cells;
  sim::DipoleCells scratch;
  const long pairs_all = sim::dipole_forces(pos, mu, 0.0, all, scratch);
  CHECK(pairs_all == 300 * 299 / 2);
  // A cutoff beyond every distance: the same forces, summed in another order.
  CHECK(sim::dipole_forces(pos, mu, 10.0, cells, scratch) == pairs_all);
  for (size_t i = 0; i < pos.size(); ++i) {
    CHECK(cells[i].x == Approx(all[i].x).epsilon(1e-12).margin(1e-18));
    CHECK(cells[i].y == Approx(all[i].y).epsilon(1e-12).margin(1e-18));
  }
  // A short cutoff: exactly the pairs within it.
  long within = 0;
  for (size_t i = 0; i < pos.size(); ++i)
    for (size_t j = i + 1; j < pos.size(); ++j) within += core::length(pos[i] - pos[j]) <= 0.2;
  CHECK(sim::dipole_forces(pos, mu, 0.2, cells, scratch) == within);
  // Two grains: F = 3e-7 mu_1 mu_2 / r^4.
  std::vector<core::Vec2> two = {{0, 0}, {0.1, 0}}, f;
  sim::dipole_forces(two, {0.5, 2.0}, 0.0, f, scratch);
  CHECK(-f[0].x == Approx(3e-7 * 0.5 * 2.0 / 1e-4));
}

TEST_CASE("the clog rule off: a clog lasts until the run ends, and says so", "[sim][scenes]") {
  // A narrow outlet without a drive clogs for good.
  sim::Silo h(core::compile(flat_silo({"aperture=0.18", "clog_timeout=0", "clog_min_gap=0.5"})));
  h.advance_to(15.0);
  h.finish();
  REQUIRE_FALSE(h.events().clogs.empty());
  CHECK(h.events().clogs.back().ended_by == core::ClogEnd::RunEnd);
  CHECK(h.events().arches.empty());
  for (const auto& c : h.events().clogs) CHECK(c.ended_by != core::ClogEnd::Rule);
}
