// A grain's species from its measured size (lab/size_species.h).
#include "lab/size_species.h"

#include <algorithm>
#include <cmath>

namespace lab {

namespace {

constexpr int kCells = 8192;

double gauss(double x, double sigma) {
  return std::exp(-0.5 * x * x / (sigma * sigma)) / (sigma * std::sqrt(2 * M_PI));
}

}  // namespace

SizeSpecies::SizeSpecies(const std::vector<core::SpeciesDef>& species, double log_scale, double sigma)
    : log_scale_(log_scale) {
  const size_t k = species.size();
  double lo = INFINITY, hi = -INFINITY, total = 0;
  for (const core::SpeciesDef& s : species) {
    lo = std::min(lo, std::log(s.radius_min));
    hi = std::max(hi, std::log(s.radius_max));
    total += s.count;
  }
  lo -= 8 * sigma + 0.1;
  hi += 8 * sigma + 0.1;
  lo_ = lo;
  step_ = (hi - lo) / kCells;
  auto at = [&](int i) { return lo_ + (i + 0.5) * step_; };
  const int half = static_cast<int>(std::ceil(8 * sigma / step_));
  std::vector<double> kernel(static_cast<size_t>(2 * half + 1));  // the measurement's Gaussian, per cell
  for (int d = -half; d <= half; ++d) kernel[static_cast<size_t>(d + half)] = gauss(d * step_, sigma) * step_;
  density_.assign(k, std::vector<double>(kCells, 0.0));
  mean_log_.assign(k, 0.0);
  for (size_t c = 0; c < k; ++c) {
    const core::SpeciesDef& s = species[c];
    const double share = total > 0 ? s.count / total : 1.0 / static_cast<double>(k);
    std::vector<double>& out = density_[c];
    if (s.law == core::SizeLaw::Fixed) {  // a point: its blur is the measurement's Gaussian
      mean_log_[c] = std::log(s.radius);
      for (int i = 0; i < kCells; ++i)
        out[static_cast<size_t>(i)] = share * gauss(at(i) - mean_log_[c], sigma);
      continue;
    }
    // The law's density of log r on the grid, normalised there.
    std::vector<double> raw(kCells, 0.0);
    const double a = std::log(s.radius_min), b = std::log(s.radius_max);
    const double s2 = std::log(1 + s.spread * s.spread), mu = std::log(s.radius) - 0.5 * s2;
    double sum = 0;
    for (int i = 0; i < kCells; ++i) {
      const double l = at(i);
      if (l < a || l > b) continue;
      raw[static_cast<size_t>(i)] =
          s.law == core::SizeLaw::Uniform ? std::exp(l) : gauss(l - mu, std::sqrt(s2));
      sum += raw[static_cast<size_t>(i)];
    }
    if (!(sum > 0)) {  // narrower than a cell
      raw[static_cast<size_t>(
          std::clamp(static_cast<int>((std::log(s.radius) - lo_) / step_), 0, kCells - 1))] = 1;
      sum = 1;
    }
    for (int i = 0; i < kCells; ++i) {
      raw[static_cast<size_t>(i)] /= sum * step_;
      mean_log_[c] += at(i) * raw[static_cast<size_t>(i)] * step_;
    }
    // Blurred by the measurement (a sum over the Gaussian's cells; none when it is narrower than a cell).
    for (int i = 0; i < kCells; ++i) {
      if (half == 0) {
        out[static_cast<size_t>(i)] = share * raw[static_cast<size_t>(i)];
        continue;
      }
      double v = 0;
      for (int j = std::max(0, i - half); j <= std::min(kCells - 1, i + half); ++j)
        v += raw[static_cast<size_t>(j)] * kernel[static_cast<size_t>(j - i + half)];
      out[static_cast<size_t>(i)] = share * v;
    }
  }
  // The most likely species per cell; where every density has vanished (between two sizes far apart), the
  // species whose mean log radius is nearest.
  best_.assign(kCells, 0);
  double kept = 0, all = 0;
  for (int i = 0; i < kCells; ++i) {
    int best = 0;
    for (size_t c = 1; c < k; ++c)
      if (density_[c][static_cast<size_t>(i)] > density_[static_cast<size_t>(best)][static_cast<size_t>(i)])
        best = static_cast<int>(c);
    if (!(density_[static_cast<size_t>(best)][static_cast<size_t>(i)] > 0))
      for (size_t c = 1; c < k; ++c)
        if (std::fabs(at(i) - mean_log_[c]) < std::fabs(at(i) - mean_log_[static_cast<size_t>(best)]))
          best = static_cast<int>(c);
    best_[static_cast<size_t>(i)] = best;
    kept += density_[static_cast<size_t>(best)][static_cast<size_t>(i)] * step_;
    for (size_t c = 0; c < k; ++c) all += density_[c][static_cast<size_t>(i)] * step_;
  }
  error_rate_ = all > 0 ? std::max(0.0, 1 - kept / all) : 0;
}

int SizeSpecies::species(double size) const {
  const double l = std::log(size) - log_scale_;
  const double cell = std::clamp(std::floor((l - lo_) / step_), 0.0, kCells - 1.0);  // NaN: not a size
  return std::isnan(cell) ? best_.front() : best_[static_cast<size_t>(cell)];
}

double SizeSpecies::mean_log_radius(int k) const {
  return mean_log_[static_cast<size_t>(k)];
}

namespace {

double median_of(std::vector<double>& v) {
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>((v.size() - 1) / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

}  // namespace

SizeSpecies fit_size_species(const std::vector<core::SpeciesDef>& species, std::vector<double> sizes,
                             double log_scale, double* spread) {
  const SizeSpecies nominal(species, log_scale, kAssumedSizeSpread);
  // Each size's log ratio to the radius of the species nearest it (in log size), kept when that species has
  // one fixed size.
  std::vector<double> ratio;
  for (double s : sizes) {
    if (!(s > 0)) continue;
    const double l = std::log(s);
    size_t best = 0;
    for (size_t k = 1; k < species.size(); ++k)
      if (std::fabs(l - log_scale - nominal.mean_log_radius(static_cast<int>(k))) <
          std::fabs(l - log_scale - nominal.mean_log_radius(static_cast<int>(best))))
        best = k;
    if (species[best].law == core::SizeLaw::Fixed) ratio.push_back(l - std::log(species[best].radius));
  }
  double scale = log_scale, sigma = kAssumedSizeSpread;
  if (ratio.size() >= 5) {
    scale = median_of(ratio);
    for (double& r : ratio) r = std::fabs(r - scale);
    sigma = std::max(kLeastSizeSpread, 1.4826 * median_of(ratio));
  }
  if (spread) *spread = sigma;
  return SizeSpecies(species, scale, sigma);
}

void TrackSizes::add(long track, double size, bool measured) {
  const size_t id = static_cast<size_t>(track);
  if (sizes_.size() <= id) sizes_.resize(id + 1);
  sizes_[id].push_back(static_cast<float>(measured ? size : -size));
}

std::vector<int> TrackSizes::species(const std::vector<core::SpeciesDef>& species, double log_scale,
                                     double* spread, double* error_rate) {
  std::vector<double> median(sizes_.size(), 0.0);
  for (size_t id = 0; id < sizes_.size(); ++id) {
    std::vector<float>& r = sizes_[id];
    // The measured sizes (positive), or the stand-ins where there are none.
    const auto measured = std::partition(r.begin(), r.end(), [](float v) { return v > 0; });
    if (measured != r.begin())
      r.erase(measured, r.end());
    else
      for (float& v : r) v = -v;
    if (r.empty()) continue;
    const auto mid = r.begin() + static_cast<std::ptrdiff_t>(r.size() / 2);
    std::nth_element(r.begin(), mid, r.end());
    median[id] = *mid;
  }
  sizes_.clear();
  sizes_.shrink_to_fit();
  const SizeSpecies likeliest = fit_size_species(species, median, log_scale, spread);
  if (error_rate) *error_rate = likeliest.error_rate();
  std::vector<int> out(median.size(), 0);
  for (size_t id = 0; id < median.size(); ++id)
    if (median[id] > 0) out[id] = likeliest.species(median[id]);
  return out;
}

}  // namespace lab
