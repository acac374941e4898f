#include "analysis/stats.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/rng.h"

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

namespace analysis {

std::vector<SurvivalStep> kaplan_meier(std::vector<Duration> samples) {
  // Events before censorings at equal times (the usual convention: a sample censored at t was at risk at t).
  std::sort(samples.begin(), samples.end(), [](const Duration& a, const Duration& b) {
    return a.t < b.t || (a.t == b.t && a.observed && !b.observed);
  });
  std::vector<SurvivalStep> out;
  double s = 1.0, greenwood = 0.0;
  long at_risk = static_cast<long>(samples.size());
  out.push_back({0.0, 1.0, 1.0, 1.0, at_risk});
  for (size_t i = 0; i < samples.size();) {
    const double t = samples[i].t;
    long events = 0, removed = 0;
    for (; i < samples.size() && samples[i].t == t; ++i) {
      events += samples[i].observed;
      ++removed;
    }
    if (events > 0) {
      s *= 1.0 - static_cast<double>(events) / static_cast<double>(at_risk);
      if (at_risk > events)
        greenwood += static_cast<double>(events) / (static_cast<double>(at_risk) * (at_risk - events));
      // Greenwood's variance on the log-log scale keeps the band within [0, 1].
      double lo = s, hi = s;
      if (s > 0 && s < 1) {
        const double se = std::sqrt(greenwood) / std::abs(std::log(s));
        lo = std::pow(s, std::exp(1.959963984540054 * se));
        hi = std::pow(s, std::exp(-1.959963984540054 * se));
      }
      out.push_back({t, s, lo, hi, at_risk});
    }
    at_risk -= removed;
  }
  return out;
}

double survival_at(const std::vector<SurvivalStep>& km, double t) {
  double s = 1.0;
  for (const auto& step : km)
    if (step.t <= t) s = step.s;
  return s;
}

}  // namespace analysis

namespace analysis {

double ks_distance(std::vector<double> a, std::vector<double> b) {
  if (a.empty() || b.empty()) return NAN;
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  size_t i = 0, j = 0;
  double d = 0;
  while (i < a.size() && j < b.size()) {
    const double x = std::min(a[i], b[j]);
    while (i < a.size() && a[i] <= x) ++i;
    while (j < b.size() && b[j] <= x) ++j;
    d = std::max(d, std::abs(static_cast<double>(i) / a.size() - static_cast<double>(j) / b.size()));
  }
  return d;
}

double ks_critical_95(size_t n, size_t m) {
  if (n == 0 || m == 0) return NAN;
  return 1.358 * std::sqrt(static_cast<double>(n + m) / (static_cast<double>(n) * static_cast<double>(m)));
}

}  // namespace analysis

namespace analysis {

double normal_cdf(double z) {
  return 0.5 * std::erfc(-z / std::sqrt(2.0));
}

double normal_quantile(double p) {
  if (!(p > 0 && p < 1)) throw std::invalid_argument("normal_quantile: p must lie in (0, 1)");
  double lo = -40, hi = 40;  // Phi is monotone: bisect to the last bit
  for (int k = 0; k < 200 && hi - lo > 1e-15 * std::max(1.0, std::abs(lo)); ++k) {
    const double mid = 0.5 * (lo + hi);
    (normal_cdf(mid) < p ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

double two_sided_p(double difference, double half95) {
  if (!std::isfinite(difference) || !(half95 >= 0) || std::isinf(half95)) return 1.0;
  if (half95 == 0) return difference != 0 ? 0.0 : 1.0;
  static const double z95 = normal_quantile(0.975);
  return std::erfc(std::abs(difference) / (half95 / z95) /
                   std::sqrt(2.0));  // 2 (1 - Phi(z)), without cancellation
}

std::vector<bool> holm(const std::vector<double>& p, double alpha) {
  std::vector<size_t> order(p.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return p[a] < p[b]; });
  std::vector<bool> significant(p.size(), false);
  for (size_t rank = 0; rank < order.size(); ++rank) {
    if (!(p[order[rank]] <= alpha / static_cast<double>(order.size() - rank))) break;
    significant[order[rank]] = true;
  }
  return significant;
}

double quantile(std::vector<double> samples, double q) {
  samples.erase(std::remove_if(samples.begin(), samples.end(), [](double v) { return std::isnan(v); }),
                samples.end());
  if (samples.empty()) return NAN;
  std::sort(samples.begin(), samples.end());
  const double at = q * static_cast<double>(samples.size() - 1);
  const size_t i = static_cast<size_t>(std::floor(at));
  if (i + 1 >= samples.size()) return samples.back();
  return samples[i] + (at - static_cast<double>(i)) * (samples[i + 1] - samples[i]);
}

std::vector<double> bootstrap(const std::vector<size_t>& sizes, int rounds, std::uint64_t seed,
                              const std::function<double(const std::vector<std::vector<size_t>>&)>& stat) {
  core::Rng rng(seed, 0x626f6f74);  // "boot"
  std::vector<std::vector<size_t>> drawn(sizes.size());
  for (size_t g = 0; g < sizes.size(); ++g) drawn[g].resize(sizes[g]);
  std::vector<double> out;
  out.reserve(static_cast<size_t>(std::max(0, rounds)));
  for (int b = 0; b < rounds; ++b) {
    for (size_t g = 0; g < sizes.size(); ++g)
      for (auto& i : drawn[g])
        i = std::min(sizes[g] - 1, static_cast<size_t>(rng.uniform() * static_cast<double>(sizes[g])));
    out.push_back(stat(drawn));
  }
  return out;
}

}  // namespace analysis
