// Statistics across realizations: mean and Student-t confidence intervals.
#pragma once

#include <vector>

#include "core/stats.h"

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

}  // namespace analysis
