#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "analysis/aggregate.h"
#include "analysis/column.h"
#include "analysis/measure.h"
#include "analysis/stats.h"
#include "core/error.h"
#include "core/physics.h"
#include "io/events_csv.h"

using core::Species;

TEST_CASE("where each species sits in the column: mean height ranks along gravity, by hand", "[analysis]") {
  // Four grains in a column: original at heights 1 and 2, added at 3 and 4 (ranks 1/8, 3/8 and 5/8, 7/8); one
  // below the outlet (falling out) is not in the column.
  core::Frame f;
  f.t = 1;
  auto grain = [](float x, float y, core::Species s) {
    core::Particle p{};
    p.x = x, p.y = y, p.species = s;
    return p;
  };
  f.particles = {grain(0, 1, core::Species::Original), grain(0, 3, core::Species::Added),
                 grain(0, 2, core::Species::Original), grain(0, 4, core::Species::Added),
                 grain(0, -0.5f, core::Species::Added)};
  analysis::ColumnMeter m(0, 2);
  m.add(f);
  CHECK(m.ranks()[0] == Approx(0.25));
  CHECK(m.ranks()[1] == Approx(0.75));
  // Frames before the aperture opened are not measured; a second frame with the order reversed averages.
  f.t = -1;
  m.add(f);
  CHECK(m.frames() == 1);
  f.t = 2;
  std::swap(f.particles[0].species, f.particles[3].species);
  std::swap(f.particles[2].species, f.particles[1].species);
  m.add(f);
  CHECK(m.frames() == 2);
  CHECK(m.ranks()[0] == Approx(0.5));
  CHECK(m.ranks()[1] == Approx(0.5));
  // Tilted 90 degrees (gravity along -x): heights are x, so the same grains laid along x rank the same way.
  analysis::ColumnMeter tilted(core::kPi / 2, 2);
  core::Frame g;
  g.t = 0;
  g.particles = {grain(1, 5, core::Species::Added), grain(2, -5, core::Species::Original)};
  tilted.add(g);
  CHECK(tilted.ranks()[1] == Approx(0.25));
  CHECK(tilted.ranks()[0] == Approx(0.75));
  CHECK(std::isnan(analysis::ColumnMeter(0, 3).ranks()[2]));
}

TEST_CASE("Student t critical values match tables", "[analysis]") {
  CHECK(analysis::student_t_critical(0.95, 4) == Approx(2.776445).epsilon(1e-6));
  CHECK(analysis::student_t_critical(0.95, 49) == Approx(2.009575).epsilon(1e-6));
  CHECK(analysis::student_t_critical(0.95, 1) == Approx(12.706205).epsilon(1e-6));
  CHECK(analysis::student_t_critical(0.99, 10) == Approx(3.169273).epsilon(1e-6));
}

TEST_CASE("mean and 95% confidence interval of a small sample, by hand", "[analysis]") {
  auto e = analysis::estimate({1, 2, 3, 4, 5});
  CHECK(e.n == 5);
  CHECK(e.mean == Approx(3.0));
  CHECK(e.sd == Approx(std::sqrt(2.5)));
  CHECK(e.half_width == Approx(2.776445 * std::sqrt(2.5) / std::sqrt(5.0)).epsilon(1e-6));
  auto one = analysis::estimate({7, NAN});
  CHECK(one.n == 1);
  CHECK(std::isnan(one.half_width));  // one sample: no interval, never a zero-width one
}

TEST_CASE("survival of gaps between original exits, by hand", "[analysis]") {
  std::vector<core::ExitEvent> exits = {{1.0, 0, Species::Original}, {1.5, 9, Species::Added},
                                        {2.0, 1, Species::Original}, {4.0, 2, Species::Original},
                                        {7.0, 3, Species::Original}, {7.2, 8, Species::Added},
                                        {11.0, 4, Species::Original}};
  auto gaps = analysis::original_gaps(exits);
  REQUIRE(gaps == std::vector<double>{1.0, 2.0, 3.0, 4.0});  // added exits in between do not split gaps
  auto p = analysis::survival(gaps, {0.0, 1.0, 2.0, 2.5, 4.0, 4.1});
  CHECK(p == std::vector<double>{1.0, 1.0, 0.75, 0.5, 0.25, 0.0});
}

TEST_CASE("avalanche sizes between clogs, by hand", "[analysis]") {
  // Gaps: 0.1 0.1 | 0.6 | 0.2 | 1.0 | 0.1 0.1 0.1 -> avalanches 3, 2, 4 (cut short by the end: left out).
  std::vector<core::ExitEvent> exits;
  int id = 0;
  for (double t : {1.0, 1.1, 1.2, 1.8, 2.0, 3.0, 3.1, 3.2, 3.3})
    exits.push_back({t, id++, Species::Original});
  exits[4].species = Species::Added;  // both species count
  CHECK(analysis::avalanche_sizes(exits, 0.5) == std::vector<double>{3, 2});
  CHECK(analysis::avalanche_sizes(exits, 0.15) == std::vector<double>{3, 1, 1});
  CHECK(analysis::avalanche_sizes(exits, 2.0).empty());  // never clogged: the only avalanche is cut short
  CHECK(analysis::avalanche_sizes({}, 0.5).empty());
  // A realization's avalanche count and mean size, within its analysed duration.
  core::Events ev;
  ev.exits = exits;
  auto m = analysis::measure(ev, 10.0, 0.5);
  CHECK(m.avalanches == 2);
  CHECK(m.avalanche_mean == Approx(2.5));
  m = analysis::measure(ev, 2.5, 0.5);  // the exits after 2.5 s are outside: {3} complete, {2} cut short
  CHECK(m.avalanches == 1);
  CHECK(m.avalanche_mean == Approx(3.0));
  m = analysis::measure(ev, 10.0, 2.0);
  CHECK(m.avalanches == 0);
  CHECK(std::isnan(m.avalanche_mean));
  // Pooled over a point's realizations: P(S >= s) at s = 1..largest, with the number pooled; points.csv
  // carries the mean over realizations of each one's mean size.
  std::vector<analysis::Run> runs(2);
  for (int k = 0; k < 2; ++k) {
    runs[k].source = "r" + std::to_string(k);
    runs[k].scene.seed = static_cast<std::uint64_t>(k + 1);
    runs[k].scene.duration = 10;
    runs[k].events = ev;
    if (k == 1) runs[k].events.exits.resize(4);  // gaps 0.1 0.1 | 0.6: {3} complete, then {1} cut short
    runs[k].m = analysis::measure(runs[k].events, 10.0, 0.5);
  }
  REQUIRE(runs[1].m.avalanches == 1);
  auto points = analysis::aggregate(runs);
  REQUIRE(points.size() == 1);
  CHECK(points[0].avalanche_mean.mean == Approx((2.5 + 3.0) / 2));
  CHECK(points[0].avalanche_mean.n == 2);
  // Pooled sizes {3, 2, 3}: P(S >= 1) = P(S >= 2) = 1, P(S >= 3) = 2/3.
  const std::string csv = analysis::pooled_avalanches_csv(points);
  CHECK_THAT(csv,
             Catch::Matchers::StartsWith("size_ratio,chi,mu,kick_impulse_max,size,survival,avalanches\n"));
  CHECK_THAT(csv, Catch::Matchers::Contains(",1,1,3\n") && Catch::Matchers::Contains(",2,1,3\n") &&
                      Catch::Matchers::Contains(",3,0.666666667,3\n"));
  CHECK(std::count(csv.begin(), csv.end(), '\n') == 4);  // header + s = 1, 2, 3 (the largest)
  CHECK_THAT(analysis::points_csv(points),
             Catch::Matchers::Contains(",avalanche_mean,avalanche_mean_ci95,avalanche_end\n") &&
                 Catch::Matchers::EndsWith(",gaps\n"));
}

TEST_CASE("avalanches held: only clogs the outlet held end one, transient stops do not, by hand",
          "[analysis]") {
  // Exits at 1.0 1.1 1.2 | 1.8 2.0 | 3.0 3.1 3.2 3.3 with clogs (gaps >= 0.5 s) after 1.2 (it resumed by
  // itself: spontaneous) and after 2.0 (the rule removed its arch). Held: 5 (1.0-2.0, through the transient
  // stop), then 4 cut short by the run's end: left out. Gaps: 3 and 2.
  std::vector<core::ExitEvent> exits;
  int id = 0;
  for (double t : {1.0, 1.1, 1.2, 1.8, 2.0, 3.0, 3.1, 3.2, 3.3})
    exits.push_back({t, id++, Species::Original});
  const std::vector<core::ClogEvent> clogs = {{1.2, 1.8, core::ClogEnd::Spontaneous, false, NAN, {}},
                                              {2.0, 3.0, core::ClogEnd::Rule, true, NAN, {}}};
  using analysis::AvalancheEnd;
  CHECK(analysis::avalanche_sizes(exits, clogs, 0.5, AvalancheEnd::Held) == std::vector<double>{5});
  CHECK(analysis::avalanche_sizes(exits, clogs, 0.5, AvalancheEnd::Gaps) == std::vector<double>{3, 2});
  // A clog still standing at the run's end closes the avalanche before it; clogs.csv's millisecond times
  // still find their exits.
  std::vector<core::ClogEvent> run_end = clogs;
  run_end.push_back({3.3004, 10.0, core::ClogEnd::RunEnd, true, NAN, {}});
  CHECK(analysis::avalanche_sizes(exits, run_end, 0.5, AvalancheEnd::Held) == std::vector<double>{5, 4});
  core::Events ev;
  ev.exits = exits;
  ev.clogs = run_end;
  const auto m = analysis::measure(ev, 10.0, 0.5, 1, AvalancheEnd::Held);
  CHECK(m.avalanches == 2);
  CHECK(m.avalanche_mean == Approx(4.5));
  CHECK(m.clogs_spontaneous == 1);
  // Per protocol: held without a drive, gaps with kicks or a vibrating container.
  core::Scene s;
  s.kick_impulse_max = 0;
  CHECK(analysis::avalanche_end_for(s) == AvalancheEnd::Held);
  s.vibration_gamma = 1.0;
  CHECK(analysis::avalanche_end_for(s) == AvalancheEnd::Gaps);
  s.vibration_gamma = 0;
  s.kick_impulse_max = 5e-5;
  CHECK(analysis::avalanche_end_for(s) == AvalancheEnd::Gaps);
}

TEST_CASE("per-realization measurements from synthetic events", "[analysis]") {
  core::Events ev;
  for (int i = 0; i < 30; ++i)
    ev.exits.push_back({0.5 + i, i, i % 3 == 0 ? Species::Added : Species::Original});
  ev.arches.push_back({10,
                       5,
                       {1, 2, 3},
                       {Species::Original, Species::Added, Species::Original},
                       {},
                       core::ArchMethod::ContactPath,
                       {},
                       {}});
  ev.arches.push_back({20,
                       5,
                       {4, 5, 6, 7},
                       {Species::Added, Species::Added, Species::Original, Species::Original},
                       {},
                       core::ArchMethod::ContactPath,
                       {},
                       {}});
  ev.clogs = {{5, 10, core::ClogEnd::Rule, true, NAN, {}},
              {12, 13, core::ClogEnd::Vibration, true, NAN, {}},
              {14, 15, core::ClogEnd::Spontaneous, false, NAN, {}},
              {15, 20, core::ClogEnd::Rule, true, NAN, {}}};
  auto m = analysis::measure(ev, 30.0, 0.5);
  CHECK(m.exits == 30);
  CHECK(m.exits_added == 10);
  CHECK(m.q == Approx(1.0));
  CHECK(m.q_tilde == Approx(20.0 / 30.0));
  CHECK(m.chi_eff == Approx(1.0 / 3.0));
  CHECK(m.long_arches_per_minute == Approx(4.0));
  CHECK(m.added_per_long_arch == Approx(1.5));
  CHECK(m.members_per_long_arch == Approx(3.5));
  CHECK(m.clogs_rule == 2);
  CHECK(m.fraction_broken_by_vibration == Approx(1.0 / 3.0));
  CHECK(m.avalanches ==
        29);  // every 1 s gap is a clog at 0.5 s: 29 avalanches of one disk, the last cut short
  CHECK(m.avalanche_mean == Approx(1.0));
}

TEST_CASE("event files round-trip, truncated or corrupted ones are refused with file and line",
          "[analysis][io]") {
  namespace fs = std::filesystem;
  fs::path dir = fs::temp_directory_path() / "siloscope_test_events";
  fs::remove_all(dir);
  fs::create_directories(dir);
  core::Events ev;
  ev.exits = {{0.25, 3, Species::Original}, {0.5, 7, Species::Added}};
  ev.clogs = {{0.5, 5.5, core::ClogEnd::Rule, true, NAN, {}}};
  ev.arches.push_back({5.5,
                       5.0,
                       {4, 9},
                       {Species::Original, Species::Added},
                       {0.3, 0.15, 170.0},
                       core::ArchMethod::ContactPath,
                       {},
                       {}});
  io::write_events(dir, ev);
  core::Events back = io::read_events(dir);
  REQUIRE(back.exits.size() == 2);
  CHECK(back.exits[1].species == Species::Added);
  CHECK(back.clogs[0].ended_by == core::ClogEnd::Rule);
  CHECK(back.arches[0].ids == std::vector<int>{4, 9});
  CHECK(back.arches[0].geometry.max_angle_deg == Approx(170.0));

  auto expect_error = [&](const std::string& file, const std::string& text, const std::string& needle) {
    std::ofstream(dir / file, std::ios::trunc) << text;
    try {
      io::read_events(dir);
      FAIL("no error for " << file);
    } catch (const core::InputError& e) {
      CHECK_THAT(e.what(), Catch::Matchers::Contains(needle));
    }
    io::write_events(dir, ev);
  };
  expect_error("exits.csv", "t_s,id,species\n0.25,3,original\n0.5,7,add", "exits.csv:3: truncated");
  expect_error("exits.csv", "t_s,id,species\n0.25,3,original\n0.5,x,added\n", "exits.csv:3: id = 'x'");
  expect_error("exits.csv", "time,id\n", "exits.csv:1: header");
  expect_error("clogs.csv", "start_s,end_s,duration_s,ended_by,arrested\n1,2,1,magic,0\n",
               "ended_by = 'magic'");
  fs::remove(dir / "arches.csv");
  CHECK_THROWS_AS(io::read_events(dir), core::InputError);
}

namespace {
analysis::Run synthetic_run(double chi, std::uint64_t seed, double q_tilde) {
  analysis::Run r;
  r.source = "run-chi" + std::to_string(chi) + "-s" + std::to_string(seed);
  r.scene.chi = chi;
  r.scene.seed = seed;
  r.scene.duration = 10;
  // q_tilde originals per second, plus (for chi > 0) one added exit per second.
  for (int i = 0; i < static_cast<int>(q_tilde * 10); ++i)
    r.events.exits.push_back({i * 0.1, i, Species::Original});
  r.m = analysis::measure(r.events, r.scene.duration, r.scene.clog_min_gap);
  return r;
}
}  // namespace

TEST_CASE("aggregation groups by point, computes Q~/Q_p and refuses mixed scenes and duplicate seeds",
          "[analysis]") {
  std::vector<analysis::Run> runs = {synthetic_run(0.0, 1, 2.0), synthetic_run(0.0, 2, 4.0),
                                     synthetic_run(0.4, 1, 3.0), synthetic_run(0.4, 2, 3.0)};
  auto points = analysis::aggregate(runs);
  REQUIRE(points.size() == 2);
  CHECK(points[0].q_tilde.mean == Approx(3.0));
  CHECK(points[0].q_tilde_over_qp.mean == Approx(1.0));
  CHECK(points[1].q_tilde_over_qp.mean == Approx(1.0));
  CHECK(points[1].q_tilde.half_width == Approx(0.0));
  CHECK(points[0].q_tilde.half_width == Approx(12.706205 * std::sqrt(2.0) / std::sqrt(2.0)).epsilon(1e-5));

  auto dup = runs;
  dup.push_back(synthetic_run(0.4, 2, 1.0));
  CHECK_THROWS_WITH(analysis::aggregate(dup), Catch::Matchers::Contains("seed 2 appears twice"));
  auto mixed = runs;
  mixed[3].scene.dt = 5e-4;
  CHECK_THROWS_WITH(analysis::aggregate(mixed), Catch::Matchers::Contains("dt = 0.0005"));
  // Two keys differ (as a grid of a species' count changes n_total with it): the hint names both, and
  // following it aggregates.
  mixed[3].scene.n_total = 300;
  CHECK_THROWS_WITH(analysis::aggregate(mixed),
                    Catch::Matchers::Contains("analyze with --by dt --by n_total)") ||
                        Catch::Matchers::Contains("analyze with --by n_total --by dt)"));
  CHECK(analysis::aggregate(mixed, {}, {"dt", "n_total"}).size() == 3);
  CHECK_THROWS_AS(analysis::aggregate({}), core::InputError);
}

TEST_CASE("drain.csv: the jamming probability with Wilson's interval, by hand", "[analysis]") {
  // Four drains of one point: three jammed (after 10, 20 and 30 exits), one emptied; and a point of two
  // emptied drains. Wilson's 95% interval for 3 of 4 is [0.3006, 0.9544]; for 0 of 2 [0, 0.6576].
  std::vector<analysis::Run> runs;
  const char* outcome[] = {"jammed", "jammed", "emptied", "jammed", "emptied", "emptied"};
  for (int k = 0; k < 6; ++k) {
    runs.push_back(synthetic_run(k < 4 ? 0.0 : 0.4, static_cast<std::uint64_t>(k + 1), 2.0));
    runs.back().m.drain_outcome = outcome[k];
    runs.back().m.exits = 10 * (k + 1);
    runs.back().m.drain_end_s = k + 1.0;
  }
  CHECK(analysis::drain_csv(analysis::aggregate(runs)) != "");
  const std::string csv = analysis::drain_csv(analysis::aggregate(runs));
  CAPTURE(csv);
  std::istringstream in(csv);
  std::string header, a, b;
  std::getline(in, header), std::getline(in, a), std::getline(in, b);
  CHECK(header.find("n_runs,n_emptied,n_jammed,n_draining,jam_probability,jam_probability_lo95") !=
        std::string::npos);
  CHECK(a.find(",4,1,3,0,0.75,0.300") != std::string::npos);
  CHECK(a.find(",0.954") != std::string::npos);
  CHECK(a.find(",0.75,0.300") != std::string::npos);
  CHECK(a.find(",23.3333333,") != std::string::npos);  // exits before the jam: 10, 20, 40
  CHECK(b.find(",2,2,0,0,0,0,0.657") != std::string::npos);
  for (auto& r : runs) r.m.drain_outcome.clear();
  CHECK(analysis::drain_csv(analysis::aggregate(runs)).empty());  // no drain: no file
}

TEST_CASE("with several kick strengths, Q~/Q_p compares each point with the pure system at its own kick",
          "[analysis]") {
  std::vector<analysis::Run> runs;
  for (double kick : {5e-5, 5e-3}) {
    const double scale = kick > 1e-3 ? 2.0 : 1.0;  // the stronger kick doubles every rate
    for (std::uint64_t seed : {1, 2}) {
      auto pure = synthetic_run(0.0, seed, 2.0 * scale + 0.5 * static_cast<double>(seed));
      auto mixed = synthetic_run(0.4, seed, 3.0 * scale);
      pure.scene.kick_impulse_max = mixed.scene.kick_impulse_max = kick;
      runs.push_back(pure);
      runs.push_back(mixed);
    }
  }
  auto points = analysis::aggregate(runs);
  REQUIRE(points.size() == 4);
  for (const auto& p : points) {
    INFO("kick " << p.scene.kick_impulse_max << " chi " << p.scene.chi);
    const double scale = p.scene.kick_impulse_max > 1e-3 ? 2.0 : 1.0;
    CHECK(p.q_p.mean == Approx(2.0 * scale + 0.75));
    if (p.scene.chi > 0) CHECK(p.q_tilde_over_qp.mean == Approx(3.0 * scale / (2.0 * scale + 0.75)));
  }
  const std::string csv = analysis::points_csv(points);
  CHECK_THAT(csv,
             Catch::Matchers::Contains("kick_dv_over_sqrt_g_ro") && Catch::Matchers::Contains("q_p_per_s"));
}

TEST_CASE("Kolmogorov-Smirnov distance and its 5% critical value", "[analysis]") {
  CHECK(analysis::ks_distance({1, 2, 3}, {1, 2, 3}) == 0.0);
  CHECK(analysis::ks_distance({1, 2, 3}, {4, 5, 6}) == 1.0);
  // F_a jumps to 0.5 at 1, F_b is still 0 until 2: the largest gap is 0.5.
  CHECK(analysis::ks_distance({1, 3}, {2, 4}) == Approx(0.5));
  CHECK(std::isnan(analysis::ks_distance({}, {1.0})));
  CHECK(analysis::ks_critical_95(100, 100) == Approx(1.358 * std::sqrt(200.0 / 10000)));
}

TEST_CASE("Kaplan-Meier survival: the empirical survival without censoring, by hand with it", "[analysis]") {
  // No censoring: S(t) = the fraction of durations longer than t.
  auto km = analysis::kaplan_meier({{1, true}, {2, true}, {3, true}, {4, true}});
  CHECK(analysis::survival_at(km, 0.5) == 1.0);
  CHECK(analysis::survival_at(km, 2.0) == Approx(0.5));
  CHECK(analysis::survival_at(km, 4.0) == 0.0);
  // 1 event, 2 censored at 2 (still at risk just before 2), 1 event at 3: S(1) = 3/4, S(3) = 3/4 * 0 = 0
  // after the last one at risk goes.
  km = analysis::kaplan_meier({{1, true}, {2, false}, {2, false}, {3, true}});
  CHECK(analysis::survival_at(km, 1.5) == Approx(0.75));
  CHECK(analysis::survival_at(km, 2.5) == Approx(0.75));  // censoring drops the risk set, not S
  CHECK(analysis::survival_at(km, 3.0) == Approx(0.0));
  for (const auto& s : km) CHECK((s.lo <= s.s && s.s <= s.hi));
}

TEST_CASE("normal distribution, p-values and Holm's correction", "[analysis]") {
  CHECK(analysis::normal_quantile(0.975) == Approx(1.959963985).epsilon(1e-9));
  CHECK(analysis::normal_quantile(0.5) == Approx(0.0).margin(1e-12));
  CHECK(analysis::normal_cdf(analysis::normal_quantile(0.01)) == Approx(0.01).epsilon(1e-9));
  // A difference equal to its 95% half-width has p = 0.05; none without an interval; tiny p do not round
  // to 0 (erfc, not 1 - Phi).
  CHECK(analysis::two_sided_p(0.3, 0.3) == Approx(0.05).epsilon(1e-9));
  CHECK(analysis::two_sided_p(1.0, INFINITY) == 1.0);
  CHECK(analysis::two_sided_p(1.0, NAN) == 1.0);
  CHECK(analysis::two_sided_p(12.0, 1.0) > 0);
  CHECK(analysis::two_sided_p(12.0, 1.0) < 1e-30);
  // Holm: 0.01 <= 0.05/3 passes, then 0.02 <= 0.05/2 passes, then 0.04 <= 0.05 passes; with 0.03 in the
  // second place instead, 0.03 > 0.025 stops there and the rest fail too.
  CHECK(analysis::holm({0.04, 0.01, 0.02}) == std::vector<bool>{true, true, true});
  CHECK(analysis::holm({0.04, 0.01, 0.03}) == std::vector<bool>{false, true, false});
  CHECK(analysis::holm({0.2}) == std::vector<bool>{false});
  CHECK(analysis::holm({}).empty());
}

TEST_CASE("quantiles and the bootstrap over realizations", "[analysis]") {
  CHECK(analysis::quantile({3, 1, 2, NAN, 4}, 0.5) == Approx(2.5));
  CHECK(analysis::quantile({3, 1, 2, 4}, 0.0) == 1);
  CHECK(analysis::quantile({3, 1, 2, 4}, 1.0) == 4);
  CHECK(std::isnan(analysis::quantile({}, 0.5)));
  // The mean of 40 samples 0..39 (sd 11.7): the bootstrap's spread of the mean is sd / sqrt(n) = 1.85, and a
  // fixed seed gives the same rounds again.
  std::vector<double> v;
  for (int i = 0; i < 40; ++i) v.push_back(i);
  auto mean_of = [&](const std::vector<std::vector<size_t>>& idx) {
    double s = 0;
    for (size_t i : idx[0]) s += v[i];
    return s / static_cast<double>(idx[0].size());
  };
  const auto a = analysis::bootstrap({v.size()}, 4000, 7, mean_of);
  const auto b = analysis::bootstrap({v.size()}, 4000, 7, mean_of);
  CHECK(a == b);
  double m = 0, s = 0;
  for (double x : a) m += x;
  m /= static_cast<double>(a.size());
  for (double x : a) s += (x - m) * (x - m);
  s = std::sqrt(s / static_cast<double>(a.size() - 1));
  CHECK(m == Approx(19.5).margin(0.15));
  CHECK(s == Approx(std::sqrt((40.0 * 40 - 1) / 12 / 40)).epsilon(0.06));
  CHECK(analysis::bootstrap({v.size()}, 10, 8, mean_of) != analysis::bootstrap({v.size()}, 10, 7, mean_of));
}

TEST_CASE("per-realization lapse counts agree with the pooled survival", "[analysis]") {
  core::Events ev;
  for (double t : {0.1, 0.3, 1.6, 1.7, 4.0, 4.2}) ev.exits.push_back({t, 1, Species::Original});
  ev.exits.push_back({1.65, 2, Species::Added});  // does not cut a lapse of the originals
  const auto m = analysis::measure(ev, 10.0, 0.5, 2);
  // Original gaps: 0.2, 1.3, 0.1, 2.3, 0.2: five lapses, two of at least 1 s, one of at least 2 s.
  CHECK(m.lapses == 5);
  CHECK(m.lapses_ge_1s == 2);
  CHECK(m.lapses_ge_2s == 1);
  const auto s = analysis::survival(analysis::original_gaps(ev.exits), {1.0, 2.0});
  CHECK(s[0] == Approx(2.0 / 5));
  CHECK(s[1] == Approx(1.0 / 5));
}
