// Runs aggregated into points (analysis/aggregate.h): grouping by scene, each measurement's mean and 95%
// interval, pooled survival and avalanche tables, and the CSV they are written as. Over 400 lines because
// each table is a few lines of grouping and a few of writing, and they share the grouping.
#include "analysis/aggregate.h"
#include "core/format.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>

#include "analysis/tidy.h"
#include "core/error.h"
#include "core/physics.h"
#include "core/setup.h"

namespace analysis {

namespace {
const std::vector<std::string> kVaried = {"size_ratio", "chi", "mu", "kick_impulse_max"};

bool is_point_key(const std::string& k, const std::vector<std::string>& by) {
  for (const auto& v : kVaried)
    if (k == v) return true;
  for (const auto& v : by) {
    if (k == v) return true;
    // A species' count sets n_total (their sum): told apart by the count, the runs differ in n_total too.
    const std::string count = ".count";
    if (k == "n_total" && v.rfind("species.", 0) == 0 && v.size() > count.size() &&
        v.compare(v.size() - count.size(), count.size(), count) == 0)
      return true;
  }
  return k == "seed";
}

std::string point_label(const core::Scene& s, const std::vector<std::string>& by) {
  std::string out;
  for (const auto& k : kVaried) out += (out.empty() ? "" : ",") + core::field_text(s, *core::find_field(k));
  if (!by.empty()) {
    const auto values = core::scene_values(s);
    for (const auto& k : by) {
      auto it = values.find(k);
      out += "," + (it == values.end() ? std::string("-") : it->second);
    }
  }
  return out;
}

// The columns in front of every per-point row: the paper's keys, then the --by keys.
std::string key_header(const std::vector<Point>& points) {
  std::string s;
  for (const auto& k : kVaried) s += k + ",";
  if (!points.empty())
    for (const auto& [k, v] : points.front().extra) s += k + ",";
  return s;
}
std::string key_values(const Point& p) {
  std::string s;
  for (const auto& k : kVaried) s += core::field_text(p.scene, *core::find_field(k)) + ",";
  for (const auto& [k, v] : p.extra) {
    std::string t = v;
    if (t.size() >= 2 && t.front() == '"') t = t.substr(1, t.size() - 2);
    s += t + ",";
  }
  return s;
}

Estimate estimate_of(const std::vector<const Run*>& runs, double Measurements::*field) {
  std::vector<double> v;
  for (const Run* r : runs) v.push_back(r->m.*field);
  return estimate(v);
}
// A point's estimates over its realizations: the means and intervals, each species' flow, the clogs'
// survival, and Q~/Q_p against `qp` (the pure system's Q at the same kick; NaN mean: none).
void estimate_point(Point& p, const Estimate& qp) {
  p.airborne_fraction = estimate_of(p.runs, &Measurements::airborne_fraction);
  p.avalanche_mean = estimate_of(p.runs, &Measurements::avalanche_mean);
  // Each species' flow, and the survival of clogs (durations; the rule and the run's end censor them).
  const core::Setup& st = p.setup;
  for (size_t k = 0; k < st.species.size(); ++k) {
    SpeciesEstimate e;
    e.name = st.species[k].name;
    e.count = st.species[k].count;
    std::vector<double> q, frac, rank;
    for (const Run* r : p.runs) {
      const long n = k < r->m.exits_by_species.size() ? r->m.exits_by_species[k] : 0;
      q.push_back(r->m.duration > 0 ? n / r->m.duration : NAN);
      frac.push_back(r->m.exits > 0 ? static_cast<double>(n) / r->m.exits : NAN);
      if (k < r->m.column_rank.size() && std::isfinite(r->m.column_rank[k]))
        rank.push_back(r->m.column_rank[k]);
    }
    e.q = estimate(q);
    e.exit_fraction = estimate(frac);
    e.column_rank = estimate(rank);
    p.species.push_back(e);
  }
  std::vector<Duration> durations;
  for (const Run* r : p.runs)
    for (const auto& c : r->events.clogs) {
      if (c.start > r->m.duration) continue;
      const bool broke = c.ended_by == core::ClogEnd::Spontaneous || c.ended_by == core::ClogEnd::Vibration;
      durations.push_back({c.end - c.start, broke});
      p.clogs_run_end += c.ended_by == core::ClogEnd::RunEnd;
    }
  p.clog_survival = kaplan_meier(durations);
  for (const Run* r : p.runs) {
    p.clogs += r->m.clogs;
    p.clogs_vibration += r->m.clogs_vibration;
    p.clogs_rule += r->m.clogs_rule;
    p.clogs_spontaneous += r->m.clogs_spontaneous;
    p.ballistic_runs += r->m.ballistic;
  }
  p.q = estimate_of(p.runs, &Measurements::q);
  p.q_tilde = estimate_of(p.runs, &Measurements::q_tilde);
  p.chi_eff = estimate_of(p.runs, &Measurements::chi_eff);
  p.long_arches_per_min = estimate_of(p.runs, &Measurements::long_arches_per_minute);
  p.added_per_long_arch = estimate_of(p.runs, &Measurements::added_per_long_arch);
  p.fraction_broken_by_vibration = estimate_of(p.runs, &Measurements::fraction_broken_by_vibration);
  p.q_tilde_over_qp.mean = NAN;
  if (qp.n > 0 && qp.mean > 0) {  // a pure point exists (an empty Estimate has n = 0)
    // Ratio of two independent means; relative half-widths add in quadrature (first-order propagation).
    p.q_tilde_over_qp.mean = p.q_tilde.mean / qp.mean;
    // NaN when either side has a single realization: no interval.
    double rel =
        std::hypot(p.q_tilde.mean > 0 ? p.q_tilde.half_width / p.q_tilde.mean : 0, qp.half_width / qp.mean);
    p.q_tilde_over_qp.half_width = p.q_tilde_over_qp.mean * rel;
    p.q_tilde_over_qp.n = p.q_tilde.n;
  }
}

}  // namespace

std::vector<Point> aggregate(const std::vector<Run>& runs, const std::vector<Refused>& refused,
                             const std::vector<std::string>& by) {
  if (runs.empty()) throw core::InputError("analyze: no runs to aggregate");
  for (const auto& k : by) {
    const auto values = core::scene_values(runs.front().scene);
    if (!values.count(k))
      throw core::InputError("analyze: --by " + k + ": not a key of " + runs.front().source +
                             "'s scene (scene keys, or species.NAME.KEY)");
  }
  // Every key a campaign does not vary must agree with the first run's.
  const Run& first = runs.front();
  const auto first_values = core::scene_values(first.scene);
  // Every key that differs is named in the hint: a campaign gridding a species' count also changes n_total,
  // and a hint naming one key only led to the same error for the other.
  auto same_campaign = [&](const core::Scene& s, const std::string& source) {
    const auto values = core::scene_values(s);
    std::string first_diff, hint;
    for (const auto& [k, a] : first_values) {
      if (is_point_key(k, by)) continue;
      auto it = values.find(k);
      const std::string b = it == values.end() ? "(absent)" : it->second;
      if (a == b) continue;
      if (first_diff.empty())
        first_diff = first.source + " has " + k + " = " + a + " but " + source + " has " + k + " = " + b;
      hint += " --by " + k;
    }
    for (const auto& [k, b] : values)
      if (!first_values.count(k) && !is_point_key(k, by)) {
        if (first_diff.empty())
          first_diff = source + " has " + k + " = " + b + " but " + first.source + " has no such key";
        hint += " --by " + k;
      }
    if (!first_diff.empty())
      throw core::InputError("analyze: runs of different scenes are mixed: " + first_diff +
                             " (if your campaign varies them, analyze with" + hint + ")");
  };
  for (const Run& r : runs) same_campaign(r.scene, r.source);
  for (const Refused& r : refused) same_campaign(r.scene, r.source);
  std::map<std::string, Point> by_label;
  std::vector<std::string> order;
  std::map<std::string, std::set<std::uint64_t>> seeds;
  for (const Run& r : runs) {
    std::string label = point_label(r.scene, by);
    if (!by_label.count(label)) {
      order.push_back(label);
      by_label[label].scene = r.scene;
      by_label[label].setup = r.setup;
      const auto values = core::scene_values(r.scene);
      for (const auto& k : by) by_label[label].extra.push_back({k, values.at(k)});
    }
    if (!seeds[label].insert(r.scene.seed).second)
      throw core::InputError("analyze: seed " + std::to_string(r.scene.seed) +
                             " appears twice at the point (" + label + "); " + r.source +
                             " duplicates an earlier run");
    by_label[label].runs.push_back(&r);
  }
  for (const Refused& r : refused) {
    const std::string label = point_label(r.scene, by);
    if (!by_label.count(label)) continue;  // a point with no finished run has no row
    if (!seeds[label].insert(r.scene.seed).second)
      throw core::InputError("analyze: seed " + std::to_string(r.scene.seed) +
                             " appears twice at the point (" + label + "); " + r.source +
                             " records a refusal of a seed that also finished");
    ++by_label[label].refused;
  }
  // Q_p: the mean Q of the pure system (chi = 0) at the same kick strength; a campaign over kicks has one
  // pure point per kick.
  std::vector<std::pair<std::string, std::string>> s_extra;
  auto pure_for = [&](const core::Scene& s) -> const Point* {
    const Point* found = nullptr;
    if (!s.shorthand()) return found;  // Q_p is the paper's: a scene of its own species has none
    for (auto& [label, p] : by_label)
      if (p.scene.shorthand() && p.scene.n_added() == 0 && p.scene.kick_impulse_max == s.kick_impulse_max &&
          p.extra == s_extra)
        found = &p;
    return found;
  };

  std::vector<Point> out;
  for (const auto& label : order) {
    Point p = by_label[label];
    s_extra = p.extra;
    const Point* pure = pure_for(p.scene);
    Estimate qp;
    if (pure) qp = estimate_of(pure->runs, &Measurements::q);
    p.q_p = qp;
    estimate_point(p, qp);
    out.push_back(std::move(p));
  }
  return out;
}

std::string realizations_csv(const std::vector<Run>& runs) {
  std::string s = summary_header() + ",source\n";
  for (const Run& r : runs) s += summary_row(r.scene, r.m) + "," + r.source + "\n";
  return s;
}

std::string points_csv(const std::vector<Point>& points) {
  std::string s = key_header(points);
  s += "dipole_force_ratio,kick_dv_over_sqrt_g_ro,n_runs,n_runs_pure,clogs,clogs_vibration,clogs_rule,"
       "clogs_spontaneous,ballistic_runs,n_refused";
  const char* names[] = {"q_per_s",
                         "q_tilde_per_s",
                         "chi_eff",
                         "long_arches_per_min",
                         "added_per_long_arch",
                         "fraction_broken_by_vibration",
                         "q_tilde_over_qp",
                         "q_p_per_s",
                         "airborne_fraction",
                         "avalanche_mean"};
  for (const char* n : names) s += std::string(",") + n + "," + n + "_ci95";
  s += ",avalanche_end\n";  // what ended the avalanches of avalanche_mean (analysis/measure.h)
  for (const auto& p : points) {
    s += key_values(p);
    // The shorthand's dipole strength and kick; a scene of its own species has neither (its species.csv
    // holds each species' flow).
    const core::Scene& sc = p.scene;
    if (sc.shorthand()) {
      s += core::format_g(core::dipole_contact_force(sc) /
                          (core::mass_of(sc.radius_added(), sc.density) * sc.gravity)) +
           ",";
      // The kick's largest velocity change for an original disk, in units of sqrt(g r_o).
      s += core::format_g(sc.kick_impulse_max / core::mass_of(sc.radius_original, sc.density) /
                          std::sqrt(sc.gravity * sc.radius_original)) +
           ",";
    } else {
      s += "nan,nan,";
    }
    s += std::to_string(p.runs.size()) + "," + std::to_string(p.q_p.n) + "," + std::to_string(p.clogs) + "," +
         std::to_string(p.clogs_vibration) + "," + std::to_string(p.clogs_rule) + "," +
         std::to_string(p.clogs_spontaneous) + "," + std::to_string(p.ballistic_runs) + "," +
         std::to_string(p.refused);
    for (const Estimate* e : {&p.q, &p.q_tilde, &p.chi_eff, &p.long_arches_per_min, &p.added_per_long_arch,
                              &p.fraction_broken_by_vibration, &p.q_tilde_over_qp, &p.q_p,
                              &p.airborne_fraction, &p.avalanche_mean})
      s += "," + core::format_g(e->mean) + "," + core::format_g(e->half_width);
    s += std::string(",") + avalanche_end_name(p.runs.front()->m.avalanche_end) + "\n";
  }
  return s;
}

std::string pooled_survival_csv(const std::vector<Point>& points) {
  std::string s = key_header(points);
  s += "tau_s,survival,gaps\n";
  for (const auto& p : points) {
    std::vector<double> gaps;
    for (const Run* r : p.runs) {
      auto g = original_gaps(r->events.exits);
      gaps.insert(gaps.end(), g.begin(), g.end());
    }
    auto taus = survival_taus(p.scene);
    auto surv = survival(gaps, taus);
    const std::string prefix = key_values(p);
    for (size_t i = 0; i < taus.size(); ++i)
      s += prefix + core::format_g(taus[i]) + "," + core::format_g(surv[i]) + "," +
           std::to_string(gaps.size()) + "\n";
  }
  return s;
}

std::string pooled_avalanches_csv(const std::vector<Point>& points) {
  std::string s = key_header(points);
  s += "size,survival,avalanches\n";
  for (const auto& p : points) {
    std::vector<double> sizes;
    for (const Run* r : p.runs) {
      std::vector<core::ExitEvent> within;
      for (const auto& e : r->events.exits)
        if (e.t <= r->m.duration) within.push_back(e);
      auto a = avalanche_sizes(within, r->events.clogs, p.scene.clog_min_gap, r->m.avalanche_end);
      sizes.insert(sizes.end(), a.begin(), a.end());
    }
    const std::string prefix = key_values(p);
    if (sizes.empty()) continue;
    const double largest = *std::max_element(sizes.begin(), sizes.end());
    std::vector<double> at;
    for (double v = 1; v <= std::min(10.0, largest); ++v) at.push_back(v);
    for (int k = 21; std::pow(10.0, k / 20.0) <= largest; ++k) {
      const double v = std::round(std::pow(10.0, k / 20.0));
      if (v > at.back()) at.push_back(v);
    }
    if (at.back() < largest) at.push_back(largest);
    const auto surv = survival(sizes, at);
    for (size_t i = 0; i < at.size(); ++i)
      s += prefix + core::format_g(at[i]) + "," + core::format_g(surv[i]) + "," +
           std::to_string(sizes.size()) + "\n";
  }
  return s;
}

std::string species_points_csv(const std::vector<Point>& points) {
  std::string s =
      key_header(points) + "species,count,n_runs,q_per_s,q_per_s_ci95,exit_fraction,exit_fraction_ci95\n";
  for (const auto& p : points)
    for (const auto& e : p.species)
      s += key_values(p) + e.name + "," + std::to_string(e.count) + "," + std::to_string(p.runs.size()) +
           "," + core::format_g(e.q.mean) + "," + core::format_g(e.q.half_width) + "," +
           core::format_g(e.exit_fraction.mean) + "," + core::format_g(e.exit_fraction.half_width) + "\n";
  return s;
}

std::string clog_survival_csv(const std::vector<Point>& points) {
  std::string s =
      key_header(points) +
      "t_s,survival,survival_lo95,survival_hi95,at_risk,clogs,clogs_broken,clogs_rule,clogs_run_end\n";
  for (const auto& p : points) {
    const long broken = p.clogs_spontaneous + p.clogs_vibration;
    for (const auto& step : p.clog_survival)
      s += key_values(p) + core::format_g(step.t) + "," + core::format_g(step.s) + "," +
           core::format_g(step.lo) + "," + core::format_g(step.hi) + "," + std::to_string(step.at_risk) +
           "," + std::to_string(p.clogs) + "," + std::to_string(broken) + "," + std::to_string(p.clogs_rule) +
           "," + std::to_string(p.clogs_run_end) + "\n";
  }
  return s;
}

std::string column_csv(const std::vector<Point>& points) {
  bool any = false;
  for (const auto& p : points)
    for (const Run* r : p.runs) any = any || r->m.column_frames > 0;
  if (!any) return "";
  std::string s =
      key_header(points) + "species,count,n_runs,n_runs_measured,frames,column_rank,column_rank_ci95\n";
  for (const auto& p : points) {
    long frames = 0, measured = 0;
    for (const Run* r : p.runs) frames += r->m.column_frames, measured += r->m.column_frames > 0;
    for (const auto& e : p.species)
      s += key_values(p) + e.name + "," + std::to_string(e.count) + "," + std::to_string(p.runs.size()) +
           "," + std::to_string(measured) + "," + std::to_string(frames) + "," +
           core::format_g(e.column_rank.mean) + "," + core::format_g(e.column_rank.half_width) + "\n";
  }
  return s;
}

std::string drain_csv(const std::vector<Point>& points) {
  bool any = false;
  for (const auto& p : points)
    for (const Run* r : p.runs) any = any || !r->m.drain_outcome.empty();
  if (!any) return "";
  std::string s = key_header(points);
  s += "n_runs,n_emptied,n_jammed,n_draining,jam_probability,jam_probability_lo95,jam_probability_hi95,"
       "exits_before_jam_mean,exits_before_jam_ci95,jam_time_s_mean,jam_time_s_ci95\n";
  for (const auto& p : points) {
    long emptied = 0, jammed = 0, draining = 0;
    std::vector<double> exits, times;
    for (const Run* r : p.runs) {
      if (r->m.drain_outcome == "emptied") ++emptied;
      if (r->m.drain_outcome == "draining") ++draining;
      if (r->m.drain_outcome != "jammed") continue;
      ++jammed;
      exits.push_back(static_cast<double>(r->m.exits));
      times.push_back(r->m.drain_end_s);
    }
    // Wilson's score interval (95%): never zero width, never outside [0, 1].
    const double n = static_cast<double>(emptied + jammed), z = 1.959963984540054;
    double j = NAN, lo = NAN, hi = NAN;
    if (n > 0) {
      j = jammed / n;
      const double c = (j + z * z / (2 * n)) / (1 + z * z / n),
                   h = z / (1 + z * z / n) * std::sqrt(j * (1 - j) / n + z * z / (4 * n * n));
      lo = std::max(0.0, c - h), hi = std::min(1.0, c + h);
    }
    const Estimate e = estimate(exits), t = estimate(times);
    auto g = [](double v) { return core::format_g(v); };
    s += key_values(p) + std::to_string(p.runs.size()) + "," + std::to_string(emptied) + "," +
         std::to_string(jammed) + "," + std::to_string(draining) + "," + g(j) + "," + g(lo) + "," + g(hi) +
         "," + g(jammed ? e.mean : NAN) + "," + g(jammed > 1 ? e.half_width : NAN) + "," +
         g(jammed ? t.mean : NAN) + "," + g(jammed > 1 ? t.half_width : NAN) + "\n";
  }
  return s;
}

}  // namespace analysis
