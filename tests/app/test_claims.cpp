// siloscope claims: verdicts from synthetic campaigns whose answers are known.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "helpers.h"

namespace fs = std::filesystem;
using test::cli;
using test::slurp;

namespace {
fs::path temp_dir(const std::string& name) {
  return test::temp_dir("claims_" + name);
}

// An analysis/points.csv in dir, its header written.
std::ofstream points_csv(const fs::path& dir) {
  fs::create_directories(dir);
  std::ofstream f(dir / "points.csv");
  f << "size_ratio,chi,mu,kick_impulse_max,dipole_force_ratio,n_runs,q_tilde_over_qp,q_tilde_over_qp_ci95,"
       "q_tilde_per_s,q_tilde_per_s_ci95,chi_eff,chi_eff_ci95,long_arches_per_min,long_arches_per_min_ci95,"
       "added_per_long_arch,added_per_long_arch_ci95\n";
  return f;
}

// A synthetic analysis/points.csv: r = 0.4 and 1.0 at F/W 0 and 10, the pure system; Q~/Q_p at r = 0.4 is
// `small`, at r = 1 `large`, each +- 0.1 from 10 realizations.
void synthetic_points(const fs::path& dir, double small, double large) {
  std::ofstream f = points_csv(dir);
  for (double r : {0.4, 1.0})
    for (double fr : {0.0, 10.0}) {
      const double ratio = r < 0.5 ? small : large;
      f << r << ",0.4," << fr << ",5e-05," << fr << ",10," << ratio << ",0.1," << 2 * ratio << ",0.2,"
        << (fr > 0 ? 0.30 : 0.45) << ",0.02,9,0.5,0.5,0.1\n";
    }
  f << "0.4,0,0,5e-05,0,10,1,0.1,2,0.2,0,0,10,0.5,0,0\n";
}

// r = 0.4: non-magnetic chi = 0.1 .. 0.4 with chi_eff = chi + 0.02 and Q~ = 2 + 5 chi_eff; one magnetic point
// (F/W = 10) at chi_eff = 0.41, beyond the nominal chi range, with Q~ = `q_mag`; every Q~ +- `ci`.
void c5_points(const fs::path& dir, double q_mag, double ci) {
  std::ofstream f = points_csv(dir);
  for (double chi : {0.1, 0.2, 0.3, 0.4})
    f << "0.4," << chi << ",0,5e-05,0,10,1,0.1," << 2 + 5 * (chi + 0.02) << "," << ci << "," << chi + 0.02
      << ",0.005,9,0.5,0.5,0.1\n";
  f << "0.4,0.4,1,5e-05,10,10,1,0.1," << q_mag << "," << ci << ",0.41,0.005,9,0.5,0.5,0.1\n";
  f << "0.4,0,0,5e-05,0,10,1,0.1,2,0.2,0,0,10,0.5,0,0\n";
}
}  // namespace

TEST_CASE("claims: C5 compares at equal chi_eff and needs shown agreement, not only wide intervals",
          "[claims][app]") {
  fs::path d = temp_dir("claims-c5");
  c5_points(d / "same" / "analysis", 2 + 5 * 0.41, 0.05);  // on the non-magnetic curve, tight
  c5_points(d / "off" / "analysis", 5.5, 0.05);            // well above it
  c5_points(d / "wide" / "analysis", 2 + 5 * 0.41, 1.0);   // on it, but the intervals allow +-25%
  auto r = cli("claims same=" + (d / "same").string() + " off=" + (d / "off").string() +
               " wide=" + (d / "wide").string() + " --out " + (d / "claims.md").string());
  REQUIRE(r.code == 0);
  CHECK_THAT(r.output, Catch::Matchers::Contains("same: C1") && Catch::Matchers::Contains("C5 reproduced"));
  const std::string md = slurp(d / "claims.md");
  CHECK_THAT(md, Catch::Matchers::Contains("measured chi_eff"));
  auto verdict_of = [&](const std::string& label) {
    const size_t at = r.output.find(label + ": ");
    REQUIRE(at != std::string::npos);
    const std::string line = r.output.substr(at, r.output.find('\n', at) - at);
    const size_t c5 = line.find("C5 ");
    REQUIRE(c5 != std::string::npos);
    return line.substr(c5 + 3, line.find(',', c5) - c5 - 3);
  };
  CHECK(verdict_of("same") == "reproduced");
  CHECK(verdict_of("off") == "contradicted");
  CHECK(verdict_of("wide") == "not resolved");
  // What would settle "wide": the difference (0) +- sqrt(2) inside +-10% of 4.05 needs n = 10 (1.414 /
  // 0.405)^2.
  CHECK_THAT(md, Catch::Matchers::Contains("## What stands between each verdict and the paper") &&
                     Catch::Matchers::Contains("within +-10% at about n = 122 per point (now 10)") &&
                     Catch::Matchers::Contains("a resolved difference (n = 10)"));
}

TEST_CASE("claims: a claim of several comparisons is not decided by one that chance alone resolves",
          "[claims][app]") {
  fs::path d = temp_dir("claims-holm");
  // C2: Q~ at r = 1 falls with the dipoles by 0.3 +- 0.28 (p = 0.038 alone): resolved when it is the claim's
  // only comparison, not when r = 0.4 (no change) is a second one (Holm: the smallest p must be below 0.05 /
  // 2).
  for (const char* name : {"one", "two"}) {
    std::ofstream f = points_csv(d / name / "analysis");
    if (std::string(name) == "two")
      f << "0.4,0.4,0,5e-05,0,10,1.5,0.1,3.0,0.2,0.45,0.02,9,0.5,0.5,0.1\n"
           "0.4,0.4,1,5e-05,10,10,1.5,0.1,3.0,0.2,0.30,0.02,9,0.5,0.5,0.1\n";
    f << "1,0.4,0,5e-05,0,10,0.6,0.1,2.0,0.2,0.45,0.02,9,0.5,0.5,0.1\n"
         "1,0.4,5,5e-05,10,10,0.6,0.1,1.7,0.2,0.30,0.02,9,0.5,0.5,0.1\n"
         "0.4,0,0,5e-05,0,10,1,0.1,2,0.2,0,0,10,0.5,0,0\n";
  }
  auto r = cli("claims one=" + (d / "one").string() + " two=" + (d / "two").string() + " --out " +
               (d / "claims.md").string());
  REQUIRE(r.code == 0);
  CHECK_THAT(r.output, Catch::Matchers::Contains("one: C1 not resolved, C2 contradicted") &&
                           Catch::Matchers::Contains("two: C1 reproduced, C2 not resolved"));
  CHECK_THAT(slurp(d / "claims.md"),
             Catch::Matchers::Contains("-0.3 +- 0.28 (p = 0.038), against the claim, not resolved "
                                       "among the claim's 2 comparisons"));
}

TEST_CASE("claims: verdicts follow the intervals (reproduced, contradicted, not resolved)", "[claims][app]") {
  fs::path d = temp_dir("claims");
  synthetic_points(d / "good" / "analysis", 1.5, 0.6);  // C1's shape, resolved
  synthetic_points(d / "bad" / "analysis", 0.6, 1.5);   // the opposite
  auto r = cli("claims good=" + (d / "good").string() + " bad=" + (d / "bad").string() + " --out " +
               (d / "claims.md").string());
  REQUIRE(r.code == 0);
  CHECK_THAT(r.output, Catch::Matchers::Contains("good: C1 reproduced") &&
                           Catch::Matchers::Contains("bad: C1 contradicted"));
  // chi_eff 0.45 -> 0.30 with +- 0.02: C4 reproduced in both.
  CHECK_THAT(r.output, Catch::Matchers::Contains("C4 reproduced"));
  const std::string md = slurp(d / "claims.md");
  CHECK_THAT(
      md, Catch::Matchers::Contains("| C1 non-magnetic") && Catch::Matchers::Contains("n = 10 realizations"));
  // The contradicted claim names the comparison that contradicts it; a reproduced one is not listed.
  CHECK_THAT(md, Catch::Matchers::Contains("Q~/Q_p at r = 0.4 against 1: -0.4 +- 0.1 (p = ") &&
                     Catch::Matchers::Contains("resolved against the claim (n = 10)"));
  CHECK_THAT(md, !Catch::Matchers::Contains("Q~/Q_p at r = 0.4 against 1: +0.5"));
  // Realizations the health monitor refused are named with their point, out of n.
  {
    fs::path sel = d / "sel" / "analysis";
    synthetic_points(sel, 1.5, 0.6);
    std::istringstream in(slurp(sel / "points.csv"));
    std::string out, line;
    for (int k = 0; std::getline(in, line); ++k)
      out += line + (k == 0 ? ",n_refused" : k == 1 ? ",3" : ",0") + "\n";
    std::ofstream(sel / "points.csv") << out;
    REQUIRE(cli("claims sel=" + (d / "sel").string() + " --out " + (d / "sel.md").string()).code == 0);
    CHECK_THAT(slurp(d / "sel.md"), Catch::Matchers::Contains("Refused by the health monitor") &&
                                        Catch::Matchers::Contains("r = 0.4, chi = 0.4, F/W = 0: 3 of 13"));
    CHECK_THAT(md, !Catch::Matchers::Contains("Refused by the health monitor"));
  }
  // One realization per point: no interval, nothing resolved.
  fs::path one = d / "one" / "analysis";
  synthetic_points(one, 1.5, 0.6);
  std::string text = slurp(one / "points.csv");
  for (size_t at = text.find(",10,"); at != std::string::npos; at = text.find(",10,", at + 1))
    text.replace(at, 4, ",1,");
  std::ofstream(one / "points.csv") << text;
  r = cli("claims one=" + (d / "one").string() + " --out " + (d / "one.md").string());
  REQUIRE(r.code == 0);
  CHECK_THAT(r.output, Catch::Matchers::Contains("one: C1 not resolved"));
  // Its own table is replaced with --force, a user's file is not; a missing analysis is named.
  CHECK(cli("claims good=" + (d / "good").string() + " --force --out " + (d / "claims.md").string()).code ==
        0);
  std::ofstream(d / "notes.md") << "# my notes\n";
  CHECK(cli("claims good=" + (d / "good").string() + " --force --out " + (d / "notes.md").string()).code ==
        2);
  CHECK(slurp(d / "notes.md") == "# my notes\n");
  r = cli("claims x=" + (d / "nothing").string() + " --out " + (d / "x.md").string());
  CHECK(r.code == 2);
  CHECK_THAT(r.output, Catch::Matchers::Contains("holds no points.csv"));
}

TEST_CASE("claims: controls check the r = 1 non-magnetic point against the pure system and chi",
          "[claims][app]") {
  fs::path d = temp_dir("claims-controls");
  // r = 1 without dipoles is the pure system relabelled: Q, the mean avalanche size and chi_eff = chi must
  // agree. "same" agrees; "asym" has chi_eff 0.37 +- 0.01 (p < 1e-8) and Q 2.3 +- 0.1 against 2.0 +- 0.1
  // (p = 3.2e-5); "alone" has no pure point.
  for (const char* name : {"same", "asym", "alone"}) {
    const std::string n = name;
    fs::create_directories(d / name / "analysis");
    std::ofstream f(d / name / "analysis" / "points.csv");
    f << "size_ratio,chi,mu,kick_impulse_max,dipole_force_ratio,n_runs,q_per_s,q_per_s_ci95,q_tilde_over_qp,"
         "q_tilde_over_qp_ci95,q_tilde_per_s,q_tilde_per_s_ci95,chi_eff,chi_eff_ci95,long_arches_per_min,"
         "long_arches_per_min_ci95,added_per_long_arch,added_per_long_arch_ci95,avalanche_mean,"
         "avalanche_mean_ci95\n";
    f << "1,0.4,0,5e-05,0,20," << (n == "asym" ? "2.3" : "2.0") << ",0.1,0.6,0.05,1.2,0.06,"
      << (n == "asym" ? "0.37" : "0.401") << ",0.01,10,0.2,0.5,0.1,12,1\n";
    if (n != "alone") f << "0.4,0,0,5e-05,0,20,2.0,0.1,1,0.05,2.0,0.1,0,0,10,0.2,0,0,12.5,1\n";
  }
  auto r = cli("claims same=" + (d / "same").string() + " asym=" + (d / "asym").string() +
               " alone=" + (d / "alone").string() + " --out " + (d / "claims.md").string());
  REQUIRE(r.code == 0);
  const std::string md = slurp(d / "claims.md");
  INFO(md);
  CHECK_THAT(md, Catch::Matchers::Contains("## Controls: the model against itself"));
  CHECK_THAT(md,
             Catch::Matchers::Contains("- **same**: chi_eff at r = 1, F/W = 0 against chi = 0.4: 0.401 +- "
                                       "0.01 (n = 20) vs 0.4: +0.001 +- 0.01 (p = 0.84): consistent"));
  CHECK_THAT(md,
             Catch::Matchers::Contains("- **same**: Q [1/s], all disks at r = 1, F/W = 0 against the pure "
                                       "system: 2 +- 0.1 (n = 20) vs 2 +- 0.1 (n = 20): +0 +- 0.14 (p = 1): "
                                       "consistent"));
  CHECK_THAT(md,
             Catch::Matchers::Contains("- **same**: mean avalanche size [disks] at r = 1, F/W = 0 against "
                                       "the pure system: 12 +- 1 (n = 20) vs 12.5 +- 1 (n = 20)"));
  CHECK_THAT(md, Catch::Matchers::Contains("-0.03 +- 0.01 (p = ") &&
                     Catch::Matchers::Contains("): **differs** (measured cause: the deposition"));
  CHECK_THAT(md, Catch::Matchers::Contains("+0.3 +- 0.14 (p = 3.2e-05): **differs**"));
  CHECK_THAT(
      md, Catch::Matchers::Contains("- **alone**: the grid lacks r = 1 without dipoles or the pure system"));
}
