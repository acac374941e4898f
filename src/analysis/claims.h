// The paper's seven claims (../shared/model.md, C1-C7) judged against a campaign's analysis, part by part.
//
// Each claim is split into its parts as model.md words them; each part has its own comparisons and verdict:
// - reproduced, contradicted or not resolved, from 95% intervals. A difference counts only when it survives
//   Holm's correction over every p-valued comparison of its claim (5% chance of any false difference per
//   claim). A part over a range of r ("for r > 0.6") is decided by the pooled difference over that range (the
//   mean of the per-r differences), with no single r resolved against it; a part over every value ("at any
//   mu") needs each one resolved. A located quantity (the maximum of Q~, the crossing Q~ = Q_p) is reproduced
//   when its bootstrap interval lies within the paper's value +- one grid step, contradicted when it lies
//   wholly outside.
// - "cannot be tested at this kick" where the protocol pins the measure (almost every clog lasting to the 5 s
//   rule pins the long arches per minute), with the measured fraction of clogs broken by vibration.
// - "not tested" where the outputs hold no measure of the part.
// - "resolved, smaller than its words" where a part's words imply a size ("much rarer") written down with
//   the claim (Part::implied) and the effect, resolved the claim's way, falls short of it over its whole
//   interval; a part whose effect reaches the size only within its interval is not resolved.
// A claim is reproduced when all its parts are, contradicted when one is, partly reproduced when some are and
// the rest are not resolved or cannot be tested, not resolved otherwise.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace analysis::claims {

// An estimate: mean, 95% half-width (infinite: no interval), realizations behind it.
struct Est {
  double m = 0, h = 0;
  long n = 0;
  static Est none();
  static Est exact(double v) { return {v, 0, 0}; }  // a constant (the 1 of Q~/Q_p = 1), n = 0
  bool finite() const;
};

enum class Verdict { Reproduced, Contradicted, NotResolved, Partly, Pinned, NotTested, Smaller };
const char* verdict_text(Verdict v);

// `a` against `b`: the claim says a > b (expected +1), a < b (-1), or a = b within kEquivalence of b (0).
struct Comparison {
  Comparison() = default;
  Comparison(std::string l, Est x, Est y, int e) : label(std::move(l)), a(x), b(y), expected(e) {}
  std::string label;
  Est a, b;
  int expected = 0;
  double diff = 0, half = 0, p = 1;  // a - b, its 95% half-width, two-sided p (1: none)
  bool bootstrap = false;            // half and p from a bootstrap over realizations
  int sign = 0;                      // +1 / -1: resolved that way (after Holm); 0: not resolved
  int k = 1;                         // p-valued comparisons in the claim (Holm's family)
  bool pooled = false;               // the mean difference over a range of r
  std::string note;                  // e.g. what a pooled comparison pools
};
// A claim of equality (C5, C2's "negligible near 0.6") needs the difference's interval within this fraction
// of b.
constexpr double kEquivalence = 0.10;
// Below this fraction of clogs broken by vibration, the long arches per minute are pinned by the 5 s rule.
constexpr double kPinnedVibration = 0.05;
// Rounding allowed in every comparison of an interval with the paper's range, on both sides alike (relative
// to the numbers compared, at least 1): an end that touches the range within this is neither inside nor
// outside.
constexpr double kRounding = 1e-9;
// The lapse the survival of C6 is read at, s.
constexpr double kLongLapse = 1.0;

// A quantity located with a bootstrap interval (the maximum of Q~, the crossing of Q~/Q_p with 1).
struct Located {
  Located() = default;
  Located(std::string w, double v, double p, double tol)
      : what(std::move(w)), value(v), paper(p), tolerance(tol) {}
  std::string what;
  double value = 0, lo = 0, hi = 0;  // estimate and 95% percentile interval
  double paper = 0, tolerance = 0;   // the paper's value and the half-width of "near"
  double missing = 0;                // fraction of resamples in which it could not be located
};

// The size a part's words imply, written down with the claim before any verdict: the effect (the pooled
// comparison, or each) in the claim's direction, absolute or relative to one side of the comparison.
struct Implied {
  enum class Of { Absolute, A, B };
  std::string words;  // what the words mean in numbers, e.g. "at most half as often: a fall of >= 50%"
  double size = 0;    // the least effect
  Of of = Of::Absolute;
};

struct Part {
  Part() = default;
  explicit Part(std::string w) : words(std::move(w)) {}
  std::string words;
  Verdict verdict = Verdict::NotResolved;
  std::vector<Comparison> comparisons;
  std::optional<Located> located;
  std::string evidence;            // a summary of the estimates (empty: the comparisons speak for themselves)
  std::string why;                 // Pinned / NotTested: the reason; otherwise a remark (may be empty)
  bool own_family = false;         // its comparisons are a Holm family of their own (C3's "only there")
  std::optional<Implied> implied;  // the effect its words imply (none: the sign alone)
};

struct Claim {
  Claim() = default;
  Claim(std::string i, std::string w) : id(std::move(i)), words(std::move(w)) {}
  std::string id, words;
  std::vector<Part> parts;
  Verdict verdict = Verdict::NotResolved;
};

struct Control {
  std::string label;
  Est a, b;
  double p = 1;
  bool differs = false;
};

struct Preset {
  std::string label, dir;  // dir: the analysis directory
  std::string column_dir;  // where column.csv came from when not `dir` (judge's `column_dir`)
  long n_min = 0, n_max = 0;
  std::string refused;  // points with realizations the health monitor refused, as text (may be empty)
  std::vector<Claim> claims;
  std::vector<Control> controls;
  std::vector<std::string> causes;  // measured facts that bear on the verdicts
};

// Judges the campaign whose `siloscope analyze` output is in `analysis_dir` (points.csv; realizations.csv for
// the bootstrap parts). Throws core::InputError for a missing or malformed table.
// `column_dir`: an analysis directory whose column.csv (where each species sits, from trajectories) stands
// for this campaign's at the same points (empty: `analysis_dir`'s own, when it has one).
Preset judge(const std::string& label, const std::string& analysis_dir, const std::string& column_dir = "");

// The report: claims.md (summary table, each part with its evidence, controls, what stands between each
// verdict and the paper) and claims.csv (one row per comparison or located quantity).
std::string markdown(const std::vector<Preset>& presets, const std::string& version);
std::string csv(const std::vector<Preset>& presets);
extern const char* const kCsvHeader;  // claims.csv's first line
// One line per preset, e.g. "literal: C1 partly reproduced, C2 ...".
std::string summary_line(const Preset& p);

}  // namespace analysis::claims
