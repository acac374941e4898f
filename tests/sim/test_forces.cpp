// Contact forces from the solver (issue 51, forces): normal and tangential, with the walls, and what they
// must satisfy at rest: the walls carry the column's weight, an arch's load balances what its walls give
// back, and friction stays in its cone.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <string>

#include "core/forces.h"
#include "core/physics.h"
#include "core/scene.h"
#include "helpers.h"
#include "io/contacts.h"
#include "sim/breaking.h"
#include "sim/silo.h"

namespace {

double norm(core::Vec2 v) {
  return std::hypot(v.x, v.y);
}

// A preset without kicks or the clog rule, stepped until a clog is arrested and half a second beyond: every
// grain at rest on the walls, the outlet held by an arch.
struct Resting {
  core::Scene scene;
  std::unique_ptr<sim::Silo> silo;
  explicit Resting(const std::string& preset) {
    scene = core::load_scene(std::string(SILOSCOPE_SOURCE_DIR) + "/assets/scenes/" + preset + ".toml");
    scene.kick_impulse_max = 0;
    scene.clog_timeout = 0;
    silo = std::make_unique<sim::Silo>(core::compile(scene));
    while (!(silo->clog().open && silo->clog().arrested) && silo->time() < 30) silo->step();
    silo->advance_to(silo->time() + 0.5);
  }
};

}  // namespace

TEST_CASE("contact forces at rest: the walls carry the weight, an arch's load meets its walls' reaction",
          "[sim][forces]") {
  for (const char* preset : {"paper", "pentagons", "silo-obstacle"}) {
    CAPTURE(preset);
    Resting r(preset);
    sim::Silo& h = *r.silo;
    REQUIRE(h.clog().open);
    REQUIRE(h.clog().arrested);
    const auto forces = h.contact_forces();
    const auto weights = h.weights();
    core::Vec2 weight;
    for (const auto& w : weights) weight = weight + w;
    const core::Vec2 down{weight.x / norm(weight), weight.y / norm(weight)};
    // The column's weight comes out at the walls (grain-grain forces cancel in pairs; dipoles too).
    const core::Vec2 walls = core::wall_reaction(forces);
    CHECK(norm(walls + weight) < 0.02 * norm(weight));
    // Friction inside its cone, compression only.
    double mu = r.scene.friction;
    for (const auto& sp : r.scene.species)
      if (sp.friction) mu = std::max(mu, *sp.friction);
    int outside = 0;
    for (const auto& c : forces) outside += c.fn < 0 || std::abs(c.ft) > mu * c.fn * 1.001 + 1e-9;
    CHECK(outside == 0);
    // The arch as a body: the load from the grains above against what the walls hold up, with its weight.
    const std::vector<int>& arch = h.clog().arch;
    REQUIRE(arch.size() >= 2);
    const core::ArchBalance b = core::arch_balance(forces, arch, weights);
    CAPTURE(b.load(down), b.held(down), norm(b.weight));
    CHECK(b.load(down) > 0);
    CHECK(b.held(down) > b.load(down));  // the walls carry the load and the arch's own weight
    CHECK(norm(b.residual()) < 0.02 * b.held(down));
    // Love-Weber: every grain that touches something is compressed; the pressure sums its contacts' work.
    std::vector<core::Vec2> centres;
    std::vector<double> areas;
    const core::Frame f = h.frame(false);
    for (const auto& p : f.particles) {
      centres.push_back({p.x, p.y});
      areas.push_back(core::kPi * p.radius * p.radius);
    }
    const auto stress = core::love_weber(forces, centres, areas);
    int loaded = 0, compressed = 0;
    for (const auto& s : stress) {
      if (s.xx == 0 && s.yy == 0) continue;
      ++loaded;
      compressed += s.pressure() > 0;
    }
    CHECK(loaded > static_cast<int>(stress.size()) / 2);
    CHECK(compressed == loaded);

    // What a recording keeps: the frame's contacts (grain pairs and walls) are the same forces, and through a
    // contacts file and back they still balance the weight and give each grain the same pressure.
    const core::Frame g = h.frame(true);
    auto key = [](const core::ContactForce& c) { return std::make_pair(c.a, c.b); };
    auto sorted = [&](std::vector<core::ContactForce> v) {
      std::sort(v.begin(), v.end(), [&](const auto& x, const auto& y) { return key(x) < key(y); });
      return v;
    };
    const auto want = sorted(forces), got = sorted(core::contact_forces(g));
    REQUIRE(got.size() == want.size());
    for (size_t k = 0; k < got.size(); ++k) {
      CHECK(key(got[k]) == key(want[k]));
      CHECK(std::abs(got[k].fn - want[k].fn) <= 1e-6 * (1 + want[k].fn));
      CHECK(std::abs(got[k].ft - want[k].ft) <= 1e-6 * (1 + std::abs(want[k].ft)));
      CHECK(norm(got[k].point - want[k].point) < 1e-6);
      CHECK(norm(got[k].normal - want[k].normal) < 1e-6);
    }
    const auto dir = test::temp_dir("forces_file");
    {
      io::ContactsWriter w(dir / "contacts.sscon", static_cast<std::uint32_t>(g.particles.size()));
      w.add(g.contacts, g.wall_contacts);
      w.close();
    }
    const io::Contacts back(dir / "contacts.sscon", static_cast<std::uint32_t>(g.particles.size()), 1);
    core::Frame read = f;
    read.contacts = back.frame(0), read.wall_contacts = back.walls(0);
    CHECK(norm(core::wall_reaction(core::contact_forces(read)) + weight) < 0.02 * norm(weight));
    const std::vector<double> p = core::pressures(read);
    REQUIRE(p.size() == stress.size());
    for (size_t i = 0; i < p.size(); ++i)
      CHECK(std::abs(p[i] - stress[i].pressure()) <= 1e-3 * (1 + std::abs(p[i])));
  }
}

TEST_CASE("the kick that breaks an arrested clog: bracketed by bisection, the same in every copy",
          "[sim][forces][slow]") {
  core::Scene s = core::load_scene(std::string(SILOSCOPE_SOURCE_DIR) + "/assets/scenes/paper.toml");
  s.seed = 3;
  s.duration = 4;  // its first clog is arrested from about 1 s on
  const core::Model model = core::compile(s);
  sim::Silo h(model);
  h.advance_to(s.duration);
  h.finish();
  int row = 0;
  for (size_t k = 0; k < h.events().clogs.size() && row == 0; ++k)
    if (h.events().clogs[k].arrested) row = static_cast<int>(k) + 1;
  REQUIRE(row > 0);
  const core::ClogEvent& c = h.events().clogs[static_cast<size_t>(row) - 1];
  sim::BreakOptions o;
  o.bisections = 4;
  const sim::BreakResult r = sim::break_clog(model, c, row, o);
  CAPTURE(r.outcome, r.t, r.dv_held, r.dv_broke, r.trials);
  REQUIRE(r.outcome == "broken");
  CHECK(r.t > c.start);
  CHECK(r.t < c.end + o.settle);
  CHECK(r.arch.size() >= 2);
  CHECK(r.load_N > 0);
  CHECK(r.held_N > r.load_N);
  CHECK(r.dv_held < r.dv_broke);
  // Doubling from dv_first, then four halvings of the bracket.
  CHECK(r.dv_broke - r.dv_held <= r.dv_broke / 16 + 1e-12);
  // A copy is the state bit for bit: the same test gives the same numbers.
  const sim::BreakResult again = sim::break_clog(model, c, row, o);
  CHECK(again.dv_broke == r.dv_broke);
  CHECK(again.arch == r.arch);
  // Kicks too weak for this arch: it holds, and says up to what.
  sim::BreakOptions weak = o;
  weak.dv_first = weak.dv_max = r.dv_held > 0 ? r.dv_held : r.dv_broke / 4;
  const sim::BreakResult held = sim::break_clog(model, c, row, weak);
  CHECK(held.outcome == "held");
  CHECK(held.dv_held == weak.dv_max);
  // The scene's kick law as velocity changes: every grain its own, the same draws at every amplitude.
  sim::BreakOptions law = o;
  law.random = true;
  const sim::BreakResult random = sim::break_clog(model, c, row, law);
  CHECK(random.arch == r.arch);
  CHECK((random.outcome == "broken" || random.outcome == "held"));
}

TEST_CASE("forces averaged over a frame: each contact's mean over the steps since the last frame",
          "[sim][forces]") {
  core::Scene scene =
      core::load_scene(std::string(SILOSCOPE_SOURCE_DIR) + "/assets/scenes/paper-vibrated.toml");
  sim::Silo h(core::compile(scene));
  h.advance_to(1.0);  // flowing, shaken: forces change from step to step
  h.average_forces(true);
  std::map<std::pair<int, int>, double> normal, tangent;
  const int steps = 25;
  for (int k = 0; k < steps; ++k) {
    h.step();
    for (const auto& c : h.contact_forces()) {
      normal[{c.a, c.b}] += c.fn / steps;
      tangent[{c.a, c.b}] += c.ft / steps;
    }
  }
  const core::Frame f = h.frame(true);
  REQUIRE(f.contacts.size() > 100);
  int differs = 0;  // from the last step's: the average is not the last step again
  const auto last = h.contact_forces();
  for (const auto* list : {&f.contacts, &f.wall_contacts})
    for (const auto& c : *list) {
      CAPTURE(c.a, c.b);
      CHECK(c.force == Approx(normal[{c.a, c.b}]).margin(1e-5));
      CHECK(c.ft == Approx(tangent[{c.a, c.b}]).margin(1e-5));
      for (const auto& l : last)
        if (l.a == c.a && l.b == c.b) differs += std::abs(l.fn - c.force) > 1e-3 * (1 + l.fn);
    }
  CHECK(differs > 10);
  // A new window: the next frame averages the next steps only.
  h.restart_force_average();
  h.step();
  const core::Frame g = h.frame(true);
  const auto now = h.contact_forces();
  for (const auto& c : g.contacts)
    for (const auto& l : now)
      if (l.a == c.a && l.b == c.b) CHECK(c.force == Approx(l.fn).margin(1e-5));
}
