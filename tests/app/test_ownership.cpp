// Issue 27: no flag can destroy a campaign, and no file is believed without a check. Each case failed on the
// main of 2026-11-24 (docs/robustness.md lists them).
#include <catch2/catch.hpp>

#include <chrono>
#include <filesystem>
#include <fstream>

#include "helpers.h"

namespace fs = std::filesystem;
using test::cli;
using test::kScene;
using test::slurp;
using test::temp_dir;

namespace {
const std::string kShort = " --duration 1 --set settle_time=2 --quiet";

// A run directory made by `run`, with its manifest.
fs::path make_run(const fs::path& where, int seed = 1) {
  REQUIRE(
      cli("run " + kScene + kShort + " --seed " + std::to_string(seed) + " --out " + where.string()).code ==
      0);
  REQUIRE(fs::exists(where / "manifest.toml"));
  return where;
}
}  // namespace

TEST_CASE("force replaces only siloscope's output of the same kind, holding what its manifest lists",
          "[trust][app][heavy]") {
  const fs::path d = temp_dir("ownership");
  const fs::path run = make_run(d / "run");
  // The same kind, untouched: replaced.
  CHECK(cli("run " + kScene + kShort + " --seed 2 --force --out " + run.string()).code == 0);
  // Another kind: analyze --force may not replace a run.
  auto r = cli("analyze " + run.string() + " --force --out " + run.string());
  CHECK(r.code == 2);
  CHECK(fs::exists(run / "exits.csv"));
  r = cli("analyze " + run.string() + " --out " + (d / "a").string());
  REQUIRE(r.code == 0);
  r = cli("run " + kScene + kShort + " --force --out " + (d / "a").string());
  CHECK(r.code == 2);
  CHECK_THAT(r.output, Catch::Matchers::Contains("siloscope's analysis output, not a run one"));
  CHECK(fs::exists(d / "a" / "points.csv"));
  // A file the user added inside a run: the run is no longer only siloscope's.
  std::ofstream(run / "notes.txt") << "my notes on this run\n";
  r = cli("run " + kScene + kShort + " --force --out " + run.string());
  CHECK(r.code == 2);
  CHECK_THAT(r.output, Catch::Matchers::Contains("notes.txt is not in its manifest"));
  CHECK(slurp(run / "notes.txt") == "my notes on this run\n");
  fs::remove(run / "notes.txt");
  // A file siloscope wrote, then changed (or truncated) by hand.
  std::ofstream(run / "summary.csv", std::ios::app) << "a line of mine\n";
  r = cli("run " + kScene + kShort + " --force --out " + run.string());
  CHECK(r.code == 2);
  CHECK_THAT(r.output, Catch::Matchers::Contains("summary.csv is"));
  // A directory with a copied siloscope metadata.toml but no manifest: not provably siloscope's.
  fs::create_directories(d / "mine");
  fs::copy_file(run / "metadata.toml", d / "mine" / "metadata.toml");
  std::ofstream(d / "mine" / "thesis.tex") << "\\chapter{}\n";
  r = cli("run " + kScene + kShort + " --force --out " + (d / "mine").string());
  CHECK(r.code == 2);
  CHECK_THAT(r.output, Catch::Matchers::Contains("without a manifest"));
  CHECK(fs::exists(d / "mine" / "thesis.tex"));
}

TEST_CASE("no command replaces a campaign's results or its own input", "[trust][app]") {
  const fs::path d = temp_dir("campaign_safe");
  // A campaign's results directory: campaign.toml, scenes/, runs/.
  const fs::path results = d / "results";
  make_run(results / "runs" / "p000" / "r000");
  fs::create_directories(results / "scenes");
  std::ofstream(results / "campaign.toml") << "name = \"x\"\n";
  for (const std::string& cmd : {"run " + kScene + kShort, "analyze " + (results / "runs").string()}) {
    auto r = cli(cmd + " --force --out " + results.string());
    CHECK(r.code == 2);
    // analyze names the input it would replace first; run names the campaign.
    CHECK_THAT(r.output, Catch::Matchers::Contains("a campaign's results") ||
                             Catch::Matchers::Contains("an input of this command"));
  }
  CHECK(fs::exists(results / "runs" / "p000" / "r000" / "exits.csv"));
  // analyze RUNS --out RUNS (or above them): refused before anything is read.
  auto r = cli("analyze " + (results / "runs").string() + " --force --out " + (results / "runs").string());
  CHECK(r.code == 2);
  CHECK_THAT(r.output, Catch::Matchers::Contains("an input of this command"));
  CHECK(fs::exists(results / "runs" / "p000" / "r000" / "exits.csv"));
}

TEST_CASE("output paths are resolved first: r1/../r1, a trailing slash, empty and '.'", "[trust][app]") {
  const fs::path d = temp_dir("paths");
  const fs::path run = make_run(d / "r1");
  // r1/../r1 is r1: replaced in place with --force, no leftover beside it.
  auto r = cli("run " + kScene + kShort + " --seed 3 --force --out " + (d / "r1" / ".." / "r1").string());
  CHECK(r.code == 0);
  size_t entries = 0;
  for (const auto& e : fs::directory_iterator(d)) entries += e.path().filename() != ".r1.lock";
  CHECK(entries == 1);
  CHECK_THAT(slurp(run / "metadata.toml"), Catch::Matchers::Contains("seed = 3"));
  r = cli("run " + kScene + kShort + " --seed 4 --force --out " + (d / "r1").string() + "/");
  CHECK(r.code == 0);
  // Names that are no new entry are refused before any simulation.
  for (const std::string& bad : {std::string("''"), std::string("."), (d / "..").string()}) {
    const auto t0 = std::chrono::steady_clock::now();
    r = cli("run " + kScene + " --duration 30 --quiet --out " + bad);
    CHECK(r.code == 2);
    CHECK(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() < 5.0);
  }
}

TEST_CASE("readers check what they read: a truncated file, a cut metadata.toml, a link to a device",
          "[trust][app][heavy]") {
  const fs::path d = temp_dir("readers");
  // exits.csv cut to half (at a line end, so the CSV itself still parses): the manifest names it.
  const fs::path a = make_run(d / "runs" / "a");
  std::string exits = slurp(a / "exits.csv");
  exits = exits.substr(0, exits.find('\n', exits.size() / 2) + 1);
  std::ofstream(a / "exits.csv", std::ios::binary) << exits;
  auto r = cli("analyze " + (d / "runs").string() + " --out " + (d / "an").string());
  CHECK(r.code == 2);
  CHECK_THAT(r.output,
             Catch::Matchers::Contains("exits.csv is") && Catch::Matchers::Contains("(truncated?)"));
  CHECK_FALSE(fs::exists(d / "an"));
  // A run without a manifest (as before manifests) whose metadata.toml lost its tail: not read with defaults.
  const fs::path b = make_run(d / "old" / "b");
  test::strip_manifest(b);
  std::string meta = slurp(b / "metadata.toml");
  std::ofstream(b / "metadata.toml", std::ios::binary) << meta.substr(0, meta.find("[derived]"));
  r = cli("analyze " + (d / "old").string() + " --out " + (d / "an2").string());
  CHECK(r.code == 2);
  CHECK_THAT(r.output, Catch::Matchers::Contains("no health.status") &&
                           Catch::Matchers::Contains("truncated or cut by hand"));
  // exits.csv a link to /dev/zero: refused at once instead of read forever.
  const fs::path c = make_run(d / "dev" / "c");
  test::strip_manifest(c);
  fs::remove(c / "exits.csv");
  fs::create_symlink("/dev/zero", c / "exits.csv");
  r = cli("analyze " + (d / "dev").string() + " --out " + (d / "an3").string());
  CHECK(r.code == 2);
  CHECK_THAT(r.output, Catch::Matchers::Contains("must be a regular file"));
  // An inspector script that is a device (on a run that has a trajectory to inspect).
  REQUIRE(cli("run " + kScene + kShort + " --trajectory-fps 10 --out " + (d / "t").string()).code == 0);
  r = cli("inspect " + (d / "t").string() + " --script /dev/zero");
  CHECK(r.code == 2);
  CHECK_THAT(r.output, Catch::Matchers::Contains("an inspector script must be a regular file"));
}

TEST_CASE("a campaign resumed after its scene changed is refused, a comment-only edit is accepted",
          "[trust][app][campaign]") {
  const fs::path d = temp_dir("resume_scene");
  std::ofstream(d / "base.toml") << "duration = 0.5\nsettle_time = 2.0\n";
  const std::string campaign =
      "name = \"tiny\"\nscene = \"base.toml\"\nseed = 7\nrealizations = 1\nduration = 0.5\n[grid]\n"
      "size_ratio = [0.4]\n";
  std::ofstream(d / "c.toml") << campaign;
  const std::string sweep = "sweep " + (d / "c.toml").string() + " --results " + (d / "res").string() +
                            " --workers 1 --quiet --no-analyze";
  REQUIRE(cli(sweep).code == 0);
  // A comment and another key order: the same campaign.
  std::ofstream(d / "c.toml") << "# tried again\nseed = 7\nname = \"tiny\"\nscene = \"base.toml\"\n"
                                 "realizations = 1\nduration = 0.5\n[grid]\nsize_ratio = [0.4]\n";
  auto r = cli(sweep);
  CHECK(r.code == 0);
  // The base scene edited between the sweep and its resume: the point would mix two scenes.
  std::ofstream(d / "base.toml") << "duration = 0.5\nsettle_time = 2.0\naperture = 0.35\n";
  r = cli(sweep);
  CHECK(r.code == 2);
  CHECK_THAT(r.output, Catch::Matchers::Contains("ran with aperture = 0.299, the campaign now gives 0.35"));
  // Another seed: another campaign.
  std::ofstream(d / "base.toml") << "duration = 0.5\nsettle_time = 2.0\n";
  std::ofstream(d / "c.toml") << campaign.substr(0, campaign.find("seed = 7")) + "seed = 8" +
                                     campaign.substr(campaign.find("seed = 7") + 8);
  r = cli(sweep);
  CHECK(r.code == 2);
  CHECK_THAT(r.output, Catch::Matchers::Contains("seed 7 there, 8 here"));
  // A results directory that is not this campaign's (a user's folder with files in it).
  fs::create_directories(d / "folder");
  std::ofstream(d / "folder" / "data.csv") << "1,2\n";
  std::ofstream(d / "c.toml") << campaign;
  r = cli("sweep " + (d / "c.toml").string() + " --results " + (d / "folder").string() + " --quiet");
  CHECK(r.code == 2);
  CHECK_THAT(r.output, Catch::Matchers::Contains("holds no campaign.toml"));
  CHECK(slurp(d / "folder" / "data.csv") == "1,2\n");
}

TEST_CASE("an existing file or foreign directory is named as what it is, and --force is not suggested",
          "[trust][app]") {
  const fs::path d = temp_dir("named");
  std::ofstream(d / "afile") << "mine\n";
  auto r = cli("run " + kScene + kShort + " --out " + (d / "afile").string());
  CHECK(r.code == 2);
  CHECK_THAT(r.output, Catch::Matchers::Contains("is a regular file, not a siloscope output directory"));
  CHECK_THAT(r.output, !Catch::Matchers::Contains("--force"));
  make_run(d / "run");
  r = cli("analyze " + (d / "run").string() + " --out " + (d / "run").string());
  CHECK(r.code == 2);
  r = cli("run " + kScene + kShort + " --out " + (d / "run").string());
  CHECK(r.code == 2);
  CHECK_THAT(r.output,
             Catch::Matchers::Contains("pass --force to replace it"));  // the same kind: it would work
  CHECK(slurp(d / "afile") == "mine\n");
}

TEST_CASE("figures on a points.csv that analyze did not write: one line, no traceback",
          "[trust][app][figures]") {
  const fs::path d = temp_dir("figures_foreign");
  fs::create_directories(d / "a");
  std::ofstream(d / "a" / "points.csv")
      << "size_ratio,chi,mu,kick_impulse_max,dipole_force_ratio,n_runs,q_tilde_per_s,q_tilde_per_s_ci95\n"
         "0.4,0.4,0,5e-05,0,5,2.0,0.1\n";
  auto r = cli("figures " + (d / "a").string() + " --out " + (d / "f").string());
  CHECK(r.code == 2);
  CHECK_THAT(r.output, Catch::Matchers::Contains("has no column"));
  CHECK_THAT(r.output, !Catch::Matchers::Contains("Traceback"));
  CHECK_FALSE(fs::exists(d / "f"));
}

TEST_CASE("edges: seeds TOML cannot hold, a misspelt command, a campaign given as a scene, an empty scene",
          "[trust][app]") {
  const fs::path d = temp_dir("edges");
  auto r = cli("run " + kScene + " --seed 9223372036854775808 --quiet --out " + (d / "s").string());
  CHECK(r.code == 2);
  CHECK_THAT(r.output, Catch::Matchers::Contains("9223372036854775807"));
  r = cli("run " + kScene + " --set seed=18446744073709551615 --quiet --out " + (d / "s").string());
  CHECK(r.code == 2);
  CHECK_FALSE(fs::exists(d / "s"));
  r = cli("run " + kScene + " --duration 0 --quiet --out " + (d / "z").string());
  CHECK(r.code == 2);
  CHECK_THAT(r.output, Catch::Matchers::Contains("--duration: duration = 0.0 is not allowed"));
  CHECK_FALSE(fs::exists(d / "z"));
  r = cli("rnu " + kScene);
  CHECK(r.code == 2);
  CHECK_THAT(r.output, Catch::Matchers::Contains("did you mean 'run'?"));
  r = cli("run " + std::string(SILOSCOPE_SOURCE_DIR) + "/assets/campaigns/quick.toml --quiet --out " +
          (d / "q").string());
  CHECK(r.code == 2);
  CHECK_THAT(r.output, Catch::Matchers::Contains("is a campaign file") && Catch::Matchers::Contains("sweep"));
  std::ofstream(d / "empty.toml") << "# nothing yet\n";
  r = cli("run " + (d / "empty.toml").string() + kShort + " --out " + (d / "e").string());
  CHECK(r.code == 0);
  CHECK_THAT(r.output, Catch::Matchers::Contains("sets no keys: running the built-in default scene"));
}

TEST_CASE("claims and figures refuse a points.csv with impossible counts", "[trust][app][claims]") {
  const fs::path d = temp_dir("bad_points");
  fs::create_directories(d / "analysis");
  std::ofstream(d / "analysis" / "points.csv")
      << "size_ratio,chi,mu,kick_impulse_max,dipole_force_ratio,n_runs,q_tilde_per_s,q_tilde_per_s_ci95\n"
         "0.4,0.4,0,5e-05,0,-3,2.0,0.1\n";
  auto r = cli("claims x=" + d.string() + " --out " + (d / "claims.md").string());
  CHECK(r.code == 2);
  CHECK_THAT(r.output, Catch::Matchers::Contains("points.csv:2: n_runs = -3 is not a whole number from 1"));
  CHECK_FALSE(fs::exists(d / "claims.md"));
}

TEST_CASE("every single-file writer: --force replaces its own untouched file, never one a user changed",
          "[trust][app][heavy]") {
  // Each writer's file gets a record beside it (.NAME.siloscope: size and hash); a line added to the file, or
  // a movie re-encoded, no longer matches it.
  const fs::path d = temp_dir("single_files");
  const std::string rec =
      "record " + kScene + " --duration 3 --size 64x48 --quiet --out " + (d / "r").string();
  REQUIRE(cli(rec).code == 0);
  const fs::path r = d / "r";
  struct Writer {
    std::string name, command;  // the command writes d/name
  };
  const std::vector<Writer> writers = {
      {"r.mp4", rec},
      {"e.xyz", "export " + r.string() + " --format xyz --out " + (d / "e.xyz").string()},
      {"e.csv", "export " + r.string() + " --format csv --out " + (d / "e.csv").string()},
      {"t.svg", "timeline " + r.string() + " --out " + (d / "t.svg").string()},
      {"f.svg", "filmstrip " + r.string() + " --clog 1 --times -0.5,0 --out " + (d / "f.svg").string()},
  };
  for (const auto& w : writers) {
    CAPTURE(w.command);
    const fs::path f = d / w.name;
    if (w.name != "r.mp4") REQUIRE(cli(w.command).code == 0);
    REQUIRE(fs::exists(f));
    CHECK(fs::exists(d / ("." + w.name + ".siloscope")));
    // Untouched: replaced.
    auto out = cli(w.command + " --force");
    CHECK(out.code == 0);
    // A line of the user's: refused, named, kept.
    std::ofstream(f, std::ios::app | std::ios::binary) << "\nmy note\n";
    const std::string mine = slurp(f);
    out = cli(w.command + " --force");
    CHECK(out.code == 2);
    CHECK_THAT(out.output, Catch::Matchers::Contains(w.name) &&
                               Catch::Matchers::Contains("changed since siloscope wrote it"));
    CHECK(slurp(f) == mine);
    // A file siloscope never recorded (written by an older version, or copied without its record).
    fs::remove(d / ("." + w.name + ".siloscope"));
    out = cli(w.command + " --force");
    CHECK(out.code == 2);
    CHECK_THAT(out.output, Catch::Matchers::Contains("no record that siloscope wrote it"));
    CHECK(slurp(f) == mine);
  }
}
