#include <catch2/catch.hpp>

#include <cmath>

#include "core/portable_math.h"

TEST_CASE("portable exp, log and sincos agree with libm to a few units in the last place", "[core]") {
  for (double x = -30; x <= 30; x += 0.0137) {
    CHECK(core::portable::exp(x) == Approx(std::exp(x)).epsilon(4e-16));
    double s = 0, c = 0;
    core::portable::sincos(x, s, c);
    CHECK(s == Approx(std::sin(x)).margin(4e-16));
    CHECK(c == Approx(std::cos(x)).margin(4e-16));
  }
  for (double x = 1e-8; x < 1e8; x *= 1.173)
    CHECK(core::portable::log(x) == Approx(std::log(x)).epsilon(4e-16).margin(4e-16));
  CHECK(core::portable::log(1.0) == 0.0);
  CHECK(std::isinf(core::portable::log(0.0)));
  CHECK(core::portable::exp(-1000) == 0.0);
}
