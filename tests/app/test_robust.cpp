// Faults the user did not cause: a full disk, a read-only place, SIGTERM. Nothing half-written under a final
// name, temporary files removed, earlier outputs intact.
#include <catch2/catch.hpp>

#include "siloscope_version.h"

#include <signal.h>
#include <sys/mount.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "helpers.h"

namespace fs = std::filesystem;
using Catch::Matchers::Contains;

namespace {
using test::cli;
using test::kBin;
using test::kScene;
using test::slurp;

// A small tmpfs, unmounted when the test ends. Needs root (CI and the developers' machines run as root).
struct SmallDisk {
  fs::path dir;
  bool mounted = false;
  SmallDisk(const std::string& name, const char* options)
      : dir(fs::temp_directory_path() / ("siloscope_disk_" + name)) {
    ::umount(dir.c_str());
    fs::remove_all(dir);
    fs::create_directories(dir);
    mounted = ::mount("tmpfs", dir.c_str(), "tmpfs", 0, options) == 0;
  }
  ~SmallDisk() {
    if (mounted) ::umount(dir.c_str());
  }
};
}  // namespace

TEST_CASE("a full disk during record: a clear error, no partial files, earlier outputs intact",
          "[robust][app][heavy]") {
  SmallDisk disk("full", "size=3m");
  if (!disk.mounted && ::geteuid() != 0) {
    WARN("not root: cannot mount a small tmpfs, the full-disk test does not run here");
    return;
  }
  REQUIRE(disk.mounted);
  // An earlier run on the same disk.
  REQUIRE(cli("run " + kScene + " --duration 1 --set settle_time=2 --quiet --out " +
              (disk.dir / "earlier").string())
              .code == 0);
  const std::string earlier = slurp(disk.dir / "earlier" / "exits.csv");
  // A recording far larger than what is left (the trajectory alone grows by 185 kB per simulated second).
  auto r = cli("record " + kScene + " --duration 60 --set settle_time=2 --size 640x360 --quiet --out " +
               (disk.dir / "big").string());
  CHECK(r.code == 1);
  CHECK_THAT(r.output, Contains("No space left on device"));
  std::vector<std::string> left;
  for (const auto& e : fs::directory_iterator(disk.dir)) left.push_back(e.path().filename().string());
  CHECK(left == std::vector<std::string>{"earlier"});
  CHECK(slurp(disk.dir / "earlier" / "exits.csv") == earlier);
  // Replacing the earlier run with --force when the new one cannot be written keeps the earlier one.
  r = cli("record " + kScene + " --duration 60 --set settle_time=2 --size 640x360 --quiet --force --out " +
          (disk.dir / "earlier").string());
  CHECK(r.code == 1);
  CHECK(slurp(disk.dir / "earlier" / "exits.csv") == earlier);
}

TEST_CASE("a read-only place: exit 2 before any work, naming the directory", "[robust][app]") {
  SmallDisk disk("ro", "size=1m");
  if (!disk.mounted && ::geteuid() != 0) {
    WARN("not root: cannot mount a read-only tmpfs here");
    return;
  }
  REQUIRE(disk.mounted);
  REQUIRE(::mount("tmpfs", disk.dir.c_str(), "tmpfs", MS_REMOUNT | MS_RDONLY, "size=1m") == 0);
  for (const char* cmd : {"run", "record"}) {
    auto r =
        cli(std::string(cmd) + " " + kScene + " --duration 1 --quiet --out " + (disk.dir / "x").string());
    CAPTURE(cmd);
    CHECK(r.code == 2);
    CHECK_THAT(r.output, Contains(disk.dir.string()) && Contains("not writable"));
  }
}

TEST_CASE("SIGTERM during record also leaves a playable movie", "[robust][app]") {
  fs::path d = fs::temp_directory_path() / "siloscope_sigterm";
  fs::remove_all(d);
  fs::create_directories(d);
  const std::string out = (d / "cut").string();
  pid_t pid = test::start_long_record(out);
  REQUIRE(pid > 0);
  const int status = test::signal_and_wait(pid, SIGTERM);
  REQUIRE(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 130);
  CHECK(fs::exists(out + ".mp4"));
  CHECK_FALSE(fs::exists(out + ".mp4.partial"));
  CHECK(fs::exists(d / "cut" / "trajectory.sstraj"));
  CHECK(slurp(out + ".mp4").find("moov") < 200);
}

TEST_CASE("every subcommand answers --help and --version, wrong arguments give usage and exit 2",
          "[robust][app][heavy]") {
  for (const char* sub : {"run", "record", "inspect", "live", "sweep", "analyze", "figures", "gallery",
                          "timeline", "frame", "claims", "export", "scene", "bench sim", "bench arch",
                          "bench accuracy", "bench stability", "bench sweep"}) {
    CAPTURE(sub);
    auto h = cli(std::string(sub) + " --help");
    CHECK(h.code == 0);
    CHECK_THAT(h.output, Contains("Usage"));
    auto v = cli(std::string(sub) + " --version");
    CHECK(v.code == 0);
    CHECK_THAT(v.output, Contains(SILOSCOPE_VERSION));
    auto w = cli(std::string(sub) + " --no-such-option");
    CHECK(w.code == 2);
    CHECK_THAT(w.output, Contains("usage"));
  }
}
