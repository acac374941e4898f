#include <catch2/catch.hpp>

#include <box2d/box2d.h>

#include "core/physics.h"
#include "core/setup.h"
#include "sim/dipole.h"
#include "sim/silo.h"

TEST_CASE("dipole force: magnitude 3e-7 mu^2 / r^4, repulsive, along the line of centres", "[sim][dipole]") {
  const double mu = 1.3;
  std::vector<core::Vec2> pos = {{0.1, 0.2}, {0.1 + 0.03, 0.2 + 0.04}};  // 5 cm apart
  std::vector<core::Vec2> f;
  CHECK(sim::dipole_forces(pos, mu, 0.0, f) == 1);
  const double expected = 3e-7 * mu * mu / std::pow(0.05, 4);
  CHECK(core::length(f[0]) == Approx(expected).epsilon(1e-12));
  // Disk 0 is pushed away from disk 1: along (0 - 1) = (-0.03, -0.04) / 0.05.
  CHECK(f[0].x == Approx(-0.6 * expected));
  CHECK(f[0].y == Approx(-0.8 * expected));
  CHECK(f[1].x == Approx(-f[0].x));
  CHECK(f[1].y == Approx(-f[0].y));
  // The same from the mu0 form: 3 mu0 mu^2 / (4 pi r^4).
  const double mu0 = 4e-7 * M_PI;
  CHECK(expected == Approx(3 * mu0 * mu * mu / (4 * M_PI * std::pow(0.05, 4))));
}

TEST_CASE("dipole forces: none at mu = 0, pairs beyond the cutoff skipped, total force zero",
          "[sim][dipole]") {
  std::vector<core::Vec2> pos = {{0, 0}, {0.05, 0}, {0.5, 0.1}, {0.2, 0.3}};
  std::vector<core::Vec2> f;
  CHECK(sim::dipole_forces(pos, 0.0, 0.0, f) == 0);
  for (auto v : f) CHECK(core::length(v) == 0.0);
  CHECK(sim::dipole_forces(pos, 1.0, 0.0, f) == 6);
  core::Vec2 total{};
  for (auto v : f) total = total + v;
  CHECK(core::length(total) < 1e-12 * core::length(f[0]));
  CHECK(sim::dipole_forces(pos, 1.0, 0.1, f) == 1);  // only the 5 cm pair
  CHECK(core::length(f[2]) == 0.0);
}

TEST_CASE("in the hopper, only added disks feel the dipoles", "[sim][dipole]") {
  core::Scene s;
  core::apply_overrides(s, {"n_total=3", "chi=0.67", "mu=0.5", "gravity=0", "kick_impulse_max=0",
                            "settle_time=0", "size_ratio=0.4"});
  sim::Silo h(core::compile(s));
  REQUIRE(h.species()[0] == core::Species::Original);
  REQUIRE(h.species()[1] == core::Species::Added);
  REQUIRE(h.species()[2] == core::Species::Added);
  h.place(0, {-0.12, 3.0});  // original, 12 cm from added disk 1 (not touching)
  h.place(1, {0.0, 3.0});
  h.place(2, {0.06, 3.0});  // 6 cm right of disk 1
  h.step();
  core::Frame f = h.frame(false);
  const double m_a = core::mass_of(s.radius_added(), s.density);
  const double force = 3e-7 * 0.25 / std::pow(0.06, 4);
  // Symplectic Euler: velocity after one step is F dt / m.
  CHECK(f.particles[2].vx == Approx(force * s.dt / m_a).epsilon(1e-3));
  CHECK(f.particles[1].vx == Approx(-force * s.dt / m_a).epsilon(1e-3));
  CHECK(f.particles[0].vx == 0.0f);
  CHECK(f.particles[0].vy == 0.0f);
}

TEST_CASE("the dipole's safe time step refuses a stiff scene and names the largest safe dt",
          "[sim][dipole][health]") {
  core::Scene s;
  core::apply_overrides(s, {"size_ratio=0.2", "mu=2.0", "dt=0.002", "kick_period=0.1", "settle_time=0"});
  const double safe = core::dipole_safe_dt(core::resolve(s));
  REQUIRE(safe < s.dt);
  try {
    sim::Silo h(core::compile(s));
    FAIL("no error");
  } catch (const std::exception& e) {
    std::string msg = e.what();
    CHECK_THAT(msg, Catch::Matchers::Contains("largest safe time step"));
    CHECK_THAT(msg, Catch::Matchers::Contains("mu = 2"));
  }
}
