// Campaigns: grid expansion, seeds, resuming after an interruption, workers, and the GNU parallel path.
#include <catch2/catch.hpp>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <thread>

#include "app/services/campaign.h"
#include "core/error.h"
#include "core/physics.h"
#include "helpers.h"

namespace fs = std::filesystem;

namespace {
using test::kBin;
using test::sh;
using test::slurp;
const std::string kScenes = std::string(SILOSCOPE_SOURCE_DIR) + "/assets/scenes/";
fs::path temp_dir(const std::string& name) {
  return test::temp_dir("sweep_" + name);
}

// A tiny campaign: 3 points x `n` realizations of 1 s (after 2 s of settling).
fs::path tiny_campaign(const fs::path& dir, int n, const std::string& extra = "") {
  std::ofstream(dir / "short.toml") << "settle_time = 2.0\n";
  std::ofstream(dir / "c.toml")
      << "name = \"tiny\"\nscene = \"short.toml\"\nseed = 7\nrealizations = " << n
      << "\nduration = 1.0\n[grid]\nsize_ratio = [0.4, 1.0]\n[[points]]\nchi = 0.0\n"
      << extra;
  return dir / "c.toml";
}

long count_runs(const fs::path& results) {
  long n = 0;
  if (!fs::exists(results / "runs")) return 0;
  for (const auto& e : fs::recursive_directory_iterator(results / "runs"))
    n += e.path().filename() == "metadata.toml";
  return n;
}
}  // namespace

TEST_CASE("a campaign grid expands to the product of its lists plus its extra points", "[campaign]") {
  fs::path d = temp_dir("grid");
  std::ofstream(d / "c.toml")
      << "scene = \"" << kScenes << "paper.toml\"\nrealizations = 3\nduration = 10\n"
      << "[grid]\nsize_ratio = [0.4, 0.6]\nmu = [0.0, 0.5, 1.0]\n[[points]]\nchi = 0.0\n";
  app::Campaign c = app::load_campaign((d / "c.toml").string());
  REQUIRE(c.points.size() == 7);
  CHECK(c.name == "c");
  CHECK(c.points[0].label == "mu=0,size_ratio=0.4");
  CHECK(c.points[5].scene.mu == 1.0);
  CHECK(c.points[5].scene.size_ratio == 0.6);
  CHECK(c.points[6].scene.chi == 0.0);
  CHECK(c.points[6].scene.duration == 10);
  // Seeds: distinct across points and realizations, and a function of the point's label, not its position.
  std::set<std::uint64_t> seeds;
  for (size_t p = 0; p < c.points.size(); ++p)
    for (int k = 0; k < 3; ++k) seeds.insert(c.realization_seed(p, k));
  CHECK(seeds.size() == 21);
  std::ofstream(d / "swapped.toml")
      << "scene = \"" << kScenes << "paper.toml\"\nrealizations = 3\nduration = 10\n"
      << "[[points]]\nchi = 0.0\n[grid]\nsize_ratio = [0.6, 0.4]\nmu = [1.0, 0.5, 0.0]\n";
  app::Campaign s = app::load_campaign((d / "swapped.toml").string());
  CHECK(s.points.back().label == "chi=0");
  CHECK(s.realization_seed(s.points.size() - 1, 2) == c.realization_seed(6, 2));
}

TEST_CASE("the dipole force ratio sets mu per size ratio", "[campaign]") {
  core::Scene s;
  s.size_ratio = 0.4;
  s.mu = core::mu_for_force_ratio(s, 10.0);
  // model.md: contact force over weight is about 2.0 mu^2 at r = 0.4.
  CHECK(s.mu * s.mu * 1.97 == Approx(10.0).epsilon(0.02));
  s.size_ratio = 0.2;
  CHECK(core::mu_for_force_ratio(s, 126.0) == Approx(1.0).epsilon(0.02));
}

TEST_CASE("bad campaigns are refused with the file and the key", "[campaign]") {
  fs::path d = temp_dir("bad");
  auto error_of = [&](const std::string& text) {
    std::ofstream(d / "c.toml", std::ios::trunc)
        << "scene = \"" << kScenes << "paper.toml\"\nrealizations = 2\n"
        << text;
    try {
      app::load_campaign((d / "c.toml").string());
    } catch (const core::InputError& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  CHECK_THAT(error_of(""), Catch::Matchers::Contains("grid is empty"));
  CHECK_THAT(error_of("[grid]\nsize_ratio = []\n"),
             Catch::Matchers::Contains("grid.size_ratio must be a non-empty list"));
  CHECK_THAT(error_of("[grid]\nmagnetism = [1.0]\n"), Catch::Matchers::Contains("unknown key 'magnetism'"));
  CHECK_THAT(error_of("[grid]\nsize_ratio = [0.1]\n"), Catch::Matchers::Contains("size_ratio = 0.1"));
  CHECK_THAT(error_of("[grid]\nmu = [0.5, 0.5]\n"), Catch::Matchers::Contains("duplicates an earlier point"));
  CHECK_THAT(error_of("[[points]]\nmu = 0.0\n[[points]]\nchi=0.4\n"),
             Catch::Matchers::Contains("duplicates"));
}

TEST_CASE("sweeps: identical results with 1 and 2 workers, and through GNU parallel",
          "[campaign][app][heavy]") {
  fs::path d = temp_dir("workers");
  fs::path c = tiny_campaign(d, 2);
  REQUIRE(sh(kBin + " sweep " + c.string() + " --workers 1 --quiet --results " + (d / "one").string()) == 0);
  REQUIRE(sh(kBin + " sweep " + c.string() + " --workers 2 --quiet --results " + (d / "two").string()) == 0);
  CHECK(count_runs(d / "one") == 6);
  const std::string points = slurp(d / "one" / "analysis" / "points.csv");
  CHECK(points.find("q_tilde_over_qp") != std::string::npos);
  CHECK(slurp(d / "two" / "analysis" / "points.csv") == points);
  CHECK(slurp(d / "one" / "runs" / "p001" / "r001" / "exits.csv") ==
        slurp(d / "two" / "runs" / "p001" / "r001" / "exits.csv"));
  // The job list, run by GNU parallel from the results directory, gives the same aggregate.
  REQUIRE(sh(kBin + " sweep " + c.string() + " --emit-jobs --results " + (d / "gnu").string() +
             " > /dev/null") == 0);
  CHECK(fs::exists(d / "gnu" / "jobs.slurm"));
  REQUIRE(sh("cd " + (d / "gnu").string() + " && parallel --will-cite -j 2 < jobs.txt") == 0);
  REQUIRE(sh(kBin + " analyze " + (d / "gnu" / "runs").string() + " --out " +
             (d / "gnu" / "analysis").string() + " > /dev/null") == 0);
  CHECK(slurp(d / "gnu" / "analysis" / "points.csv") == points);
  // A results directory of another campaign is refused and left alone.
  fs::path other = tiny_campaign(d, 2, "[[points]]\nchi = 0.2\n");
  CHECK(sh(kBin + " sweep " + other.string() + " --quiet --results " + (d / "one").string() +
           " 2> /dev/null") == 2);
  CHECK(count_runs(d / "one") == 6);
  // The same campaign with more realizations extends it: the first ones are kept, not rerun.
  const auto first_exits = slurp(d / "one" / "runs" / "p001" / "r001" / "exits.csv");
  fs::path more = tiny_campaign(d, 3);
  CHECK(sh(kBin + " sweep " + more.string() + " --quiet --up-to 3 --results " + (d / "one").string()) == 0);
  CHECK(count_runs(d / "one") == 9);
  CHECK(slurp(d / "one" / "runs" / "p001" / "r001" / "exits.csv") == first_exits);
}

TEST_CASE("a sweep killed mid-way resumes without losing or duplicating a realization",
          "[campaign][app][heavy]") {
  fs::path d = temp_dir("resume");
  fs::path c = tiny_campaign(d, 4);  // 12 realizations
  for (int sig : {SIGINT, SIGKILL}) {
    fs::path r = d / (sig == SIGINT ? "int" : "kill");
    pid_t pid = fork();
    REQUIRE(pid >= 0);
    if (pid == 0) {
      execl(kBin.c_str(), kBin.c_str(), "sweep", c.c_str(), "--workers", "2", "--quiet", "--results",
            r.c_str(), static_cast<char*>(nullptr));
      _exit(127);
    }
    for (int i = 0; i < 400 && count_runs(r) < 3; ++i)
      std::this_thread::sleep_for(std::chrono::milliseconds(25));
    kill(pid, sig);
    int status = 0;
    waitpid(pid, &status, 0);
    CAPTURE(sig);
    CHECK(count_runs(r) < 12);  // it really was cut short
    REQUIRE(sh(kBin + " sweep " + c.string() + " --workers 2 --quiet --results " + r.string()) == 0);
    CHECK(count_runs(r) == 12);
    long partial = 0;
    for (const auto& e : fs::recursive_directory_iterator(r / "runs"))
      partial += e.path().filename().string().find(".partial-") != std::string::npos;
    CHECK(partial == 0);
  }
  // Both resumed campaigns equal an uninterrupted one.
  REQUIRE(sh(kBin + " sweep " + c.string() + " --workers 2 --quiet --results " + (d / "whole").string()) ==
          0);
  const std::string whole = slurp(d / "whole" / "analysis" / "points.csv");
  CHECK(slurp(d / "int" / "analysis" / "points.csv") == whole);
  CHECK(slurp(d / "kill" / "analysis" / "points.csv") == whole);
}

TEST_CASE("a resumed sweep refuses a finished realization that was cut, edited or lost its manifest",
          "[campaign][app][heavy]") {
  fs::path d = temp_dir("resume_check");
  fs::path c = tiny_campaign(d, 1);  // 3 realizations
  const fs::path r = d / "r";
  const std::string sweep = kBin + " sweep " + c.string() + " --quiet --results " + r.string();
  REQUIRE(sh(sweep) == 0);
  const fs::path run = r / "runs" / "p000" / "r000";
  const fs::path keep = d / "keep";
  fs::copy(run, keep, fs::copy_options::recursive);
  auto refused = [&](const std::string& says) {
    auto out = test::cli("sweep " + c.string() + " --quiet --results " + r.string());
    INFO(out.output);
    CHECK(out.code == 2);
    CHECK_THAT(out.output,
               Catch::Matchers::Contains(says) && Catch::Matchers::Contains("remove " + run.string()));
    CHECK(fs::exists(run / "metadata.toml"));  // left as it is: the user decides
    fs::remove_all(run);
    fs::copy(keep, run, fs::copy_options::recursive);
  };
  std::string exits = slurp(run / "exits.csv");
  std::ofstream(run / "exits.csv", std::ios::binary) << exits.substr(0, exits.size() - 7);
  refused("exits.csv is");
  exits[exits.size() - 2] = exits[exits.size() - 2] == '1' ? '2' : '1';
  std::ofstream(run / "exits.csv", std::ios::binary) << exits;
  refused("differs from what siloscope wrote");
  fs::remove(run / "manifest.toml");
  refused("no manifest.toml, though its metadata.toml says siloscope wrote one");
  fs::copy_file(r / "runs" / "p001" / "r000" / "clogs.csv", run / "clogs.csv",
                fs::copy_options::overwrite_existing);
  refused("clogs.csv");
  CHECK(sh(sweep) == 0);  // restored: resumes (nothing left to do) and analyses
}

TEST_CASE("a realization the health monitor refuses is recorded once, not rerun, and counted by analyze",
          "[campaign][app][heavy]") {
  fs::path d = temp_dir("refused");
  // Two points: the literal kick, and one so strong (0.5 N s) that the first kick throws a disk out.
  std::ofstream(d / "short.toml") << "settle_time = 1.0\n";
  std::ofstream(d / "c.toml") << "name = \"refusals\"\nscene = \"short.toml\"\nseed = 3\nrealizations = 2\n"
                                 "duration = 1.0\n[grid]\nkick_impulse_max = [5e-05, 0.5]\n";
  const fs::path res = d / "res";
  auto r = test::cli("sweep " + (d / "c.toml").string() + " --workers 2 --results " + res.string());
  CHECK(r.code == 0);  // a refusal is an outcome, recorded; not a failure of the sweep
  CHECK_THAT(r.output, Catch::Matchers::Contains("2 realizations refused by the health monitor"));
  CHECK(count_runs(res) == 2);
  std::vector<fs::path> markers;
  for (const auto& e : fs::recursive_directory_iterator(res / "runs"))
    if (e.path().string().find(".refused.toml") != std::string::npos) markers.push_back(e.path());
  REQUIRE(markers.size() == 2);
  const std::string marker = slurp(markers.front());
  CHECK_THAT(marker, Catch::Matchers::Contains("# reason: unstable integration") &&
                         Catch::Matchers::Contains("kick_impulse_max = 0.5"));
  // The refused point has no finished run, so no row; analyze says so.
  CHECK_THAT(r.output,
             Catch::Matchers::Contains("2 refused realizations belong to points with no finished run"));
  // Resuming runs nothing again: the refusals are settled.
  r = test::cli("sweep " + (d / "c.toml").string() + " --workers 2 --no-analyze --results " + res.string());
  CHECK(r.code == 0);
  CHECK_THAT(r.output, Catch::Matchers::Contains("4 finished (2 refused by the health monitor") &&
                           Catch::Matchers::Contains("0 to run"));
  // A refusal recorded at a point that has finished runs is counted there: n_refused.
  std::string text = slurp(markers.front());
  const size_t at = text.find("kick_impulse_max = 0.5");
  text.replace(at, std::string("kick_impulse_max = 0.5").size(), "kick_impulse_max = 5e-05");
  const size_t seed = text.find("\nseed = ");
  text = text.substr(0, seed) + "\nseed = 987654321\n";
  std::ofstream(res / "runs" / "extra.refused.toml") << text;
  fs::remove(markers[0]);
  fs::remove(markers[1]);
  REQUIRE(test::cli("analyze " + (res / "runs").string() + " --out " + (d / "an").string()).code == 0);
  const std::string points = slurp(d / "an" / "points.csv");
  const std::string header = points.substr(0, points.find('\n'));
  const std::string row =
      points.substr(header.size() + 1, points.find('\n', header.size() + 1) - header.size() - 1);
  auto column = [](const std::string& line, int k) {
    std::stringstream s(line);
    std::string cell;
    for (int i = 0; i <= k; ++i) std::getline(s, cell, ',');
    return cell;
  };
  int k = 0;
  while (column(header, k) != "n_refused") REQUIRE(++k < 60);
  CHECK(column(row, k) == "1");
  CHECK(column(row, 6) == "2");  // n_runs: the two that finished
  // A plain run refused the same way exits 3 and writes nothing, no record either (that is for campaign
  // jobs).
  r = test::cli("run " + (d / "short.toml").string() +
                " --duration 1 --set kick_impulse_max=0.5 --quiet --out " + (d / "alone").string());
  CHECK(r.code == 3);
  CHECK_THAT(r.output, Catch::Matchers::Contains("unstable integration"));
  CHECK_FALSE(fs::exists(d / "alone"));
  CHECK_FALSE(fs::exists(d / "alone.refused.toml"));
  CHECK_THAT(slurp(d / "an" / "metadata.toml"), Catch::Matchers::Contains("runs_refused = 1"));
}

TEST_CASE("sweep --status says how far a campaign got and what is left, and writes nothing",
          "[campaign][app][heavy]") {
  fs::path d = temp_dir("status");
  fs::path c = tiny_campaign(d, 2);  // 3 points x 2
  const fs::path res = d / "res";
  // No results yet: one line, exit 2, nothing made.
  auto r = test::cli("sweep " + c.string() + " --status --results " + res.string());
  CHECK(r.code == 2);
  CHECK_THAT(r.output, Catch::Matchers::Contains("no results of campaign tiny there yet"));
  CHECK_FALSE(fs::exists(res));
  REQUIRE(sh(kBin + " sweep " + c.string() + " --up-to 1 --quiet --no-analyze --results " + res.string()) ==
          0);
  // A realization a killed run left half-written (its process is gone), and one the health monitor refused.
  pid_t gone = fork();
  if (gone == 0) _exit(0);
  waitpid(gone, nullptr, 0);
  fs::create_directories(res / "runs" / "p000" / ("r001.partial-" + std::to_string(gone)));
  std::ofstream(res / "runs" / "p002" / "r001.refused.toml") << "# reason: test\n";
  auto listing = [&] {
    std::string all;
    for (const auto& e : fs::recursive_directory_iterator(res)) all += e.path().string() + "\n";
    return all;
  };
  // The estimate is the median wall time of the finished runs (read from their metadata) times what is left,
  // shared by the workers. Give the three runs known times: 1000, 1800 and 3600 s.
  const std::vector<std::string> runs = {"p000/r000", "p001/r000", "p002/r000"};
  const double walls[] = {1000, 1800, 3600};
  for (size_t i = 0; i < runs.size(); ++i) {
    const fs::path meta = res / "runs" / runs[i] / "metadata.toml";
    std::string text = slurp(meta), out;
    std::istringstream lines(text);
    int replaced = 0;
    for (std::string line; std::getline(lines, line);) {
      if (line.rfind("wall_time_settle_s = ", 0) == 0) line = "wall_time_settle_s = 0.0", ++replaced;
      if (line.rfind("wall_time_discharge_s = ", 0) == 0)
        line = "wall_time_discharge_s = " + std::to_string(walls[i]), ++replaced;
      out += line + "\n";
    }
    REQUIRE(replaced == 2);
    std::ofstream(meta) << out;
  }
  const std::string before = listing();
  r = test::cli("sweep " + c.string() + " --status --workers 2 --results " + res.string());
  INFO(r.output);
  CHECK(r.code == 0);
  CHECK_THAT(r.output, Catch::Matchers::Contains("3 points x 2 realizations of 1 s"));
  CHECK_THAT(r.output, Catch::Matchers::Contains("settled   4 of 6 (66.7%): 3 finished, 1 refused"));
  CHECK_THAT(r.output, Catch::Matchers::Contains("running   0, and 1 left by killed runs"));
  CHECK_THAT(r.output, Catch::Matchers::Contains("per point 1 to 2 settled; fewest at p000"));
  CHECK_THAT(r.output, Catch::Matchers::Contains("refused   p002: 1"));
  CHECK_THAT(r.output, Catch::Matchers::Contains("median 1800.0 s wall per realization") &&
                           Catch::Matchers::Contains("3 finished runs"));
  CHECK_THAT(r.output, Catch::Matchers::Contains(
                           "left      2 realizations: about 60 min of one core, 30 min on 2 workers"));
  r = test::cli("sweep " + c.string() + " --status --workers 4 --results " + res.string());
  CHECK_THAT(r.output, Catch::Matchers::Contains("15 min on 4 workers"));
  CHECK(listing() == before);  // read only: the dead run's leftovers go when a sweep starts, not here
  // --up-to counts against the first K realizations.
  r = test::cli("sweep " + c.string() + " --status --up-to 1 --results " + res.string());
  CHECK_THAT(r.output, Catch::Matchers::Contains("settled   3 of 3 (100.0%)") &&
                           Catch::Matchers::Contains("complete  every realization is settled"));
  // Another campaign's directory is refused.
  fs::path other = tiny_campaign(d, 2, "[[points]]\nchi = 0.2\n");
  r = test::cli("sweep " + other.string() + " --status --results " + res.string());
  CHECK(r.code == 2);
  CHECK_THAT(r.output, Catch::Matchers::Contains("holds another campaign"));
  // The results' own copy cut short: named as the results' copy, not as the campaign file given.
  const std::string stamp = slurp(res / "campaign.toml");
  std::ofstream(res / "campaign.toml") << stamp.substr(0, 40);
  r = test::cli("sweep " + c.string() + " --status --results " + res.string());
  CHECK(r.code == 2);
  CHECK_THAT(r.output, Catch::Matchers::Contains("its copy of the campaign does not parse (" +
                                                 (res / "campaign.toml").string() + ":"));
  std::ofstream(res / "campaign.toml") << stamp;
}

TEST_CASE("figures draws what the grid allows, avalanche sizes included, and names what it skipped",
          "[campaign][app][heavy]") {
  fs::path d = temp_dir("figures");
  std::ofstream(d / "short.toml") << "settle_time = 2.0\n";
  std::ofstream(d / "c.toml") << "name = \"fig\"\nscene = \"short.toml\"\nseed = 5\nrealizations = 2\n"
                                 "duration = 10.0\n[grid]\nsize_ratio = [0.4, 1.0]\n[[points]]\nchi = 0.0\n";
  const fs::path res = d / "res";
  REQUIRE(sh(kBin + " sweep " + (d / "c.toml").string() + " --workers 2 --quiet --results " + res.string()) ==
          0);
  // Each point has complete avalanches (ended by a clog) in 2 x 10 s at the literal kick (of 636 realizations
  // of the paper campaign none had its first clog later than 10 s; the median is 0.3 s), so a mean size in
  // points.csv and a distribution.
  const std::string points = slurp(res / "analysis" / "points.csv");
  CHECK_THAT(points, Catch::Matchers::Contains(",avalanche_mean,avalanche_mean_ci95"));
  const std::string av = slurp(res / "analysis" / "avalanches.csv");
  for (const char* prefix : {"\n0.4,0.4,", "\n1.0,0.4,", "\n0.4,0.0,"})
    CHECK_THAT(av, Catch::Matchers::Contains(std::string(prefix) + "0.0,5e-05,1,1,"));
  auto r = test::cli("figures " + res.string());
  INFO(r.output);
  CHECK(r.code == 0);
  for (const char* name : {"qtilde_vs_r", "survival", "avalanches", "avalanche_size_vs_r"})
    CHECK(fs::file_size(res / "figures" / (std::string(name) + ".png")) > 10000);
  CHECK_THAT(r.output, Catch::Matchers::Contains("skipped qtilde_vs_mu: the grid has one dipole strength"));
  CHECK_FALSE(fs::exists(res / "figures" / "qtilde_vs_mu.png"));

  // One size ratio left (r = 1.0 removed), and a point no figure shows (chi = 0.25 at r = 1.0): the skipped
  // figure is not written, the point is named.
  fs::copy(res / "analysis", d / "one_r", fs::copy_options::recursive);
  std::istringstream rows(points);
  std::string line, kept, moved;
  while (std::getline(rows, line)) {
    if (line.rfind("1.0,0.4,", 0) == 0) {
      moved = "1.0,0.25," + line.substr(8);
      continue;
    }
    kept += line + "\n";
  }
  REQUIRE(!moved.empty());
  std::ofstream(d / "one_r" / "points.csv") << kept << moved << "\n";
  // A table made by hand has no manifest (an analysis' table edited under its manifest is refused:
  // tests/python/test_readers.py).
  test::strip_manifest(d / "one_r");
  r = test::cli("figures " + (d / "one_r").string() + " --out " + (d / "f1").string());
  INFO(r.output);
  CHECK(r.code == 0);
  CHECK_THAT(r.output, Catch::Matchers::Contains("skipped qtilde_vs_r: the grid has one size ratio"));
  CHECK_FALSE(fs::exists(d / "f1" / "qtilde_vs_r.png"));
  CHECK_THAT(r.output,
             Catch::Matchers::Contains("not drawn: the point r = 1, chi = 0.25, mu = 0 fits no figure"));
}

TEST_CASE("emit-jobs groups realizations into array tasks of --task-minutes and at most --max-array of them",
          "[campaign][app][heavy]") {
  fs::path d = temp_dir("array");
  fs::path c = tiny_campaign(d, 2);
  // Without a finished realization there is no wall time to fill minutes with: the limit on tasks decides.
  REQUIRE(sh(kBin + " sweep " + c.string() + " --emit-jobs --max-array 4 --results " + (d / "cold").string() +
             " > " + (d / "cold.txt").string()) == 0);
  CHECK_THAT(slurp(d / "cold.txt"), Catch::Matchers::Contains("array:         3 tasks of 2 realizations") &&
                                        Catch::Matchers::Contains("no finished realization"));
  // A first pass measures the wall time; the rest goes into at most 2 tasks, run as SLURM runs them (its
  // array variables), and the aggregate equals a local sweep's.
  REQUIRE(sh(kBin + " sweep " + c.string() + " --up-to 1 --quiet --results " + (d / "arr").string()) == 0);
  REQUIRE(sh(kBin + " sweep " + c.string() + " --emit-jobs --task-minutes 0.1 --max-array 2 --results " +
             (d / "arr").string() + " > " + (d / "emit.txt").string()) == 0);
  const std::string emit = slurp(d / "emit.txt");
  INFO(emit);
  CHECK_THAT(emit, Catch::Matchers::Contains("3 jobs written"));
  // T tasks of K: K fills 6 s at the measured median (at least 2 so that T <= 2), T * K covers the 3 jobs.
  const auto at = emit.find("array:");
  REQUIRE(at != std::string::npos);
  int tasks = 0, per = 0;
  double minutes = 0, median = 0;
  REQUIRE(std::sscanf(emit.c_str() + at,
                      "array: %d tasks of %d realizations (about %lf min each at the median %lf", &tasks,
                      &per, &minutes, &median) == 4);
  CHECK(tasks <= 2);
  CHECK(tasks * per >= 3);
  CHECK((tasks - 1) * per < 3);
  CHECK(per >= 2);
  CHECK((per == 2 || per * median <= 6.0 * 1.01));  // the most that fit 6 s (the median printed to 3 digits)
  CHECK((per + 1) * median > 6.0 * 0.99);
  CHECK_THAT(slurp(d / "arr" / "jobs.slurm"), Catch::Matchers::Contains("per=" + std::to_string(per) + "\n"));
  for (int task = 1; task <= tasks; ++task)
    REQUIRE(sh("cd " + (d / "arr").string() + " && SLURM_ARRAY_TASK_ID=" + std::to_string(task) +
               " bash jobs.slurm") == 0);
  CHECK(count_runs(d / "arr") == 6);
  REQUIRE(sh(kBin + " analyze " + (d / "arr" / "runs").string() + " --out " +
             (d / "arr" / "analysis").string() + " --force > /dev/null") == 0);
  REQUIRE(sh(kBin + " sweep " + c.string() + " --quiet --results " + (d / "local").string()) == 0);
  CHECK(slurp(d / "arr" / "analysis" / "points.csv") == slurp(d / "local" / "analysis" / "points.csv"));
  // Options that only mean something for a job list are refused without it.
  CHECK(sh(kBin + " sweep " + c.string() + " --max-array 5 --results " + (d / "x").string() +
           " 2> /dev/null") == 2);
  // Bounds printed as written, not as CLI11's "0.100000 to 10000.000000".
  auto bad =
      test::cli("sweep " + c.string() + " --emit-jobs --task-minutes 0.01 --results " + (d / "y").string());
  CHECK(bad.code != 0);
  CHECK_THAT(bad.output,
             Catch::Matchers::Contains("--task-minutes: 0.01 is out of range; expected a number from "
                                       "0.1 to 10000 minutes"));
}

TEST_CASE("the committed paper figures are what the current figure script draws from the committed analysis",
          "[campaign][app][heavy]") {
  // One of each kind the figure script draws from the tidy tables: a curve over r, a curve over mu, a
  // survival; byte for byte (matplotlib's PNG output is deterministic here, and no version is drawn in).
  fs::path d = temp_dir("figures_again");
  const std::string pack = std::string(SILOSCOPE_SOURCE_DIR) + "/docs/campaigns/paper";
  REQUIRE(sh(kBin + " figures " + pack + "/analysis --out " + (d / "f").string() + " > /dev/null") == 0);
  for (const char* f : {"qtilde_vs_r.png", "qtilde_vs_mu.png", "survival.png", "avalanches.png"}) {
    INFO(f);
    CHECK(slurp(d / "f" / f) == slurp(fs::path(pack) / "figures" / f));
  }
}

TEST_CASE("a campaign gridding a species' count is analysed by that key alone (n_total follows it)",
          "[campaign][app]") {
  fs::path d = temp_dir("species_count");
  std::ofstream(d / "c.toml") << "name = \"count\"\nscene = \"" << SILOSCOPE_SOURCE_DIR
                              << "/assets/scenes/silo-obstacle.toml\"\nseed = 3\nrealizations = 1\n"
                                 "duration = 0.5\n[grid]\n\"species.beads.count\" = [100, 120]\n";
  REQUIRE(sh(kBin + " sweep " + (d / "c.toml").string() + " --quiet --results " + (d / "r").string()) == 0);
  const std::string points = slurp(d / "r" / "analysis" / "points.csv");
  CHECK(std::count(points.begin(), points.end(), '\n') == 3);  // the header and two points
  // A run copied in by hand under the campaign's runs/ is not counted as one of its realizations.
  fs::copy(d / "r" / "runs" / "p001" / "r000", d / "r" / "runs" / "p000" / "r001",
           fs::copy_options::recursive);
  auto copied = test::cli("analyze " + (d / "r" / "runs").string() + " --out " + (d / "a0").string() +
                          " --by species.beads.count");
  CHECK(copied.code == 2);
  CHECK_THAT(copied.output,
             Catch::Matchers::Contains("p000/r001 is not the campaign's realization runs/p000/r001") &&
                 Catch::Matchers::Contains("a run copied in by hand?"));
  fs::remove_all(d / "r" / "runs" / "p000" / "r001");
  // The message for runs mixed in two keys names both.
  auto r = test::cli("analyze " + (d / "r" / "runs").string() + " --out " + (d / "a").string());
  CHECK(r.code == 2);
  CHECK_THAT(r.output, Catch::Matchers::Contains("analyze with --by n_total --by species.beads.count)"));
}
