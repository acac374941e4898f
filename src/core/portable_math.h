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

// Double-double arithmetic (a value as an unevaluated sum hi + lo, about 106 bits), from exact operations:
// Knuth's two-sum and Dekker's product with Veltkamp's split (no fused multiply-add: -ffp-contract=off).
struct DD {
  double hi, lo;
};
inline DD two_sum(double a, double b) {
  const double s = a + b, bb = s - a;
  return {s, (a - (s - bb)) + (b - bb)};
}
inline DD two_prod(double a, double b) {
  constexpr double kSplit = 134217729.0;  // 2^27 + 1
  const double p = a * b;
  const double ca = kSplit * a, ah = ca - (ca - a), al = a - ah;
  const double cb = kSplit * b, bh = cb - (cb - b), bl = b - bh;
  return {p, ((ah * bh - p) + ah * bl + al * bh) + al * bl};
}
inline DD dd_add(DD a, DD b) {
  DD s = two_sum(a.hi, b.hi);
  s.lo += a.lo + b.lo;
  return two_sum(s.hi, s.lo);
}
inline DD dd_mul(DD a, DD b) {
  DD p = two_prod(a.hi, b.hi);
  p.lo += a.hi * b.lo + a.lo * b.hi;
  return two_sum(p.hi, p.lo);
}
inline DD dd_div(DD a, double d) {  // a / d for an exact double d
  const double q = a.hi / d;
  const DD p = two_prod(q, d);
  const double e = ((a.hi - p.hi) - p.lo + a.lo) / d;
  return two_sum(q, e);
}
inline DD dd_neg(DD a) {
  return {-a.hi, -a.lo};
}

// sin and cos of x together, correctly rounded but for astronomically rare hard cases: reduced by pi/2 and
// summed in double-double, rounded once at the end: the same bits on every machine. glibc's sin and cos are
// not correctly rounded: they differ from these in the last bit for 0.28% of kick directions (55043 of 2e7),
// but the float impulses Box2D receives (magnitude times cosine, rounded to float) agreed in all 2e7.
inline void sincos(double x, double& s, double& c) {
  constexpr double kTwoOverPi = 0.63661977236758134308;
  // pi/2 in four parts (fdlibm's): P1-P3 of 33 bits each, so k * P1 is exact and x - k P1 too near a
  // multiple of pi/2; the products with P2-P4 are kept exactly as double-doubles.
  constexpr double kP1 = 1.57079632673412561417e+00, kP2 = 6.07710050630396597660e-11,
                   kP3 = 2.02226624871116645580e-21, kP4 = 8.47842766036889956997e-32;
  const double k = std::floor(x * kTwoOverPi + 0.5);
  // r = x - k pi/2 as a double-double.
  DD r{x - k * kP1, 0.0};
  r = dd_add(r, dd_neg(two_prod(k, kP2)));
  r = dd_add(r, dd_neg(two_prod(k, kP3)));
  r = dd_add(r, dd_neg(two_prod(k, kP4)));
  const DD r2 = dd_mul(r, r);
  // Horner in double-double: sin r = r (1 - r^2/(2 3) (1 - r^2/(4 5) (...))) to r^27, cos r = 1 - r^2/(1 2)
  // (1 - ...) to r^28: below 1e-33 at pi/4.
  DD ps{1.0, 0.0}, pc{1.0, 0.0};
  for (int n = 27; n >= 3; n -= 2) ps = dd_add(DD{1.0, 0.0}, dd_neg(dd_div(dd_mul(r2, ps), n * (n - 1.0))));
  for (int n = 28; n >= 2; n -= 2) pc = dd_add(DD{1.0, 0.0}, dd_neg(dd_div(dd_mul(r2, pc), n * (n - 1.0))));
  const DD sr = dd_mul(r, ps);
  const double sv = sr.hi + sr.lo, cv = pc.hi + pc.lo;
  switch (static_cast<long>(k) & 3) {
    case 0:
      s = sv, c = cv;
      break;
    case 1:
      s = cv, c = -sv;
      break;
    case 2:
      s = -sv, c = -cv;
      break;
    default:
      s = -cv, c = sv;
      break;
  }
}

}  // namespace core::portable
