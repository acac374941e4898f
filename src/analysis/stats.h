// Statistics across realizations: mean and Student-t confidence intervals.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "core/median.h"

namespace analysis {

using core::median;

// Regularized incomplete beta function I_x(a, b).
double incomplete_beta(double a, double b, double x);
// Cumulative distribution of Student's t with nu degrees of freedom.
double student_t_cdf(double t, double nu);
// The two-sided critical value t* with P(|T| <= t*) = confidence, for nu degrees of freedom.
double student_t_critical(double confidence, double nu);

struct Estimate {
  double mean = 0;
  double sd = 0;          // sample standard deviation (n - 1)
  double half_width = 0;  // half-width of the confidence interval of the mean; 0 for n < 2
  int n = 0;
};
// Mean and confidence interval (Student t, default 95%) of independent samples; NaN samples are skipped.
Estimate estimate(const std::vector<double>& samples, double confidence = 0.95);

// A duration that ended (observed) or was cut short (censored: by the clog rule or the run's end).
struct Duration {
  double t;
  bool observed;
};
// One step of a Kaplan-Meier estimate: S(t) = P(T > t) just after t, its 95% band (Greenwood, log-log), and
// the samples at risk just before t. The first step is (0, 1).
struct SurvivalStep {
  double t, s, lo, hi;
  long at_risk;
};
// The Kaplan-Meier estimate of the survival of `samples`: the survival function of durations when some were
// censored (the 5 s rule censors every clog at 5 s; the run's end censors the last one).
std::vector<SurvivalStep> kaplan_meier(std::vector<Duration> samples);
// The two-sample Kolmogorov-Smirnov distance: the largest gap between the empirical distributions of `a` and
// `b` (NaN when either is empty).
double ks_distance(std::vector<double> a, std::vector<double> b);
// The distance two samples of sizes n and m of one distribution exceed 5% of the time (asymptotic, 1.358
// sqrt((n + m) / (n m))).
double ks_critical_95(size_t n, size_t m);

// S(t) of an estimate (a step function, right-continuous).
double survival_at(const std::vector<SurvivalStep>& km, double t);

}  // namespace analysis

namespace analysis {

// The standard normal distribution: Phi(z) and its inverse (p in (0, 1)).
double normal_cdf(double z);
double normal_quantile(double p);
// Two-sided p-value of a difference whose 95% half-width is `half95` (normal approximation): 1 without an
// interval (half95 infinite or NaN), 0 for a non-zero difference known exactly.
double two_sided_p(double difference, double half95);
// Holm's step-down correction: which of a family's p-values are significant with a chance `alpha` of any
// false one in the family (the smallest p judged at alpha / k, the next at alpha / (k - 1), ..., stopping at
// the first that fails).
std::vector<bool> holm(const std::vector<double>& p, double alpha = 0.05);
// The q-quantile of `samples` (linear interpolation between order statistics; NaN samples skipped).
double quantile(std::vector<double> samples, double q);

// The bootstrap over realizations: `rounds` resamples, each drawing every group's members with replacement
// (groups: points of a campaign, each of `sizes[g]` realizations), passed to `stat` as, per group, the drawn
// member indices. A fixed seed makes the intervals reproducible. Returns the statistic of each round.
std::vector<double> bootstrap(const std::vector<size_t>& sizes, int rounds, std::uint64_t seed,
                              const std::function<double(const std::vector<std::vector<size_t>>&)>& stat);

}  // namespace analysis
