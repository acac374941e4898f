// Issue 12: nothing a user owns is lost, and no number is silently wrong. Each case failed on the main of
// 2026-11-21 (see docs/robustness.md) and must keep passing.
#include <catch2/catch.hpp>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <thread>
#include <vector>

#include "helpers.h"
#include "io/trajectory.h"

namespace fs = std::filesystem;
using test::cli;
using test::kBin;
using test::kScene;
using test::slurp;
using test::temp_dir;

namespace {
const std::string kShort = " --duration 1 --set settle_time=2 --quiet";

// Replace the first occurrence of `from` in a file.
void edit(const fs::path& p, const std::string& from, const std::string& to) {
  std::string s = slurp(p);
  const auto at = s.find(from);
  REQUIRE(at != std::string::npos);
  s.replace(at, from.size(), to);
  std::ofstream(p, std::ios::binary) << s;
}

// A pid that is certainly not running: a child that has exited and been reaped.
pid_t dead_pid() {
  pid_t pid = fork();
  if (pid == 0) _exit(0);
  int status = 0;
  waitpid(pid, &status, 0);
  return pid;
}
}  // namespace

TEST_CASE("force replaces only what siloscope wrote, a user's files and directories are refused and kept",
          "[trust][app]") {
  fs::path d = temp_dir("force");
  // A directory of earlier runs (no metadata.toml of its own), a thesis file, a foreign movie.
  REQUIRE(cli("run " + kScene + kShort + " --out " + (d / "runs" / "a").string()).code == 0);
  std::ofstream(d / "mythesis") << "\\chapter{Clogs}\n";
  std::ofstream(d / "talk.mp4") << "not a siloscope movie";

  auto r = cli("run " + kScene + kShort + " --force --out " + (d / "runs").string());
  CHECK(r.code == 2);
  CHECK_THAT(r.output, Catch::Matchers::Contains((d / "runs").string()) &&
                           Catch::Matchers::Contains("siloscope did not write"));
  CHECK(fs::exists(d / "runs" / "a" / "metadata.toml"));

  r = cli("run " + kScene + kShort + " --force --out " + (d / "mythesis").string());
  CHECK(r.code == 2);
  CHECK_THAT(r.output, Catch::Matchers::Contains("regular file"));
  CHECK(slurp(d / "mythesis") == "\\chapter{Clogs}\n");

  r = cli("record " + kScene + kShort + " --size 64x48 --force --out " + (d / "talk").string());
  CHECK(r.code == 2);
  CHECK_THAT(r.output, Catch::Matchers::Contains("not a siloscope MP4"));
  CHECK(slurp(d / "talk.mp4") == "not a siloscope movie");
  CHECK_FALSE(fs::exists(d / "talk"));

  std::ofstream(d / "notes.csv") << "my,own,table\n";
  r = cli("bench arch --csv " + (d / "notes.csv").string());
  CHECK(r.code == 2);
  CHECK(slurp(d / "notes.csv") == "my,own,table\n");

  r = cli("figures " + (d / "runs").string() + " --force --out " + (d / "runs").string());
  CHECK(r.code == 2);
  CHECK(fs::exists(d / "runs" / "a" / "metadata.toml"));

  // A run directory siloscope wrote is replaced, and only once the new one is complete.
  const std::string before = slurp(d / "runs" / "a" / "metadata.toml");
  REQUIRE(cli("run " + kScene + kShort + " --seed 5 --force --out " + (d / "runs" / "a").string()).code == 0);
  CHECK(slurp(d / "runs" / "a" / "metadata.toml") != before);
  CHECK_THAT(slurp(d / "runs" / "a" / "metadata.toml"), Catch::Matchers::Contains("\nseed = 5 "));
}

TEST_CASE("one writer per output: a second process aiming at the same --out is refused at once",
          "[trust][app]") {
  fs::path d = temp_dir("busy");
  const std::string out = (d / "r").string();
  pid_t pid = fork();
  if (pid == 0) {
    if (!freopen("/dev/null", "w", stdout) || !freopen("/dev/null", "w", stderr)) _exit(126);
    execl(kBin.c_str(), kBin.c_str(), "run", kScene.c_str(), "--duration", "300", "--out", out.c_str(),
          "--quiet", static_cast<char*>(nullptr));
    _exit(127);
  }
  // The partial directory appears only after the lock is taken.
  const std::string partial = out + ".partial-" + std::to_string(pid);
  for (int i = 0; i < 400 && !fs::exists(partial); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(25));
  REQUIRE(fs::exists(partial));
  const auto t0 = std::chrono::steady_clock::now();
  auto r = cli("run " + kScene + kShort + " --out " + out);
  const double waited = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  CHECK(r.code == 75);
  CHECK_THAT(r.output, Catch::Matchers::Contains("another siloscope process is writing"));
  CHECK(waited < 5.0);  // refused before any simulation (a settled 1 s run takes longer than the refusal)
  r = cli("record " + kScene + kShort + " --size 64x48 --out " + out);
  CHECK(r.code == 75);
  CHECK(test::signal_and_wait(pid, SIGINT) != 0);
  CHECK_FALSE(fs::exists(out));
  CHECK_FALSE(fs::exists(out + ".mp4"));
}

TEST_CASE("leftovers of a dead process are removed by the next run to the same output, with a line saying so",
          "[trust][app]") {
  fs::path d = temp_dir("leftovers");
  const pid_t gone = dead_pid();
  const fs::path dead_dir = d / ("r.partial-" + std::to_string(gone));
  fs::create_directories(dead_dir);
  std::ofstream(d / "r.mp4.partial") << "half a movie";
  std::ofstream(d / "r.partial-notes") << "a user's file with a similar name";
  auto r = cli("record " + kScene + kShort + " --size 64x48 --out " + (d / "r").string());
  REQUIRE(r.code == 0);
  CHECK_THAT(r.output, Catch::Matchers::Contains("removed " + dead_dir.string()));
  CHECK_THAT(r.output, Catch::Matchers::Contains("r.mp4.partial"));
  CHECK_FALSE(fs::exists(dead_dir));
  CHECK_FALSE(fs::exists(d / "r.mp4.partial"));
  CHECK(fs::exists(d / "r.partial-notes"));
  CHECK(fs::exists(d / "r.mp4"));
  // An old output that a dead process moved aside before its replacement arrived is put back, not removed:
  // it may be the only copy. The new run then finds it in place and, without --force, leaves it alone.
  const fs::path dead_old = d / ("q.old-" + std::to_string(gone));
  fs::create_directories(dead_old);
  std::ofstream(dead_old / "exits.csv") << "t_s,id,species\n";
  r = cli("run " + kScene + kShort + " --quiet --out " + (d / "q").string());
  CHECK(r.code == 2);
  CHECK_THAT(r.output, Catch::Matchers::Contains("put " + dead_old.string() + " back") &&
                           Catch::Matchers::Contains("already exists"));
  CHECK_FALSE(fs::exists(dead_old));
  CHECK(test::slurp(d / "q" / "exits.csv") == "t_s,id,species\n");
}

TEST_CASE("analyze counts a run for the time it covered and names what it leaves out",
          "[trust][app][analysis][heavy]") {
  fs::path d = temp_dir("analyze_cover");
  for (int seed : {1, 2, 3})
    REQUIRE(cli("run " + kScene + " --duration 6 --set settle_time=2 --quiet --seed " + std::to_string(seed) +
                " --out " + (d / "runs" / ("s" + std::to_string(seed))).string())
                .code == 0);
  // s2 as if it had been stopped after 2 s (what record writes when interrupted), s3 as if unhealthy.
  edit(d / "runs" / "s2" / "metadata.toml", "[run]\n", "[run]\ninterrupted = true\nsimulated_s = 2.0\n");
  edit(d / "runs" / "s3" / "metadata.toml", "warnings = 0", "warnings = 3");
  // Edited by hand, the two no longer match their manifests (analyze would refuse them as changed); without
  // a manifest they are read as runs made before manifests were written.
  test::strip_manifest(d / "runs" / "s2");
  test::strip_manifest(d / "runs" / "s3");
  auto r = cli("analyze " + (d / "runs").string() + " --out " + (d / "a").string());
  REQUIRE(r.code == 0);
  CHECK_THAT(r.output,
             Catch::Matchers::Contains("leaves out " + (d / "runs" / "s2").string() + ": interrupted"));
  CHECK_THAT(r.output,
             Catch::Matchers::Contains("leaves out " + (d / "runs" / "s3").string() + ": unhealthy"));
  CHECK_THAT(slurp(d / "a" / "metadata.toml"), Catch::Matchers::Contains("runs = 1\n"));

  r = cli("analyze " + (d / "runs").string() + " --include-interrupted --include-unhealthy --out " +
          (d / "b").string());
  REQUIRE(r.code == 0);
  const std::string rows = slurp(d / "b" / "realizations.csv");
  // s2's row: 2 s of discharge, its exits in those 2 s divided by 2 s.
  std::istringstream in(rows);
  std::string line, header;
  std::getline(in, header);
  int found = 0;
  while (std::getline(in, line)) {
    if (line.find("/s2") == std::string::npos) continue;
    ++found;
    CHECK_THAT(line, Catch::Matchers::Contains(",2,"));  // duration_s column
  }
  CHECK(found == 1);
  CHECK_THAT(slurp(d / "b" / "metadata.toml"), Catch::Matchers::Contains("runs = 3\n"));

  // A run stopped before the aperture opened is refused, not counted as Q = 0.
  edit(d / "runs" / "s2" / "metadata.toml", "simulated_s = 2.0", "simulated_s = 0.0");
  r = cli("analyze " + (d / "runs").string() + " --include-interrupted --out " + (d / "c").string());
  CHECK(r.code == 2);
  CHECK_THAT(r.output, Catch::Matchers::Contains("before the aperture opened"));
  CHECK_FALSE(fs::exists(d / "c"));
}

TEST_CASE("scene and campaign readers accept only regular files of bounded size", "[trust][app]") {
  fs::path d = temp_dir("scene_kinds");
  REQUIRE(cli("run " + kScene + kShort + " --seed 7 --out " + (d / "s7").string()).code == 0);
  auto r = cli("run " + (d / "s7").string() + kShort + " --out " + (d / "again").string());
  CHECK(r.code == 2);
  CHECK_THAT(r.output,
             Catch::Matchers::Contains("is a directory") &&
                 Catch::Matchers::Contains("did you mean " + (d / "s7" / "metadata.toml").string()));
  CHECK_FALSE(fs::exists(d / "again"));
  r = cli("run /dev/zero" + kShort + " --out " + (d / "z").string());
  CHECK(r.code == 2);
  CHECK_THAT(r.output, Catch::Matchers::Contains("regular file"));
  std::ofstream(d / "big.toml") << std::string(2u << 20, '#');
  r = cli("run " + (d / "big.toml").string() + kShort + " --out " + (d / "b").string());
  CHECK(r.code == 2);
  CHECK_THAT(r.output, Catch::Matchers::Contains("too large"));
  r = cli("sweep " + (d / "s7").string() + " --dry-run");
  CHECK(r.code == 2);
  CHECK_THAT(r.output, Catch::Matchers::Contains("is a directory"));
}

TEST_CASE("metadata round-trips any output path, quotes included", "[trust][app]") {
  fs::path d = temp_dir("quote_path");
  const fs::path odd = d / "a \"quoted\" \\ name";
  REQUIRE(cli("run " + kScene + kShort + " --out '" + odd.string() + "'").code == 0);
  auto r = cli("run '" + (odd / "metadata.toml").string() + "' --quiet --out " + (d / "again").string());
  REQUIRE(r.code == 0);
  CHECK(slurp(d / "again" / "exits.csv") == slurp(odd / "exits.csv"));
}

TEST_CASE("integer options refuse negative and out-of-range values with the allowed range", "[trust][app]") {
  fs::path d = temp_dir("ints");
  auto r = cli("run " + kScene + kShort + " --seed -1 --out " + (d / "r").string());
  CHECK(r.code == 2);
  CHECK_THAT(r.output,
             Catch::Matchers::Contains("--seed") && Catch::Matchers::Contains("whole number from 0"));
  r = cli("run " + kScene + kShort + " --seed 18446744073709551616 --out " + (d / "r").string());
  CHECK(r.code == 2);
  r = cli("record " + kScene + kShort + " --fps -30 --out " + (d / "m").string());
  CHECK(r.code == 2);
  CHECK_THAT(r.output, Catch::Matchers::Contains("1 to 240"));
  r = cli("sweep " + std::string(SILOSCOPE_SOURCE_DIR) +
          "/assets/campaigns/quick.toml --workers 0 --dry-run");
  CHECK(r.code == 2);
  CHECK_FALSE(fs::exists(d / "r"));
  CHECK_FALSE(fs::exists(d / "m"));
}

TEST_CASE("conflicting flags are refused with both named, and output lost on a full device is an error",
          "[trust][app]") {
  fs::path d = temp_dir("conflicts");
  // A camera move decides every frame's view: a fixed camera beside it would be ignored silently.
  auto r = cli("record " + kScene + kShort + " --camera outlet --camera-path 0:hopper,1:outlet --out " +
               (d / "m").string());
  CHECK(r.code == 2);
  CHECK_THAT(r.output, Catch::Matchers::Contains("--camera") && Catch::Matchers::Contains("--camera-path"));
  CHECK_FALSE(fs::exists(d / "m"));
  CHECK_FALSE(fs::exists(d / "m.mp4"));
  // What a command prints must arrive: /dev/full takes nothing.
  CHECK(test::sh(kBin + " scene " + kScene + " > /dev/full 2> " + (d / "err.txt").string()) == 1);
  CHECK_THAT(test::slurp(d / "err.txt"), Catch::Matchers::Contains("cannot write to standard output"));
  CHECK(test::sh(kBin + " scene " + kScene + " > /dev/null") == 0);
  // --help and --version too (CLI11 printed them and the program exited 0 whatever the write did).
  for (const char* args : {" --help", " run --help", " --version"}) {
    INFO(args);
    CHECK(test::sh(kBin + args + " > /dev/full 2> " + (d / "err.txt").string()) == 1);
    CHECK_THAT(test::slurp(d / "err.txt"), Catch::Matchers::Contains("cannot write to standard output"));
    CHECK(test::sh(kBin + args + " > /dev/null") == 0);
  }
}

TEST_CASE("keys that do nothing in this scene and species rounded to no grains are warned about, by origin",
          "[trust][app][heavy]") {
  auto r = cli("scene " + kScene +
               " --set obstacle_height=0.5 --set chi=0.001 --set kick_impulse_max=0 --set "
               "kick_period=0.5");
  CHECK(r.code == 0);  // the scene still runs: a warning, not an error
  CHECK_THAT(r.output, Catch::Matchers::Contains("warning: obstacle_height (--set) does nothing: obstacle = "
                                                 "\"none\"") &&
                           Catch::Matchers::Contains("warning: kick_period (--set) does nothing") &&
                           Catch::Matchers::Contains("species added has no grains: chi = 0.001 of n_total"));
  // The shipped scenes give none.
  for (const char* f :
       {"paper", "paper-vibrated", "pure", "pentagons", "silo-obstacle", "three-species", "vibrated-silo"}) {
    r = cli("scene " + std::string(SILOSCOPE_SOURCE_DIR) + "/assets/scenes/" + f + ".toml");
    CHECK(r.code == 0);
    CHECK(r.output.find("warning") == std::string::npos);
  }
}

TEST_CASE("scene FILE makes the checks run makes before its discharge: it settles the grains",
          "[trust][app]") {
  // A settle too short for the grains to fall below the top: run refuses it after settling, and so does
  // scene.
  auto r = cli("scene " + kScene + " --set settle_time=0.05");
  CHECK(r.code == 2);
  CHECK_THAT(r.output, Catch::Matchers::Contains("after settle_time = 0.05 s grain") &&
                           Catch::Matchers::Contains("is still above the top of the container"));
  r = cli("scene " + kScene + " --set settle_time=0.05 --no-settle");
  CHECK(r.code == 0);
  CHECK_THAT(r.output, Catch::Matchers::Contains("is valid (not settled: --no-settle)"));
  r = cli("scene " + kScene);
  CHECK(r.code == 0);
  CHECK_THAT(r.output, Catch::Matchers::Contains("is valid (deposited and settled as run does"));
}

TEST_CASE("an output path is resolved as the kernel resolves it: links first, then '..'", "[trust][app]") {
  fs::path d = temp_dir("kernel_paths");
  fs::create_directories(d / "sub" / "deep");
  fs::create_symlink("sub/deep", d / "lnk");
  // d/x is a siloscope run of its own: a lexical reading of d/lnk/../x would replace it with --force.
  REQUIRE(cli("run " + kScene + kShort + " --out " + (d / "x").string()).code == 0);
  const std::string before = slurp(d / "x" / "exits.csv");
  REQUIRE(cli("run " + kScene + kShort + " --seed 9 --out " + (d / "lnk" / ".." / "x").string() + " --force")
              .code == 0);
  CHECK(fs::exists(d / "sub" / "x" / "exits.csv"));  // where the kernel puts d/lnk/../x
  CHECK(slurp(d / "x" / "exits.csv") == before);     // untouched
}
