// The claims' shared machinery (claims_detail.h): reading a campaign's analysis, comparisons with their
// intervals and p-values, Holm's correction over a claim, and the rules that turn comparisons into verdicts.
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <map>

#include <toml++/toml.h>

#include "analysis/claims_detail.h"
#include "analysis/stats.h"
#include "core/error.h"
#include "core/format.h"

namespace analysis::claims {

Est Est::none() {
  return {NAN, std::numeric_limits<double>::infinity(), 0};
}
bool Est::finite() const {
  return std::isfinite(m);
}

const char* verdict_text(Verdict v) {
  switch (v) {
    case Verdict::Reproduced:
      return "reproduced";
    case Verdict::Contradicted:
      return "contradicted";
    case Verdict::NotResolved:
      return "not resolved";
    case Verdict::Partly:
      return "partly reproduced";
    case Verdict::Pinned:
      return "cannot be tested at this kick";
    case Verdict::NotTested:
      return "not tested";
    case Verdict::Smaller:
      return "resolved, smaller than its words";
  }
  return "?";
}

namespace detail {

std::string g3(double v) {
  return core::format_g(v, 3);
}

Data::Data(const std::string& dir, const std::string& column_dir)
    : points_(io::CsvTable::read(dir + "/points.csv", "points.csv of `siloscope analyze`")) {
  for (const char* key : {"size_ratio", "chi", "mu", "kick_impulse_max", "n_runs"})
    if (!points_.has(key))
      throw core::InputError(points_.path() + ": no column '" + key + "' (not a campaign's points.csv)");
  std::map<std::string, size_t> by_key;
  for (size_t i = 0; i < points_.rows(); ++i) {
    Point p;
    p.row = i;
    p.r = points_.num(i, "size_ratio");
    p.chi = points_.num(i, "chi");
    p.fr = points_.has("dipole_force_ratio") ? points_.num(i, "dipole_force_ratio") : 0.0;
    // Counts are whole and not negative, intervals not negative, the grid's keys finite: a table that says
    // otherwise was cut or edited, and its verdicts would be numbers with exit 0.
    auto line = [&] { return points_.path() + ":" + std::to_string(i + 2) + ": "; };
    for (const char* key :
         {"n_runs", "n_refused", "clogs", "clogs_vibration", "clogs_rule", "clogs_spontaneous"}) {
      if (!points_.has(key)) continue;
      const double v = points_.num(i, key);
      if (!(v >= 0) || v != std::floor(v) || (std::string(key) == "n_runs" && v < 1))
        throw core::InputError(
            line() + key + " = " + points_.text(i, key) + " is not " +
            (std::string(key) == "n_runs" ? "a whole number from 1" : "a whole number from 0"));
    }
    // Rates, sizes, shares and their intervals: finite and >= 0, or NaN (not measured at this point), as the
    // Python package's read_campaign checks them.
    for (const char* key : {"q_per_s", "q_tilde_per_s", "q_p_per_s", "long_arches_per_min",
                            "added_per_long_arch", "avalanche_mean", "q_tilde_over_qp", "chi_eff",
                            "fraction_broken_by_vibration", "airborne_fraction"})
      for (const std::string& col : {std::string(key), std::string(key) + "_ci95"}) {
        if (!points_.has(col)) continue;
        const double v = points_.num(i, col);
        if (!std::isnan(v) && !(std::isfinite(v) && v >= 0))
          throw core::InputError(line() + col + " = " + points_.text(i, col) +
                                 " is not a finite number >= 0");
      }
    for (const char* key : {"size_ratio", "chi", "mu"})
      if (!std::isfinite(points_.num(i, key)) || points_.num(i, key) < 0)
        throw core::InputError(line() + key + " = " + points_.text(i, key) + " is not a finite number >= 0");
    p.n = static_cast<long>(points_.num(i, "n_runs"));
    by_key[key(points_, i)] = pts_.size();
    pts_.push_back(p);
  }
  // analyze writes how many points it wrote: a points.csv cut at a line's end (or a row deleted) keeps its
  // form, and only this count tells (the Python package's read_campaign checks the same).
  const std::string mpath = dir + "/metadata.toml";
  if (std::filesystem::exists(mpath)) {
    try {
      const toml::table meta = toml::parse_file(mpath);
      if (auto declared = meta["run"]["points"].value<std::int64_t>();
          declared && *declared != static_cast<std::int64_t>(points_.rows()))
        throw core::InputError(points_.path() + " has " + std::to_string(points_.rows()) +
                               " points where its metadata.toml says analyze wrote " +
                               std::to_string(*declared) + " (cut, or rows removed by hand?)");
    } catch (const toml::parse_error&) {
      throw core::InputError(mpath + ": malformed TOML (truncated or edited by hand?)");
    }
  }
  const std::string rpath = dir + "/realizations.csv";
  if (std::filesystem::exists(rpath)) {
    reals_.emplace(io::CsvTable::read(rpath, "realizations.csv of `siloscope analyze`"));
    for (size_t i = 0; i < reals_->rows(); ++i) {
      auto it = by_key.find(key(*reals_, i));
      if (it != by_key.end()) pts_[it->second].reals.push_back(i);
    }
  }
  const std::string cpath = (column_dir.empty() ? dir : column_dir) + "/column.csv";
  if (!column_dir.empty() && !std::filesystem::exists(cpath))
    throw core::InputError("claims: --column " + column_dir +
                           " holds no column.csv (analyze writes it from runs that kept a trajectory)");
  if (std::filesystem::exists(cpath)) {
    column_.emplace(io::CsvTable::read(cpath, "column.csv of `siloscope analyze`"));
    for (const char* col : {"species", "n_runs_measured", "column_rank", "column_rank_ci95"})
      if (!column_->has(col))
        throw core::InputError(cpath + ": no column '" + col + "' (written by siloscope analyze?)");
    for (size_t i = 0; i < column_->rows(); ++i) {
      const double rank = column_->num(i, "column_rank"), n = column_->num(i, "n_runs_measured");
      const std::string at = cpath + ":" + std::to_string(i + 2) + ": ";
      if (!(n >= 0) || n != std::floor(n))
        throw core::InputError(at + "n_runs_measured = " + column_->text(i, "n_runs_measured") +
                               " is not a whole number from 0");
      if (!std::isnan(rank) && !(rank >= 0 && rank <= 1))
        throw core::InputError(at + "column_rank = " + column_->text(i, "column_rank") +
                               " is outside [0, 1] (a height rank)");
    }
  }
}

Est Data::column_rank(const Point* p, const std::string& species) const {
  if (!p || !column_) return Est::none();
  const std::string k = key(points_, p->row);
  for (size_t i = 0; i < column_->rows(); ++i) {
    if (column_->text(i, "species") != species || key(*column_, i) != k) continue;
    const long n = static_cast<long>(column_->num(i, "n_runs_measured"));
    const double m = column_->num(i, "column_rank"), h = column_->num(i, "column_rank_ci95");
    if (n < 1 || !std::isfinite(m)) return Est::none();
    return {m, n >= 2 && std::isfinite(h) ? h : std::numeric_limits<double>::infinity(), n};
  }
  return Est::none();
}

double mean_of(const std::vector<double>& v, const std::vector<size_t>& idx) {
  double s = 0;
  long n = 0;
  for (size_t i : idx)
    if (std::isfinite(v[i])) s += v[i], ++n;
  return n ? s / static_cast<double>(n) : NAN;
}
std::vector<size_t> all_of(size_t n) {
  std::vector<size_t> idx(n);
  for (size_t i = 0; i < n; ++i) idx[i] = i;
  return idx;
}

Comparison compare(const std::string& label, Est a, Est b, int expected) {
  Comparison c{label, a, b, expected};
  c.diff = a.m - b.m;
  c.half = std::hypot(a.h, b.h);
  if (!a.finite() || !b.finite() || std::isnan(c.half)) c.half = std::numeric_limits<double>::infinity();
  c.p = two_sided_p(c.diff, c.half);
  return c;
}

// The mean difference over `per_r` (each of equal weight), its half-width from theirs.
Comparison pooled(const std::string& label, const std::vector<Comparison>& per_r, int expected) {
  Comparison c{label, Est::none(), Est::none(), expected};
  c.pooled = true;
  double d = 0, h2 = 0;
  long n = std::numeric_limits<long>::max();
  for (const auto& x : per_r)
    d += x.diff, h2 += x.half * x.half, n = std::min({n, x.a.n, x.b.n > 0 ? x.b.n : n});
  if (per_r.empty()) return c;
  const double m = static_cast<double>(per_r.size());
  c.diff = d / m;
  c.half = std::sqrt(h2) / m;
  c.a = {c.diff, c.half, n};
  c.b = Est::exact(0);
  c.p = two_sided_p(c.diff, c.half);
  return c;
}

Comparison pooled_ratio(const Data& d, const std::vector<double>& sizes, double fr, const std::string& label,
                        int expected) {
  Comparison c{label, Est::none(), Est::none(), expected};
  c.pooled = true;
  if (sizes.empty()) return c;
  double sum = 0, h2 = 0;
  long n = std::numeric_limits<long>::max();
  for (double r : sizes) {
    const Est q = d.est(d.at(r, fr), "q_tilde_per_s");
    sum += q.m, h2 += q.h * q.h, n = std::min(n, q.n);
  }
  const double m = static_cast<double>(sizes.size());
  Est qp = d.est(d.at(sizes.front(), fr), "q_p_per_s");
  if (!qp.finite()) qp = d.est(d.pure(), "q_per_s");  // an analysis without the column: the pure point itself
  const double mean = sum / m, half_mean = std::sqrt(h2) / m;
  const double ratio = mean / qp.m;
  c.diff = ratio - 1;
  c.half = std::abs(ratio) * std::hypot(half_mean / mean, qp.h / qp.m);
  if (!std::isfinite(c.half) || !(qp.m > 0)) c.half = std::numeric_limits<double>::infinity();
  c.a = {c.diff, c.half, n};
  c.b = Est::exact(0);
  c.p = two_sided_p(c.diff, c.half);
  return c;
}

// Holm over every p-valued comparison of the claim; equality comparisons (expected 0) are judged by
// interval, Bonferroni-widened over the part's equality comparisons.
void holm_signs(const std::vector<Comparison*>& fam) {
  std::vector<double> ps;
  for (auto* c : fam) ps.push_back(c->p);
  const auto sig = holm(ps);
  for (size_t i = 0; i < fam.size(); ++i) {
    fam[i]->k = static_cast<int>(fam.size());
    fam[i]->sign = sig[i] ? (fam[i]->diff > 0 ? 1 : -1) : 0;
  }
}
// Parts already pinned or not tested are left out: their measure says nothing about the claim.
void conclude(Claim& claim) {
  std::vector<Comparison*> fam;
  for (auto& part : claim.parts) {
    if (part.verdict == Verdict::Pinned || part.verdict == Verdict::NotTested) continue;
    std::vector<Comparison*> own;
    for (auto& c : part.comparisons)
      if (c.expected != 0) (part.own_family ? own : fam).push_back(&c);
    if (part.own_family) holm_signs(own);
  }
  holm_signs(fam);
  for (auto& part : claim.parts) {
    long eq = std::count_if(part.comparisons.begin(), part.comparisons.end(),
                            [](const Comparison& c) { return c.expected == 0; });
    for (auto& c : part.comparisons) {
      if (c.expected != 0) continue;
      c.k = static_cast<int>(eq);
      const double widen = normal_quantile(1 - 0.025 / static_cast<double>(eq)) / normal_quantile(0.975);
      const double h = c.half * widen;
      c.sign = std::isfinite(h) && std::abs(c.diff) > h ? (c.diff > 0 ? 1 : -1) : 0;
    }
  }
}

// "for r in a range": the pooled difference decides, no single r resolved against it (a range of one r: that
// r decides).
Verdict by_pool(const Part& part) {
  if (std::none_of(part.comparisons.begin(), part.comparisons.end(),
                   [](const Comparison& c) { return c.pooled; }))
    return by_each(part);
  Verdict v = Verdict::NotResolved;
  for (const auto& c : part.comparisons) {
    if (c.sign == -c.expected && c.sign != 0) return Verdict::Contradicted;
    if (c.pooled && c.sign == c.expected) v = Verdict::Reproduced;
  }
  return v;
}
// "at every value": each comparison resolved the claim's way.
Verdict by_each(const Part& part) {
  bool all = !part.comparisons.empty();
  for (const auto& c : part.comparisons) {
    if (c.sign == -c.expected && c.sign != 0) return Verdict::Contradicted;
    all = all && c.sign == c.expected;
  }
  return all ? Verdict::Reproduced : Verdict::NotResolved;
}
// Equality within kEquivalence: any resolved difference contradicts; agreement must be shown.
Verdict by_equality(const Part& part) {
  bool all = !part.comparisons.empty();
  for (const auto& c : part.comparisons) {
    if (c.sign != 0) return Verdict::Contradicted;
    const double widen = normal_quantile(1 - 0.025 / std::max(1, c.k)) / normal_quantile(0.975);
    all = all && std::isfinite(c.half) && std::abs(c.diff) + c.half * widen <= kEquivalence * std::abs(c.b.m);
  }
  return all ? Verdict::Reproduced : Verdict::NotResolved;
}
Verdict by_location(const Located& l) {
  if (!std::isfinite(l.lo) || !std::isfinite(l.hi) || l.missing > 0.05) return Verdict::NotResolved;
  // One allowance for rounding on both sides: 0.4 - 0.1 is 0.30000000000000004, and an interval ending at
  // 0.3 touches the paper's range; it is neither wholly inside nor wholly outside it.
  const double a = l.paper - l.tolerance, b = l.paper + l.tolerance;
  const double eps = kRounding * std::max({1.0, std::abs(a), std::abs(b)});
  if (l.lo >= a - eps && l.hi <= b + eps) return Verdict::Reproduced;
  if (l.hi < a - eps || l.lo > b + eps) return Verdict::Contradicted;
  return Verdict::NotResolved;
}

void apply_size(Part& part) {
  if (!part.implied || part.verdict != Verdict::Reproduced) return;
  const Implied& want = *part.implied;
  const bool any_pooled = std::any_of(part.comparisons.begin(), part.comparisons.end(),
                                      [](const Comparison& c) { return c.pooled; });
  bool reaches = true, short_of = false;
  std::string measured;
  for (const auto& c : part.comparisons) {
    if (any_pooled && !c.pooled) continue;
    const double scale = want.of == Implied::Of::A ? c.a.m : want.of == Implied::Of::B ? c.b.m : 1.0;
    const double e = c.expected * c.diff / scale, h = c.half / std::abs(scale);
    reaches = reaches && std::isfinite(e) && e >= want.size;
    short_of = short_of || !(e + h >= want.size);
    measured += (measured.empty() ? "" : "; ") + core::format_g(e, 2) + " [" + core::format_g(e - h, 2) +
                ", " + core::format_g(e + h, 2) + "]";
  }
  part.verdict = reaches ? Verdict::Reproduced : short_of ? Verdict::Smaller : Verdict::NotResolved;
  part.why += std::string(part.why.empty() ? "" : ". ") + "The words read as " + want.words +
              " (written down before the verdict); measured " + measured +
              (reaches    ? ": reached"
               : short_of ? ": short of it over the whole interval"
                          : ": reached only within the interval");
}

Verdict claim_verdict(const std::vector<Part>& parts) {
  int yes = 0, no = 0, pinned = 0;
  for (const auto& p : parts) {
    yes += p.verdict == Verdict::Reproduced;
    no += p.verdict == Verdict::Contradicted;
    pinned += p.verdict == Verdict::Pinned;
  }
  if (no) return Verdict::Contradicted;
  if (yes == static_cast<int>(parts.size())) return Verdict::Reproduced;
  if (yes) return Verdict::Partly;
  if (pinned == static_cast<int>(parts.size())) return Verdict::Pinned;
  return Verdict::NotResolved;
}

std::string list(const std::vector<double>& v, const std::string& sep) {
  std::string s;
  for (double x : v) s += (s.empty() ? "" : sep) + core::format_g(x, 3);
  return s;
}
std::string text(const Est& e) {
  if (!e.finite()) return "n/a";
  if (std::isinf(e.h)) return g3(e.m) + " (n = " + std::to_string(e.n) + ": no interval)";
  return g3(e.m) + " +- " + core::format_g(e.h, 2) + " (n = " + std::to_string(e.n) + ")";
}

Broken broken_by_vibration(const Data& d, const std::vector<const Point*>& pts) {
  Broken b;
  if (!d.table().has("clogs_vibration") || !d.table().has("clogs_rule")) return b;
  for (const Point* p : pts) {
    if (!p) continue;
    const double v = d.value(p, "clogs_vibration"), r = d.value(p, "clogs_rule");
    if (std::isfinite(v) && std::isfinite(r))
      b.broken += static_cast<long>(v), b.decided += static_cast<long>(v + r);
  }
  if (b.decided > 0) b.fraction = static_cast<double>(b.broken) / static_cast<double>(b.decided);
  return b;
}
// Long arches per minute are pinned by the 5 s rule when vibration breaks (almost) no clog.
bool pin_long_arches(const Data& d, const std::vector<const Point*>& pts, Part& part, bool composition) {
  const Broken b = broken_by_vibration(d, pts);
  if (!(b.fraction < kPinnedVibration)) return false;
  part.verdict = Verdict::Pinned;
  part.why = "vibration broke " + std::to_string(b.broken) + " of " + std::to_string(b.decided) + " clogs (" +
             core::format_g(100 * b.fraction, 2) +
             "%) at these points; every other clog lasted to the 5 s rule, ";
  part.why +=
      composition
          ? "so every arch is a long-lasting one: the added disks per long-lasting arch describe what "
            "arches are made of, not what makes them last, and the protocol, not the physics, decides "
            "(the change is shown above; no number of realizations changes that)"
          : "so the long arches per minute are 60 / (5 s + the mean flowing time between clogs): they "
            "measure the flow between clogs, not how long arches last, and no number of realizations "
            "changes that";
  return true;
}

// The ratio Q~/Q_p at (r, fr) against 1.
Comparison ratio_vs_one(const Data& d, double r, double fr, int expected) {
  std::string label = "Q~/Q_p at r = " + g3(r);
  if (fr != 0) label += ", F/W = " + g3(fr);
  return compare(label + " against 1", d.est(d.at(r, fr), "q_tilde_over_qp"), Est::exact(1), expected);
}
// Q~ (or another column) at F/W = fr against F/W = 0, same r.
Comparison with_mu(const Data& d, double r, double fr, const std::string& col, const std::string& name,
                   int expected) {
  return compare(name + " at r = " + g3(r) + ", F/W = " + g3(fr) + " against 0", d.est(d.at(r, fr), col),
                 d.est(d.at(r, 0), col), expected);
}

}  // namespace detail
}  // namespace analysis::claims
