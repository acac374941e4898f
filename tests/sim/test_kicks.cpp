#include <catch2/catch.hpp>

#include "sim/kicks.h"

TEST_CASE("kick impulses: magnitude uniform in [0, Jmax], direction isotropic", "[sim][kicks]") {
  core::Rng rng(7, 2);
  const double jmax = 5e-5;
  const int n = 200000;
  double sum_mag = 0, sum_x = 0, sum_y = 0, sum_cos2 = 0, max_mag = 0;
  for (int i = 0; i < n; ++i) {
    core::Vec2 j = sim::draw_kick(rng, jmax);
    double m = core::length(j);
    sum_mag += m;
    max_mag = std::max(max_mag, m);
    sum_x += j.x;
    sum_y += j.y;
    if (m > 0) sum_cos2 += (j.x / m) * (j.x / m);
  }
  CHECK(max_mag <= jmax);
  CHECK(sum_mag / n == Approx(jmax / 2).epsilon(0.01));  // uniform magnitude: mean Jmax/2
  // Isotropy: mean vector zero (sd of the mean ~ Jmax/sqrt(6 n) ~ 4.6e-8), <cos^2> = 1/2.
  CHECK(std::abs(sum_x / n) < 2.5e-7);
  CHECK(std::abs(sum_y / n) < 2.5e-7);
  CHECK(sum_cos2 / n == Approx(0.5).epsilon(0.01));
}

TEST_CASE("a kick adds one shared impulse to every disk when global_kick is on", "[sim][kicks]") {
  core::Rng a(3, 2), b(3, 2);
  std::vector<core::Vec2> with, without;
  sim::draw_kicks(a, 1.0, true, 50, with);
  sim::draw_kicks(b, 1.0, false, 50, without);
  core::Vec2 shared = with[0] - without[0];
  CHECK(core::length(shared) > 0);
  for (int i = 0; i < 50; ++i) {
    CHECK((with[i] - without[i]).x == Approx(shared.x));
    CHECK((with[i] - without[i]).y == Approx(shared.y));
  }
}
