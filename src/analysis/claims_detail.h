// Internal to src/analysis/claims*.cpp: a campaign's tables as the claims read them, and the comparison
// builders and verdict rules every claim shares (claims.h states the rules).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "analysis/claims.h"
#include "io/csv_table.h"

namespace analysis::claims::detail {

constexpr double kChi = 0.4;
constexpr int kRounds = 2000;  // bootstrap resamples: percentiles to about +-1% of the width
constexpr std::uint64_t kSeed = 0x636c61696d73;  // "claims": the same intervals on every run

// One point of the campaign (a row of points.csv) and its realizations (rows of realizations.csv).
struct Point {
  size_t row = 0;
  double r = 0, chi = 0, fr = 0;
  long n = 0;
  std::vector<size_t> reals;
};

class Data {
 public:
  // `column_dir`: where column.csv is read from instead of `dir` (empty: `dir`, when it holds one).
  explicit Data(const std::string& dir, const std::string& column_dir = "");
  const std::vector<Point>& points() const { return pts_; }
  const io::CsvTable& table() const { return points_; }
  // The point at size ratio r and dipole strength F/W = fr, chi = 0.4 (null if the grid lacks it).
  const Point* at(double r, double fr, double chi = kChi) const {
    for (const auto& p : pts_)
      if (std::abs(p.chi - chi) < 1e-9 && std::abs(p.r - r) < 1e-9 && std::abs(p.fr - fr) < 1e-6) return &p;
    return nullptr;
  }
  const Point* pure() const {
    for (const auto& p : pts_)
      if (p.chi == 0) return &p;
    return nullptr;
  }
  Est est(const Point* p, const std::string& col) const {
    if (!p || !points_.has(col)) return Est::none();
    Est e{points_.num(p->row, col), std::numeric_limits<double>::infinity(), p->n};
    if (points_.has(col + "_ci95") && p->n >= 2) {
      const double h = points_.num(p->row, col + "_ci95");
      if (std::isfinite(h)) e.h = h;
    }
    return e;
  }
  double value(const Point* p, const std::string& col) const {
    return p && points_.has(col) ? points_.num(p->row, col) : NAN;
  }
  // The realizations' values of `col` (empty without realizations.csv or the column).
  std::vector<double> samples(const Point* p, const std::string& col) const {
    std::vector<double> out;
    if (!p || !reals_ || !reals_->has(col)) return out;
    for (size_t i : p->reals) out.push_back(reals_->num(i, col));
    return out;
  }
  bool has_samples(const std::string& col) const { return reals_ && reals_->has(col); }
  // Where `species` sits in the column at `p` (column.csv, written by analyze from the runs' trajectories):
  // its mean height rank over the realizations measured; Est::none() without the table or the row.
  Est column_rank(const Point* p, const std::string& species) const;
  bool has_column() const { return column_.has_value(); }
  // Sizes of the non-magnetic chi = 0.4 grid, ascending; the dipole strengths, ascending.
  std::vector<double> sizes() const {
    std::vector<double> out;
    for (const auto& p : pts_)
      if (std::abs(p.chi - kChi) < 1e-9 && std::abs(p.fr) < 1e-9) out.push_back(p.r);
    std::sort(out.begin(), out.end());
    return out;
  }
  std::vector<double> strengths() const {
    std::vector<double> out;
    for (const auto& p : pts_)
      if (std::abs(p.chi - kChi) < 1e-9 &&
          std::none_of(out.begin(), out.end(), [&](double f) { return std::abs(f - p.fr) < 1e-6; }))
        out.push_back(p.fr);
    std::sort(out.begin(), out.end());
    return out;
  }

 private:
  static std::string key(const io::CsvTable& t, size_t i) {
    return t.text(i, "size_ratio") + "," + t.text(i, "chi") + "," + t.text(i, "mu") + "," +
           t.text(i, "kick_impulse_max");
  }
  io::CsvTable points_;
  std::optional<io::CsvTable> reals_;
  std::optional<io::CsvTable> column_;
  std::vector<Point> pts_;
};

// The fraction of clogs broken by vibration at `pts` (clogs_vibration / (vibration + rule)), with the counts;
// NaN without the columns.
struct Broken {
  double fraction = NAN;
  long broken = 0, decided = 0;
};
double mean_of(const std::vector<double>& v, const std::vector<size_t>& idx);
std::vector<size_t> all_of(size_t n);
// a against b: the difference, its combined half-width and p (Holm's sign is set later, by resolve).
Comparison compare(const std::string& label, Est a, Est b, int expected);
// The mean difference over `per_r` (each r of equal weight), its half-width from theirs.
Comparison pooled(const std::string& label, const std::vector<Comparison>& per_r, int expected);
// Holm over the claim's p-valued comparisons (parts pinned or not tested left out; an own_family part apart);
// equality comparisons by their Bonferroni-widened interval.
void conclude(Claim& claim);
// The verdict rules of claims.h: a range by its pool, every value each, equality within kEquivalence, a
// located quantity by its interval; the claim from its parts.
Verdict by_pool(const Part& part);
Verdict by_each(const Part& part);
Verdict by_equality(const Part& part);
Verdict by_location(const Located& l);
Verdict claim_verdict(const std::vector<Part>& parts);
// A part reproduced in sign whose words imply a size (Part::implied): kept only when the effect reaches it,
// "smaller than its words" when its whole interval falls short, not resolved between; says so in `why`.
void apply_size(Part& part);
// Long arches per minute are pinned when vibration breaks fewer than kPinnedVibration of the clogs at `pts`:
// marks `part` so and says why (false: not pinned, or the table lacks the counts).
Broken broken_by_vibration(const Data& d, const std::vector<const Point*>& pts);
// `composition`: the part is about what long-lasting arches are made of (not how many there are): with every
// clog lasting to the rule, "long-lasting" arches are all arches, and the part says that instead.
bool pin_long_arches(const Data& d, const std::vector<const Point*>& pts, Part& part,
                     bool composition = false);
// Q~/Q_p at (r, F/W) against 1; a column at F/W against F/W = 0, same r.
Comparison ratio_vs_one(const Data& d, double r, double fr, int expected);
Comparison with_mu(const Data& d, double r, double fr, const std::string& col, const std::string& name,
                   int expected);
// Numbers in text: 3 significant digits, a list of them, an estimate with its interval and n.
std::string g3(double v);
std::string list(const std::vector<double>& v, const std::string& sep = ", ");
std::string text(const Est& e);

// A part over the sizes in (lo, hi): per-r comparisons and their pool.
// Q~/Q_p - 1 pooled over the non-magnetic points at `sizes`: the mean of Q~ over r (independent points) over
// the one Q_p they all share, so that Q_p's uncertainty counts once for the whole pool, not as if each r had
// its own (the mean of the per-r ratios' intervals taken as independent was too narrow).
Comparison pooled_ratio(const Data& d, const std::vector<double>& sizes, double fr, const std::string& label,
                        int expected);

template <class PerR>
Part range_part(const std::string& words, const std::vector<double>& sizes, double lo, double hi,
                const std::string& pool_label, int expected, PerR per_r,
                const std::function<Comparison(const std::vector<double>&)>& pool = {}) {
  Part part{words};
  std::vector<Comparison> rs;
  std::vector<double> used;
  for (double r : sizes)
    if (r > lo + 1e-9 && r < hi - 1e-9) {
      Comparison c = per_r(r);
      if (c.a.finite() && c.b.finite()) rs.push_back(c), used.push_back(r);
    }
  if (rs.empty()) {
    part.verdict = Verdict::NotTested;
    part.why = "the grid has no point in this range";
    return part;
  }
  part.comparisons = rs;
  if (rs.size() >= 2) {  // a pool of one r would only repeat it
    Comparison p = pool ? pool(used) : pooled(pool_label, rs, expected);
    p.note = "mean over r = " + list(used);
    part.comparisons.push_back(p);
  }
  return part;
}

}  // namespace analysis::claims::detail
