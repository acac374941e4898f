// The claims as a report: claims.md for people (a summary table, each part with its evidence, the controls,
// what stands between each verdict and the paper) and claims.csv for scripts (one row per comparison).
#include <cmath>
#include <cstdio>

#include "analysis/claims.h"
#include "analysis/stats.h"
#include "core/format.h"

namespace analysis::claims {

namespace {
std::string g(double v, int digits = 3) {
  return core::format_g(v, digits);
}
std::string signed_g(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%+.3g", v);
  return b;
}
std::string text(const Est& e) {
  if (!e.finite()) return "n/a";
  if (std::isinf(e.h)) return g(e.m) + " (n = " + std::to_string(e.n) + ": no interval)";
  return g(e.m) + " +- " + g(e.h, 2) + " (n = " + std::to_string(e.n) + ")";
}
std::string p_text(double p) {
  return p > 0 ? "p = " + g(p, 2) : std::string("p < 1e-16");
}
std::string outcome(const Comparison& c) {
  if (c.sign == 0) return "";
  if (c.expected == 0) return ", a resolved difference";
  return c.sign == c.expected ? ", resolved" : ", resolved against the claim";
}

std::string comparison_text(const Comparison& c) {
  if (c.pooled)
    return c.label + " (" + c.note + "): " + signed_g(c.diff) + " +- " + g(c.half, 2) + " (" + p_text(c.p) +
           ")" + outcome(c);
  if (c.b.n == 0 && c.b.h == 0) return c.label + ": " + text(c.a) + outcome(c);
  return c.label + ": " + text(c.a) + " vs " + text(c.b) + ": " + signed_g(c.diff) + " +- " + g(c.half, 2) +
         (c.expected != 0 ? " (" + p_text(c.p) + (c.bootstrap ? ", bootstrap" : "") + ")" : "") + outcome(c);
}

std::string located_text(const Located& l) {
  // A location on the grid's points can have every resample at one point: said so, not as an interval of
  // zero width.
  const std::string where = l.lo == l.hi ? " (both ends of the 95% interval at this grid point)"
                                         : ", 95% interval " + g(l.lo) + " to " + g(l.hi);
  std::string s = l.what + ": " + g(l.value) + where +
                  " (bootstrap over realizations); the paper: " + g(l.paper) + " +- " + g(l.tolerance, 2);
  if (l.missing > 0) s += "; not located in " + g(100 * l.missing, 2) + "% of the resamples";
  return s;
}

bool has_pool(const Part& p) {
  for (const auto& c : p.comparisons)
    if (c.pooled) return true;
  return false;
}

// A part over a range: the pool, then each r's difference in brief (the estimates are in claims.csv).
std::string pooled_evidence(const Part& p) {
  std::string pool, each;
  for (const auto& c : p.comparisons) {
    if (c.pooled) {
      pool = comparison_text(c);
      continue;
    }
    const size_t at = c.label.find("r = ");
    std::string r =
        at == std::string::npos ? c.label : c.label.substr(at + 4, c.label.find(',', at) - at - 4);
    r = r.substr(0, r.find(' '));
    each += std::string(each.empty() ? "" : ", ") + r + ": " + signed_g(c.diff) + " +- " + g(c.half, 2) +
            (c.sign == c.expected ? " (resolved)"
             : c.sign != 0        ? " (resolved against)"
                                  : "");
  }
  return pool + "; per r: " + each;
}

std::string part_evidence(const Part& p) {
  std::string s;
  if (p.located) s = located_text(*p.located);
  if (!p.evidence.empty())
    s += (s.empty() ? "" : "; ") + p.evidence;
  else if (has_pool(p))
    s += (s.empty() ? "" : "; ") + pooled_evidence(p);
  else
    for (const auto& c : p.comparisons) s += (s.empty() ? "" : "; ") + comparison_text(c);
  if (!p.why.empty()) s += (s.empty() ? "" : ". ") + p.why;
  return s;
}

// What would settle one comparison that does not yet agree (empty if it agrees): the realizations per
// point at which a difference of this size is resolved even at the strictest step of Holm's correction
// (0.05 / k: an upper estimate), the spread shrinking as 1/sqrt(n) and the means staying.
std::string gap(const Comparison& c) {
  const long n = c.pooled ? c.a.n : std::min(c.a.n, c.b.n > 0 ? c.b.n : c.a.n);
  if (!std::isfinite(c.diff) || std::isinf(c.half))
    return c.label + ": no interval (n = " + std::to_string(n) + ")";
  const double widen = normal_quantile(1 - 0.025 / std::max(1, c.k)) / normal_quantile(0.975);
  const double h = c.half * widen;
  const std::string head = c.label + ": " + signed_g(c.diff) + " +- " + g(c.half, 2);
  if (c.expected == 0) {
    const double room = kEquivalence * std::abs(c.b.m) - std::abs(c.diff);
    if (c.sign != 0) return head + ", a resolved difference (n = " + std::to_string(n) + ")";
    if (room <= 0)
      return head +
             "; the mean difference alone exceeds +-10%: more realizations show agreement only if the means "
             "move closer (n = " +
             std::to_string(n) + ")";
    if (h <= room) return "";
    return head + "; within +-10% at about n = " +
           std::to_string(static_cast<long>(std::ceil(n * (h / room) * (h / room)))) + " per point (now " +
           std::to_string(n) + ")";
  }
  if (c.sign == c.expected) return "";
  if (c.sign == -c.expected)
    return head + " (" + p_text(c.p) + "), resolved against the claim (n = " + std::to_string(n) + ")";
  if (c.diff == 0) return c.label + ": no difference at all (n = " + std::to_string(n) + ")";
  // An estimate of the n that would resolve the difference only where more realizations could move the
  // verdict towards the paper (the estimate points the claim's way); against the claim, more runs could only
  // resolve it against, and the note says so.
  if (c.diff * c.expected < 0)
    return head + " (" + p_text(c.p) + "), against the claim, not resolved among the claim's " +
           std::to_string(c.k) +
           " comparisons; more realizations could only resolve it against the claim (n = " +
           std::to_string(n) + ")";
  return head + " (" + p_text(c.p) + "), in the claim's direction, not resolved among the claim's " +
         std::to_string(c.k) +
         " comparisons; a difference this size would be resolved for the claim at about n = " +
         std::to_string(static_cast<long>(std::ceil(n * (h / c.diff) * (h / c.diff)))) + " per point (now " +
         std::to_string(n) + ")";
}

std::string located_gap(const Located& l, long n) {
  const double room = l.tolerance - std::abs(l.value - l.paper), half = 0.5 * (l.hi - l.lo);
  std::string s = located_text(l);
  if (room <= 0)
    return s +
           "; the estimate itself lies outside the paper's range: more realizations would contradict "
           "the part if it stayed there";
  if (half > 0 && std::isfinite(half))
    s += "; the interval would fit at about n = " +
         std::to_string(static_cast<long>(std::ceil(n * (half / room) * (half / room)))) +
         " per point if the estimate stayed (now " + std::to_string(n) + ")";
  return s;
}

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char ch : s) q += ch == '"' ? std::string("\"\"") : std::string(1, ch);
  return q + "\"";
}
}  // namespace

namespace {
// The controls: r = 1 without dipoles against the pure system and chi.
std::string controls_section(const std::vector<Preset>& presets) {
  std::string s;
  s += "\n## Controls: the model against itself\n\n"
       "At r = 1 without dipoles the added disks are the original disks relabelled, so that point must match "
       "the "
       "pure system, and its chi_eff must equal chi. A control that differs (Holm's correction over the "
       "preset's "
       "controls, 5%) points at an asymmetry of the model or of its protocol, or at an unlucky sample; it is "
       "named "
       "here, not hidden.\n\n";
  for (const auto& p : presets) {
    if (p.controls.empty())
      s += "- **" + p.label + "**: the grid lacks r = 1 without dipoles or the pure system\n";
    for (const auto& c : p.controls) {
      s += "- **" + p.label + "**: " + c.label + ": " + text(c.a) + " vs " + (c.b.n ? text(c.b) : g(c.b.m)) +
           ": " + signed_g(c.a.m - c.b.m) + " +- " + g(std::hypot(c.a.h, c.b.h), 2) + " (" + p_text(c.p) +
           "): " + (c.differs ? "**differs**" : "consistent");
      if (c.differs && c.label.rfind("chi_eff", 0) == 0 && c.a.m < c.b.m)
        s += " (measured cause: the deposition places the added disks after the original ones and crowds "
             "them out of "
             "the funnel, so the first exits hold too few of them: docs/campaigns/README.md, 'The initial "
             "packing')";
      s += "\n";
    }
  }
  return s;
}

// For every part not reproduced: what pins it, or what would settle it.
std::string gaps_section(const std::vector<Preset>& presets) {
  std::string s;
  s += "\n## What stands between each verdict and the paper\n\n"
       "For every part not reproduced: a measure the protocol pins, or each comparison that does not yet "
       "agree with "
       "its difference, combined 95% half-width, and the realizations per point at which a difference of "
       "that size "
       "would be resolved even at the strictest step of the claim's correction (0.05/k: an upper estimate) "
       "if the "
       "means stayed (the half-width shrinking as 1/sqrt(n)). Then the measured facts that bear on the "
       "differences.\n";
  for (const auto& p : presets) {
    s += "\n### " + p.label + "\n\n";
    for (const auto& c : p.claims)
      for (size_t k = 0; k < c.parts.size(); ++k) {
        const Part& part = c.parts[k];
        if (part.verdict == Verdict::Reproduced) continue;
        std::string why;
        if (part.verdict == Verdict::Pinned || part.verdict == Verdict::NotTested ||
            part.verdict == Verdict::Smaller) {  // no number of realizations changes a size
          why = part.why;
        } else {
          if (part.located) why = located_gap(*part.located, p.n_min);
          if (part.own_family) why += (why.empty() ? "" : "; ") + part.evidence;
          const bool pool = has_pool(part);
          for (const auto& cmp : part.comparisons) {
            // A range is settled by its pool: each r is listed only where it is resolved against the claim.
            if (part.own_family || (pool && !cmp.pooled && cmp.sign != -cmp.expected)) continue;
            const std::string t = gap(cmp);
            if (!t.empty()) why += (why.empty() ? "" : "; ") + t;
          }
        }
        s += "- **" + c.id + "." + std::to_string(k + 1) + " (" + verdict_text(part.verdict) +
             ")**: " + (why.empty() ? "the grid lacks the points" : why) + "\n";
      }
    for (const auto& cause : p.causes) s += "- measured: " + cause + "\n";
  }
  return s;
}
}  // namespace

std::string markdown(const std::vector<Preset>& presets, const std::string& version) {
  std::string s =
      "# The paper's seven claims against siloscope's results\n\nGenerated by `siloscope claims` (" +
      version + ") from ";
  for (size_t i = 0; i < presets.size(); ++i)
    s += std::string(i ? ", " : "") + "`" + presets[i].label + "` = `" + presets[i].dir + "`" +
         (presets[i].column_dir.empty()
              ? ""
              : " (where each species sits in the column: `" + presets[i].column_dir +
                    "/column.csv`, a campaign at the same points with trajectories)");
  s += ".\n\n"
       "Each claim of `../shared/model.md` is split into its parts, in its words; each part has its own "
       "comparisons "
       "and verdict. A difference counts only when it survives Holm's step-down correction over every "
       "p-valued "
       "comparison of its claim (the chance of any false difference in a claim stays 5%); the +- shown are "
       "plain 95% "
       "half-widths (Student t over realizations; a bootstrap over realizations where marked). A part over a "
       "range of "
       "r is decided by the pooled difference (the mean of the per-r differences over the range) with no "
       "single r "
       "resolved against it; a part over every value (\"at any mu\") needs each resolved. A located quantity "
       "(the "
       "maximum of Q~, the crossing Q~ = Q_p) is reproduced when its 95% bootstrap interval lies within the "
       "paper's "
       "value +- one grid step, contradicted when it lies wholly outside. A claim of equality needs the "
       "difference's "
       "interval within +-10%. Where a part's words imply a size (\"much rarer\", \"on top\"), that size is "
       "written down with the claim before any verdict: the part is reproduced only when its effect reaches "
       "it, \"resolved, smaller than its words\" when the effect's whole interval falls short of it, and not "
       "resolved between. \"Cannot be tested at this kick\" names a measure the protocol pins (below 5% "
       "of clogs "
       "broken by vibration, the 5 s rule ends every clog). A claim is reproduced when every part is, "
       "contradicted "
       "when one part is, partly reproduced when some parts are and none is contradicted.\n\n";
  for (const auto& p : presets) {
    s += "**" + p.label + "**: n = " + std::to_string(p.n_min) +
         (p.n_max != p.n_min ? "-" + std::to_string(p.n_max) : "") + " realizations per point.";
    if (!p.refused.empty())
      s += " Refused by the health monitor, not in n (the estimates there are of the realizations that "
           "finished, a "
           "selection): " +
           p.refused + ".";
    s += "\n";
  }
  s += "\n| claim, part |";
  for (const auto& p : presets) s += " " + p.label + " |";
  s += "\n|---|";
  for (size_t i = 0; i < presets.size(); ++i) s += "---|";
  s += "\n";
  const auto& first = presets.front().claims;
  for (size_t c = 0; c < first.size(); ++c) {
    s += "| **" + first[c].id + "** " + first[c].words + " |";
    for (const auto& p : presets) s += std::string(" **") + verdict_text(p.claims[c].verdict) + "** |";
    s += "\n";
    for (size_t k = 0; k < first[c].parts.size(); ++k) {
      s += "| " + first[c].id + "." + std::to_string(k + 1) + " " + first[c].parts[k].words + " |";
      for (const auto& p : presets) s += std::string(" ") + verdict_text(p.claims[c].parts[k].verdict) + " |";
      s += "\n";
    }
  }
  for (const auto& p : presets) {
    s += "\n## " + p.label + "\n";
    for (const auto& c : p.claims) {
      s += "\n### " + c.id + " " + c.words + ": " + verdict_text(c.verdict) + "\n\n";
      for (size_t k = 0; k < c.parts.size(); ++k)
        s += "- **" + c.id + "." + std::to_string(k + 1) + " " + c.parts[k].words + ": " +
             verdict_text(c.parts[k].verdict) + ".** " + part_evidence(c.parts[k]) + "\n";
    }
  }
  return s + controls_section(presets) + gaps_section(presets);
}

const char* const kCsvHeader =
    "preset,claim,claim_verdict,part,part_words,part_verdict,kind,label,a,a_ci95,b,b_ci95,n,difference,"
    "difference_ci95,p,expected_sign,resolved_sign,holm_family,method,lo95,hi95,paper_value,paper_tolerance";

std::string csv(const std::vector<Preset>& presets) {
  std::string s = std::string(kCsvHeader) + "\n";
  auto num = [](double v) { return core::format_g(v); };
  for (const auto& p : presets)
    for (const auto& c : p.claims)
      for (size_t k = 0; k < c.parts.size(); ++k) {
        const Part& part = c.parts[k];
        const std::string head = csv_field(p.label) + "," + c.id + "," + csv_field(verdict_text(c.verdict)) +
                                 "," + c.id + "." + std::to_string(k + 1) + "," + csv_field(part.words) +
                                 "," + csv_field(verdict_text(part.verdict)) + ",";
        if (part.located) {
          const Located& l = *part.located;
          s += head + "located," + csv_field(l.what) + "," + num(l.value) + ",,,,," + ",,,,,,bootstrap," +
               num(l.lo) + "," + num(l.hi) + "," + num(l.paper) + "," + num(l.tolerance) + "\n";
        }
        for (const auto& x : part.comparisons)
          s += head + (x.pooled ? "pooled," : "comparison,") + csv_field(x.label) + "," + num(x.a.m) + "," +
               num(x.a.h) + "," + num(x.b.m) + "," + num(x.b.h) + "," + std::to_string(x.a.n) + "," +
               num(x.diff) + "," + num(x.half) + "," + (x.expected != 0 ? num(x.p) : "") + "," +
               std::to_string(x.expected) + "," + std::to_string(x.sign) + "," + std::to_string(x.k) + "," +
               (x.bootstrap       ? "bootstrap"
                : x.expected == 0 ? "equivalence"
                                  : "t") +
               ",,,,\n";
        if (!part.located && part.comparisons.empty())
          s += head + "none," + csv_field(part.why) + ",,,,,,,,,,,,,,,,\n";
      }
  return s;
}

}  // namespace analysis::claims
