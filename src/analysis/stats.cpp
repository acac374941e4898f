#include "analysis/stats.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace analysis {

namespace {
// Continued fraction for the incomplete beta function (modified Lentz's method).
double beta_fraction(double a, double b, double x) {
  constexpr double kTiny = 1e-300, kEps = 1e-15;
  double c = 1.0, d = 1.0 - (a + b) * x / (a + 1.0);
  if (std::abs(d) < kTiny) d = kTiny;
  d = 1.0 / d;
  double h = d;
  for (int m = 1; m <= 10000; ++m) {
    const double m2 = 2.0 * m;
    double aa = m * (b - m) * x / ((a + m2 - 1.0) * (a + m2));
    d = 1.0 + aa * d;
    if (std::abs(d) < kTiny) d = kTiny;
    c = 1.0 + aa / c;
    if (std::abs(c) < kTiny) c = kTiny;
    d = 1.0 / d;
    h *= d * c;
    aa = -(a + m) * (a + b + m) * x / ((a + m2) * (a + m2 + 1.0));
    d = 1.0 + aa * d;
    if (std::abs(d) < kTiny) d = kTiny;
    c = 1.0 + aa / c;
    if (std::abs(c) < kTiny) c = kTiny;
    d = 1.0 / d;
    const double del = d * c;
    h *= del;
    if (std::abs(del - 1.0) < kEps) break;
  }
  return h;
}
}  // namespace

double incomplete_beta(double a, double b, double x) {
  if (x <= 0) return 0;
  if (x >= 1) return 1;
  const double ln_front =
      std::lgamma(a + b) - std::lgamma(a) - std::lgamma(b) + a * std::log(x) + b * std::log1p(-x);
  const double front = std::exp(ln_front);
  if (x < (a + 1.0) / (a + b + 2.0)) return front * beta_fraction(a, b, x) / a;
  return 1.0 - front * beta_fraction(b, a, 1.0 - x) / b;
}

double student_t_cdf(double t, double nu) {
  const double x = nu / (nu + t * t);
  const double tail = 0.5 * incomplete_beta(0.5 * nu, 0.5, x);
  return t >= 0 ? 1.0 - tail : tail;
}

double student_t_critical(double confidence, double nu) {
  if (!(confidence > 0 && confidence < 1) || !(nu > 0))
    throw std::invalid_argument("student_t_critical: bad arguments");
  const double target = 0.5 + 0.5 * confidence;
  double lo = 0, hi = 1;
  while (student_t_cdf(hi, nu) < target) hi *= 2;
  for (int i = 0; i < 200 && hi - lo > 1e-13 * hi; ++i) {
    double mid = 0.5 * (lo + hi);
    (student_t_cdf(mid, nu) < target ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

Estimate estimate(const std::vector<double>& samples, double confidence) {
  Estimate e;
  double sum = 0;
  for (double v : samples)
    if (!std::isnan(v)) sum += v, ++e.n;
  if (e.n == 0) {
    e.mean = NAN;
    return e;
  }
  e.mean = sum / e.n;
  if (e.n < 2) {
    e.half_width = NAN;  // one sample: no interval (never a zero-width one)
    return e;
  }
  double ss = 0;
  for (double v : samples)
    if (!std::isnan(v)) ss += (v - e.mean) * (v - e.mean);
  e.sd = std::sqrt(ss / (e.n - 1));
  e.half_width = student_t_critical(confidence, e.n - 1) * e.sd / std::sqrt(static_cast<double>(e.n));
  return e;
}

}  // namespace analysis
