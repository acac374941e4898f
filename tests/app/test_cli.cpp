// The command line as a user meets it: exit codes, error messages, nothing half-written, reproducible
// outputs.
#include <catch2/catch.hpp>

#include "siloscope_version.h"

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fcntl.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "app/services/cli.h"
#include "helpers.h"

namespace fs = std::filesystem;

namespace {
using test::cli;
using test::kBin;
using test::kScene;
using test::slurp;
fs::path temp_dir(const std::string& name) {
  return test::temp_dir("cli_" + name);
}

// Nothing at all under `dir` except the entries listed.
bool only(const fs::path& dir, std::vector<std::string> names) {
  std::vector<std::string> found;
  for (const auto& e : fs::directory_iterator(dir)) found.push_back(e.path().filename().string());
  std::sort(found.begin(), found.end());
  std::sort(names.begin(), names.end());
  return found == names;
}
}  // namespace

TEST_CASE("help and version answer with exit code 0", "[app]") {
  for (const char* args : {"--help", "run --help", "record --help", "analyze --help", "bench sim --help"}) {
    auto r = cli(args);
    CAPTURE(args, r.output);
    CHECK(r.code == 0);
    CHECK_THAT(r.output, Catch::Matchers::Contains("Usage"));
  }
  for (const char* args : {"--version", "run --version", "record --version"}) {
    auto r = cli(args);
    CHECK(r.code == 0);
    CHECK_THAT(r.output, Catch::Matchers::Contains(SILOSCOPE_VERSION));
  }
}

TEST_CASE("wrong arguments give a usage line and exit code 2", "[app]") {
  auto r = cli("");
  CHECK(r.code == 2);
  CHECK_THAT(r.output, Catch::Matchers::Contains("usage"));
  r = cli("run");
  CHECK(r.code == 2);
  r = cli("fly away");
  CHECK(r.code == 2);
  r = cli("run " + kScene + " --out /tmp/x --seed notanumber");
  CHECK(r.code == 2);
}

TEST_CASE("bad scenes and outputs: one clear line, exit 2, nothing written", "[app]") {
  fs::path d = temp_dir("bad");
  auto r = cli("run " + kScene + " --set chi=2 --out " + (d / "out").string());
  CHECK(r.code == 2);
  CHECK_THAT(r.output, Catch::Matchers::Contains("chi = 2") && Catch::Matchers::Contains("[0, 1]"));
  r = cli("run " + (d / "missing.toml").string() + " --out " + (d / "out").string());
  CHECK(r.code == 2);
  CHECK_THAT(r.output, Catch::Matchers::Contains("missing.toml: cannot open"));
  std::ofstream(d / "typo.toml") << "size_ratio = 0.4\nsize_ration = 0.5\n";
  r = cli("run " + (d / "typo.toml").string() + " --out " + (d / "out").string());
  CHECK(r.code == 2);
  CHECK_THAT(r.output, Catch::Matchers::Contains("typo.toml:2: unknown key 'size_ration'"));
  r = cli("run " + kScene + " --duration -3 --out " + (d / "out").string());
  CHECK(r.code == 2);
  CHECK_THAT(r.output, Catch::Matchers::Contains("--duration"));
  r = cli("record " + kScene + " --size 641x480 --out " + (d / "movie").string());
  CHECK(r.code == 2);
  CHECK_THAT(r.output, Catch::Matchers::Contains("even"));
  r = cli("record " + kScene + " --camera sideways --out " + (d / "movie").string());
  CHECK(r.code == 2);
  CHECK_THAT(r.output, Catch::Matchers::Contains("--camera: camera 'sideways'"));
  std::ofstream(d / "file") << "x";
  r = cli("run " + kScene + " --out " + (d / "file" / "sub").string());
  CHECK(r.code == 2);
  CHECK_THAT(r.output, Catch::Matchers::Contains("cannot create directory"));
  CHECK(only(d, {"typo.toml", "file"}));  // no output, no partial directory
}

TEST_CASE("a run writes its files whole, refuses to overwrite, and its metadata repeats it exactly",
          "[app]") {
  fs::path d = temp_dir("run");
  const std::string args = " --duration 3 --set settle_time=2 --quiet --out ";
  auto r = cli("run " + kScene + args + (d / "a").string());
  REQUIRE(r.code == 0);
  CHECK(only(d / "a", {"arch_formation.csv", "arch_shapes.csv", "arches.csv", "clogs.csv", "exits.csv",
                       "manifest.toml", "metadata.toml", "species.csv", "summary.csv", "survival.csv"}));
  CHECK(slurp(d / "a" / "exits.csv").rfind("t_s,id,species\n", 0) == 0);
  // Again into the same directory: refused without --force, the first run intact.
  const std::string before = slurp(d / "a" / "exits.csv");
  r = cli("run " + kScene + args + (d / "a").string());
  CHECK(r.code == 2);
  CHECK_THAT(r.output, Catch::Matchers::Contains("already exists"));
  CHECK(slurp(d / "a" / "exits.csv") == before);
  // The metadata file is a scene file: running it gives the same events.
  r = cli("run " + (d / "a" / "metadata.toml").string() + " --quiet --out " + (d / "b").string());
  REQUIRE(r.code == 0);
  CHECK(slurp(d / "b" / "exits.csv") == before);
  CHECK(only(d, {"a", "b"}));
}

TEST_CASE("record makes NAME.mp4 and NAME/ with frames, events and metadata", "[app][record]") {
  fs::path d = temp_dir("record");
  auto r = cli("record " + kScene +
               " --duration 1 --set settle_time=2 --size 320x240 --fps 10 --png-every 5 --quiet --out " +
               (d / "demo").string());
  REQUIRE(r.code == 0);
  CHECK(only(d, {"demo", "demo.mp4", ".demo.mp4.siloscope"}));  // the movie's record (io/output.h)
  CHECK(fs::file_size(d / "demo.mp4") > 1000);
  CHECK(only(d / "demo" / "frames", {"frame_000000.png", "frame_000005.png"}));
  const std::string meta = slurp(d / "demo" / "metadata.toml");
  CHECK_THAT(meta, Catch::Matchers::Contains("frames = 10") &&
                       Catch::Matchers::Contains("movie = \"demo.mp4\"") &&
                       Catch::Matchers::Contains("[scene]") && Catch::Matchers::Contains("seed = 1"));
}

TEST_CASE("record --color-max sets the colour scale or takes it from the data (auto)", "[app][record]") {
  fs::path d = temp_dir("colormax");
  const std::string base = "record " + kScene +
                           " --duration 0.5 --set settle_time=2 --size 160x120 --fps 10 --no-movie " +
                           "--png-every 5 --color speed --out ";
  auto scale_of = [](const std::string& meta) {
    const auto at = meta.find("color_scale_max = ");
    return at == std::string::npos ? -1.0 : std::stod(meta.substr(at + 18));
  };
  auto a = cli(base + (d / "a").string() + " --color-max auto");
  REQUIRE(a.code == 0);
  CHECK_THAT(a.output, Catch::Matchers::Contains("--color-max auto:"));
  const double top = scale_of(slurp(d / "a" / "metadata.toml"));
  // Disks falling out of the aperture reach ~1-3 m/s; the fixed default is 0.5 m/s.
  CHECK(top > 0.2);
  CHECK(top < 10.0);
  CHECK(top != Approx(0.5));
  auto b = cli(base + (d / "b").string() + " --color-max auto --quiet");
  REQUIRE(b.code == 0);
  CHECK(scale_of(slurp(d / "b" / "metadata.toml")) == top);  // the same seed: the same scale
  REQUIRE(cli(base + (d / "c").string() + " --color-max 1.25 --quiet").code == 0);
  CHECK(scale_of(slurp(d / "c" / "metadata.toml")) == 1.25);
  auto bad = cli(base + (d / "e").string() + " --color-max fast");
  CHECK(bad.code == 2);
  CHECK_THAT(bad.output,
             Catch::Matchers::Contains("--color-max fast") && Catch::Matchers::Contains("or auto"));
  CHECK_FALSE(fs::exists(d / "e"));
}

TEST_CASE("record colours by displacement, coordination, stress or id on a chosen colour map and range",
          "[app][record][heavy]") {
  fs::path d = temp_dir("colorby");
  const std::string base = "record " + kScene +
                           " --duration 0.5 --set settle_time=2 --size 160x120 --fps 10 --no-movie " +
                           "--png-every 5 --quiet --out ";
  REQUIRE(cli(base + (d / "a").string() +
              " --color displacement --displacement-from 0.2 --color-max 0.1:0.8 --colormap cividis")
              .code == 0);
  const std::string meta = slurp(d / "a" / "metadata.toml");
  CHECK_THAT(meta, Catch::Matchers::Contains("color = \"displacement\"") &&
                       Catch::Matchers::Contains("color_scale_min = 0.1") &&
                       Catch::Matchers::Contains("color_scale_max = 0.8") &&
                       Catch::Matchers::Contains("colormap = \"cividis\"") &&
                       Catch::Matchers::Contains("displacement_from_s = 0.2"));
  CHECK(fs::exists(d / "a" / "frames" / "frame_000000.png"));
  REQUIRE(cli(base + (d / "b").string() + " --color coordination").code == 0);
  CHECK_THAT(slurp(d / "b" / "metadata.toml"), Catch::Matchers::Contains("color_scale_max = 6"));
  // Stress: from the solver's contacts as the movie is made, its scale in N/m; the frame command draws it
  // again from the recording's contacts, and refuses a recording whose contacts are gone.
  REQUIRE(cli(base + (d / "s").string() + " --color stress").code == 0);
  CHECK_THAT(slurp(d / "s" / "metadata.toml"), Catch::Matchers::Contains("color = \"stress\"") &&
                                                   Catch::Matchers::Contains("color_scale_max = 60"));
  REQUIRE(cli("frame " + (d / "s").string() + " --at frame:4 --out " + (d / "s4.png").string()).code == 0);
  CHECK(fs::exists(d / "s4.png"));
  REQUIRE(cli(base + (d / "c").string() + " --color displacement").code == 0);
  CHECK_THAT(slurp(d / "c" / "metadata.toml"),
             Catch::Matchers::Contains("color_scale = \"each frame's largest\""));
  const std::pair<const char*, const char*> bad[] = {
      {" --color speed --displacement-from 1", "--displacement-from applies to --color displacement"},
      {" --color coordination --color-max auto", "for displacement"},
      {" --color id --color-max 3", "not id"},
      {" --color speed --color-max 2:1", "0 <= MIN < MAX"},
      {" --colormap jet", "viridis, magma, inferno or cividis"},
      {" --color pressure", "coordination, stress or id"}};
  for (const auto& [args, says] : bad) {
    auto r = cli(base + (d / "e").string() + args);
    CHECK(r.code == 2);
    CHECK_THAT(r.output, Catch::Matchers::Contains(says));
    CHECK_FALSE(fs::exists(d / "e"));
  }
}

TEST_CASE("record --freeze holds the picture at each clog and --camera-path moves the camera",
          "[app][record][heavy]") {
  fs::path d = temp_dir("freeze");
  const std::string base =
      "record " + kScene + " --duration 9 --size 160x120 --fps 10 --no-movie --png-every 1 --quiet --out ";
  REQUIRE(cli(base + (d / "a").string() + " --freeze clog:0.5 --camera-path 0:hopper,3:outlet").code == 0);
  const std::string meta = slurp(d / "a" / "metadata.toml");
  CHECK_THAT(meta, Catch::Matchers::Contains("camera_path = \"0:hopper,3:outlet\"") &&
                       Catch::Matchers::Contains("freeze = \"clog:0.5\""));
  // Every clog that lasted clog_min_gap (0.5 s) and formed within the run is frozen once: 5 video frames
  // (the frame and 4 copies) of one picture.
  long formed = 0;
  {
    std::ifstream clogs(d / "a" / "clogs.csv");
    std::string line;
    std::getline(clogs, line);
    while (std::getline(clogs, line)) formed += std::stod(line) + 0.5 <= 9.0;
  }
  REQUIRE(formed >= 1);
  CHECK_THAT(meta, Catch::Matchers::Contains("frozen_frames = " + std::to_string(4 * formed)));
  std::vector<std::string> pngs;
  for (const auto& e : fs::directory_iterator(d / "a" / "frames")) pngs.push_back(e.path().string());
  std::sort(pngs.begin(), pngs.end());
  CHECK(pngs.size() == static_cast<size_t>(90 + 4 * formed));  // 9 s at 10 fps, and the copies
  long held = 0;                                               // frames equal to the one before
  for (size_t k = 1; k < pngs.size(); ++k) held += slurp(pngs[k]) == slurp(pngs[k - 1]);
  CHECK(held >= 4 * formed);
  // A camera on a window away from the outlet: the freeze widens its picture to show the arch whole, and says
  // so.
  {
    auto r =
        cli("record " + kScene + " --duration 3 --size 160x120 --fps 10 --no-movie --png-every 1 --out " +
            (d / "w").string() + " --camera window:0.5,1,1.5,2 --freeze clog:0.5");
    REQUIRE(r.code == 0);
    CHECK_THAT(r.output, Catch::Matchers::Contains("the held picture widens to show it whole"));
  }
  const std::pair<const char*, const char*> bad[] = {
      {" --freeze jam:1", "clog:SECONDS or rule:SECONDS"},
      {" --freeze clog:0", "0 < SECONDS <= 60"},
      {" --freeze rule:1 --set clog_timeout=0", "clog rule is off"},
      {" --camera-path 0:split", "a path moves one"},
      {" --camera-path 3:outlet,1:hopper", "times must increase"},
      {" --camera arch:9", "--camera arch:9: the run has"},
      {" --camera grain:99999", "ids 0 to 249"},
      {" --camera-path 0:outlet,2:arch:0", "K a whole number >= 1"}};
  for (const auto& [args, says] : bad) {
    auto r = cli(base + (d / "e").string() + args);
    CHECK(r.code == 2);
    CHECK_THAT(r.output, Catch::Matchers::Contains(says));
    CHECK_FALSE(fs::exists(d / "e"));
  }
}

TEST_CASE("record tags grains by region at a time and by role (a long-lasting arch's members)",
          "[app][record][heavy]") {
  fs::path d = temp_dir("tags");
  const std::string base =
      "record " + kScene + " --duration 7 --size 160x120 --fps 10 --no-movie --png-every 100 --quiet --out ";
  REQUIRE(cli(base + (d / "a").string() + " --track-arch 1").code == 0);
  // The look-ahead's members are the recording's own first removed arch (the run repeats from its seed).
  std::ifstream arches(d / "a" / "arches.csv");
  std::string line;
  std::getline(arches, line);
  REQUIRE(std::getline(arches, line));
  std::vector<std::string> cols;
  std::stringstream ss(line);
  for (std::string c; std::getline(ss, c, ',');) cols.push_back(c);
  REQUIRE(cols.size() > 5);
  std::string ids = cols[5];
  std::replace(ids.begin(), ids.end(), ';', ',');
  CHECK_THAT(slurp(d / "a" / "metadata.toml"),
             Catch::Matchers::Contains("tracked_grains = \"" + ids + "\"") &&
                 Catch::Matchers::Contains("track_arch = 1"));
  // The arch of the first clog as it formed: clogs.csv's first clog; its arch is the one the rule later
  // removed (the clog lasted to the rule).
  REQUIRE(cli(base + (d / "c").string() + " --track-clog 1").code == 0);
  CHECK_THAT(slurp(d / "c" / "metadata.toml"),
             Catch::Matchers::Contains("track_clog = 1") &&
                 Catch::Matchers::Contains("tracked_grains = \"" + ids + "\""));
  REQUIRE(cli(base + (d / "b").string() + " --track-region 0.3,0,-0.3,0.5@2").code == 0);
  const std::string meta = slurp(d / "b" / "metadata.toml");
  const auto at = meta.find("tracked_grains = \"");
  REQUIRE(at != std::string::npos);
  const std::string list = meta.substr(at + 18, meta.find('"', at + 18) - at - 18);
  CHECK(std::count(list.begin(), list.end(), ',') >= 3);  // the outlet's bottom half metre holds several
  const std::pair<const char*, const char*> bad[] = {
      {" --track-arch 40", "the run has 1 long-lasting arches"},
      {" --track-arch -1", "expected K >= 1"},
      {" --track-clog 9", "the run has 1 clogs"},
      {" --track-region 0,0,1@2", "X0,Y0,X1,Y1@T"},
      {" --track-region 0,0,0,1@2", "non-zero width"},
      {" --track-region 0,0,1,1@20", "after the run's end"},
      {" --track-region 5,5,6,6@1", "no grain's centre is in the box"}};
  for (const auto& [args, says] : bad) {
    auto r = cli(base + (d / "e").string() + args);
    CHECK(r.code == 2);
    CHECK_THAT(r.output, Catch::Matchers::Contains(says));
    CHECK_FALSE(fs::exists(d / "e"));
  }
}

TEST_CASE("Ctrl-C during record leaves a playable movie of what was recorded", "[app][record]") {
  fs::path d = temp_dir("sigint");
  const std::string out = (d / "cut").string();
  pid_t pid = test::start_long_record(out);
  REQUIRE(pid > 0);
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  const int status = test::signal_and_wait(pid, SIGINT);
  REQUIRE(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 130);
  CHECK(fs::exists(out + ".mp4"));
  CHECK_FALSE(fs::exists(out + ".mp4.partial"));
  CHECK_THAT(slurp(d / "cut" / "metadata.toml"), Catch::Matchers::Contains("interrupted = true"));
  // Playable: ffprobe-free check through our own decoder is in test_record; here the container must be
  // complete (the moov index is written at the front by +faststart).
  std::ifstream movie(out + ".mp4", std::ios::binary);
  std::string head(64, '\0');
  movie.read(head.data(), 64);
  CHECK(head.find("ftyp") != std::string::npos);
  CHECK(slurp(out + ".mp4").find("moov") < 200);
}

TEST_CASE("kill -9 during record leaves nothing under the final names", "[app][record]") {
  fs::path d = temp_dir("sigkill");
  const std::string out = (d / "cut").string();
  pid_t pid = test::start_long_record(out);
  REQUIRE(pid > 0);
  test::signal_and_wait(pid, SIGKILL);
  CHECK_FALSE(fs::exists(out + ".mp4"));
  CHECK_FALSE(fs::exists(d / "cut"));
}

TEST_CASE("record --slowmo slows the video around a long-lasting arch's removal and nowhere else",
          "[app][record][heavy]") {
  fs::path d = temp_dir("slowmo");
  // Seed 1: the first clog is removed by the rule at t = 6.521 s; the slow window is 6.021 to 7.521 s.
  const std::string common = "record " + kScene + " --duration 8 --size 160x120 --fps 10 --quiet --out ";
  REQUIRE(cli(common + (d / "plain").string()).code == 0);
  REQUIRE(cli(common + (d / "slow").string() + " --slowmo 4").code == 0);
  CHECK_THAT(slurp(d / "plain" / "metadata.toml"), Catch::Matchers::Contains("frames = 80\n"));
  const std::string slow = slurp(d / "slow" / "metadata.toml");
  // Frames at 0, 0.1, ..., 6.0 (61); slow from 6.1 (the first frame past 6.021) every 0.025 s up to 7.5 (57);
  // then 7.525, 7.625, ..., 7.925 (5): 123 frames, 57 of them slow.
  CHECK_THAT(
      slow, Catch::Matchers::Contains("frames = 123\n") && Catch::Matchers::Contains("slowmo_frames = 57\n"));
  CHECK(cli(common + (d / "bad").string() + " --slowmo 0.5").code == 2);
}

TEST_CASE("record: --background, --font-scale, --force-chains and --track are checked before any work",
          "[cli][app]") {
  const fs::path d = temp_dir("record_looks");
  for (const std::string& bad :
       {std::string("--background pink"), std::string("--font-scale 9"),
        std::string("--background dark --transparent --no-movie --png-every 1"),
        std::string("--force-chains 5:2"), std::string("--force-chains x"), std::string("--track 250"),
        std::string("--track 3,x"), std::string("--trail -1")}) {
    auto r = cli("record " + kScene + " --duration 1 --quiet " + bad + " --out " + (d / "r").string());
    INFO(bad << ": " << r.output);
    CHECK(r.code == 2);
    CHECK_FALSE(fs::exists(d / "r"));
  }
}

TEST_CASE("bench record flags a stage slowed 1.5x against its committed figures, and exits 1",
          "[cli][app][heavy]") {
  // The rule itself.
  CHECK(app::slowed_stage("record_720p30", "draw", 1.4, 1.0).empty());
  CHECK(app::slowed_stage("record_720p30", "draw", 1.5, 1.0).empty());
  CHECK_THAT(app::slowed_stage("record_720p30", "draw", 1.6, 1.0),
             Catch::Matchers::Contains("SLOWED: record_720p30 draw 1.60") &&
                 Catch::Matchers::Contains("(1.6x, limit 1.5x)"));
  CHECK(app::slowed_stage("record_720p30", "draw", 5.0, 0.0).empty());  // no reference: nothing to say
  // A reference whose draw stage is a hundredth of any real one: the bench says so and fails; one that
  // nothing could exceed passes.
  const fs::path d = temp_dir("bench_reference");
  std::ofstream(d / "slow.csv") << "case,stage,ms_per_frame,machine,commit\n"
                                << "record_720p30,draw,0.001,test,none\n";
  std::ofstream(d / "fast.csv") << "case,stage,ms_per_frame,machine,commit\n"
                                << "record_720p30,draw,100000,test,none\n";
  const std::string common = "bench record " + kScene + " --duration 0.5 --repeats 1 --reference ";
  const auto slowed = cli(common + (d / "slow.csv").string());
  INFO(slowed.output);
  CHECK(slowed.code == 1);
  CHECK_THAT(slowed.output, Catch::Matchers::Contains("SLOWED: record_720p30 draw"));
  const auto fine = cli(common + (d / "fast.csv").string());
  INFO(fine.output);
  CHECK(fine.code == 0);
  CHECK_THAT(fine.output, Catch::Matchers::Contains("record_720p30    draw"));
}
