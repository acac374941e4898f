// exp, log, sin and cos from +, -, *, / and exact operations (floor, frexp, ldexp) only, so that a value that
// feeds the dynamics (a drawn radius, a polygon's vertices) is the same on every machine: libm's
// transcendental functions differ between libraries in the last bit, and one bit is enough to change a
// chaotic run. Accurate to a few units in the last place; compiled without floating-point contraction (see
// CMakeLists.txt), so no fused multiply-add changes a bit either. Box2D's own rotations still use sinf/cosf:
// a run is one run on machines with the same Box2D build and libm (docs/scenes.md, "Determinism").
#pragma once

#include <cmath>

namespace core::portable {

inline double exp(double x) {
  if (!(x < 709.0)) return x != x ? x : HUGE_VAL;
  if (x < -745.0) return 0.0;
  constexpr double kLog2e = 1.4426950408889634, kLn2Hi = 6.93147180369123816490e-01,
                   kLn2Lo = 1.90821492927058770002e-10;
  const double k = std::floor(x * kLog2e + 0.5);
  const double r = (x - k * kLn2Hi) - k * kLn2Lo;  // |r| <= ln2 / 2; k * kLn2Hi is exact
  // Taylor series to r^16 / 16! by Horner: 1 + r/1 (1 + r/2 (1 + r/3 (...))).
  double p = 1.0;
  for (int n = 16; n >= 1; --n) p = 1.0 + r / n * p;
  return std::ldexp(p, static_cast<int>(k));
}

inline double log(double x) {
  if (!(x > 0)) return x == 0 ? -HUGE_VAL : NAN;
  if (x == HUGE_VAL) return x;
  int e = 0;
  double m = std::frexp(x, &e);  // x = m 2^e, m in [0.5, 1)
  if (m < 0.70710678118654752440) m *= 2, --e;
  // log m = 2 atanh(s), s = (m - 1) / (m + 1), |s| <= 0.1716: the series to s^25 is below 1e-19.
  const double s = (m - 1.0) / (m + 1.0), s2 = s * s;
  double p = 1.0 / 25.0;
  for (int n = 23; n >= 1; n -= 2) p = p * s2 + 1.0 / n;
  constexpr double kLn2Hi = 6.93147180369123816490e-01, kLn2Lo = 1.90821492927058770002e-10;
  return e * kLn2Hi + (2.0 * s * p + e * kLn2Lo);
}

// sin and cos of x together.
inline void sincos(double x, double& s, double& c) {
  constexpr double kTwoOverPi = 0.63661977236758134308;
  // pi/2 in three parts (Cody and Waite): k * part is exact for |k| < 2^20.
  constexpr double kP1 = 1.57079632673412561417e+00, kP2 = 6.07710050650619224932e-11,
                   kP3 = 2.02226624879595063154e-21;
  const double k = std::floor(x * kTwoOverPi + 0.5);
  const double r = ((x - k * kP1) - k * kP2) - k * kP3;  // |r| <= pi/4
  const double r2 = r * r;
  // Taylor series to r^19 (sin) and r^20 (cos), below 1e-18 at pi/4, by Horner:
  // sin r = r (1 - r^2/(2 3) (1 - r^2/(4 5) (...))), cos r = 1 - r^2/(1 2) (1 - r^2/(3 4) (...)).
  double ps = 1.0, pc = 1.0;
  for (int n = 19; n >= 3; n -= 2) ps = 1.0 - r2 / (n * (n - 1.0)) * ps;
  for (int n = 20; n >= 2; n -= 2) pc = 1.0 - r2 / (n * (n - 1.0)) * pc;
  const double sr = r * ps, cr = pc;
  const long q = static_cast<long>(k) & 3;
  switch (q) {
    case 0:
      s = sr, c = cr;
      break;
    case 1:
      s = cr, c = -sr;
      break;
    case 2:
      s = -sr, c = -cr;
      break;
    default:
      s = -cr, c = sr;
      break;
  }
}

}  // namespace core::portable
