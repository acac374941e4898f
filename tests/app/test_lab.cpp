// Issue 40: lab data. Tracked particles in trackpy's format import as a run whose clogs are the recording's;
// bad input gets one line and exit 2; the round trip through a filmed recording recovers grains, clogs and
// arches within stated bounds.
#include <catch2/catch.hpp>

#include <sys/resource.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <vector>

#include "app/services/lab.h"
#include "app/services/roundtrip.h"
#include "helpers.h"
#include "io/events_csv.h"
#include "io/trajectory.h"

namespace fs = std::filesystem;
using test::cli;
using test::kScene;
using test::slurp;
using test::temp_dir;

namespace {

constexpr double kScale = 0.004;                  // m per pixel
constexpr double kOriginX = 400, kOriginY = 600;  // the outlet's centre, px

// A recording's trajectory as a tracker would give it: pandas' index column, then trackpy's columns (pixels,
// y down), a new particle id whenever a grain jumps (an exit or the rule re-injecting it at the top: a lab's
// tracker sees a new grain), and the diameter in pixels.
void write_trackpy(const fs::path& traj, const fs::path& csv) {
  io::Trajectory t(traj);
  std::ofstream out(csv);
  out << ",y,x,mass,size,ecc,signal,raw_mass,ep,frame,particle,diameter\n";
  std::map<int, long> id_of;
  std::map<int, float> last_y;
  long next = 0, row = 0;
  for (long k = 0; k < t.size(); ++k) {
    const core::Frame f = t.frame(k);
    for (size_t i = 0; i < f.particles.size(); ++i) {
      const core::Particle& p = f.particles[i];
      const int g = static_cast<int>(i);
      if (!id_of.count(g) || std::fabs(p.y - last_y[g]) > 0.5f) id_of[g] = next++;
      last_y[g] = p.y;
      out << row++ << "," << kOriginY - p.y / kScale << "," << kOriginX + p.x / kScale
          << ",100,3,0.1,10,120,0.1," << k << "," << id_of[g] << "," << 2 * p.radius / kScale << "\n";
    }
  }
}

}  // namespace

TEST_CASE("import: a trackpy CSV of a recording gives back its clogs, arches the inspector shows, an export",
          "[lab][app][heavy]") {
  const fs::path d = temp_dir("lab_import");
  REQUIRE(
      cli("run " + kScene + " --seed 3 --duration 8 --trajectory-fps 30 --quiet --out " + (d / "r").string())
          .code == 0);
  write_trackpy(d / "r" / "trajectory.sstraj", d / "tracks.csv");
  const auto imp = cli("import " + (d / "tracks.csv").string() + " --geometry " + kScene +
                       " --scale 0.004 --origin 400,600 --fps 30.303030303 --out " + (d / "imp").string());
  INFO(imp.output);
  REQUIRE(imp.code == 0);
  const core::Events truth = io::read_events(d / "r");
  const core::Events found = io::read_events(d / "imp");
  REQUIRE(truth.clogs.size() >= 2);
  REQUIRE(found.clogs.size() == truth.clogs.size());
  for (size_t c = 0; c < truth.clogs.size(); ++c) {
    CHECK(std::fabs(found.clogs[c].start - truth.clogs[c].start) < 0.05);  // within a frame and a half
    CHECK(std::fabs(found.clogs[c].end - truth.clogs[c].end) < 0.1);
  }
  // Exits: the recording's, give or take the grains the rule removed from an arch at the outlet.
  CHECK(std::abs(static_cast<long>(found.exits.size()) - static_cast<long>(truth.exits.size())) <= 8);
  const std::string arches = slurp(d / "imp" / "clog_arches.csv");
  CHECK(test::count_of(arches, "\n") == static_cast<long>(truth.clogs.size()) + 1);
  const std::string meta = slurp(d / "imp" / "metadata.toml");
  CHECK(meta.find("imported = true") != std::string::npos);
  CHECK(fs::exists(d / "imp" / "manifest.toml"));
  // Every exit brings a new track (a new id at the top), but the run holds the container's 250 grains, not
  // one particle per track: a grain that enters takes the place of one that left (a long film's memory and
  // file then grow with its length, not with its square).
  auto count = [&](const std::string& key) {
    const size_t at = meta.find("\n" + key + " = ");
    REQUIRE(at != std::string::npos);
    return std::stol(meta.substr(at + key.size() + 4));
  };
  const long grains = count("grains"), particles = count("particles");
  INFO("grains " << grains << ", particles " << particles);
  CHECK(grains >= 250 + static_cast<long>(truth.exits.size()) / 2);
  CHECK(particles <= 250 + 10);
  CHECK(io::Trajectory(d / "imp" / "trajectory.sstraj").info().n_particles ==
        static_cast<std::uint32_t>(particles));

  // The inspector opens it at the first clog's arch and prints its members.
  std::ofstream(d / "s.txt") << "goto clog 1 arch\nprint\nsnapshot " << (d / "clog1.png").string()
                             << " 640x360\n";
  const auto ins = cli("inspect " + (d / "imp").string() + " --script " + (d / "s.txt").string());
  INFO(ins.output);
  REQUIRE(ins.code == 0);
  // At the arch from its formation: the clog confirmed or its arch forming, and the arch's members listed.
  CHECK((ins.output.find("clog 1 open") != std::string::npos ||
         ins.output.find("clog 1 forming") != std::string::npos));
  CHECK(ins.output.find("arch [") != std::string::npos);
  CHECK(ins.output.find("arch []") == std::string::npos);
  CHECK(fs::file_size(d / "clog1.png") > 1000);
  REQUIRE(cli("export " + (d / "imp").string() + " --format xyz --out " + (d / "imp.xyz").string()).code ==
          0);
  // The gallery draws its clogs' arches from the trajectory (nothing to re-simulate), one tile per clog.
  const auto gal = cli("gallery " + (d / "imp").string() + " --out " + (d / "g.svg").string());
  INFO(gal.output);
  REQUIRE(gal.code == 0);
  CHECK(gal.output.find(std::to_string(truth.clogs.size()) + " arches") != std::string::npos);
  CHECK(slurp(d / "g.svg").find("imported run") != std::string::npos);
  // A movie of the simulation beside the experiment, on one clock; a scene with another container is refused.
  const auto cmp = cli("record " + kScene + " --seed 3 --duration 3 --size 320x180 --quiet --compare-run " +
                       (d / "imp").string() + " --out " + (d / "cmp").string());
  INFO(cmp.output);
  REQUIRE(cmp.code == 0);
  CHECK(fs::file_size(d / "cmp.mp4") > 1000);
  CHECK(slurp(d / "cmp" / "metadata.toml").find("experiment: imp") != std::string::npos);
  const auto other =
      cli("record " + kScene + " --set aperture=0.4 --duration 3 --size 320x180 --quiet --compare-run " +
          (d / "imp").string() + " --out " + (d / "cmp2").string());
  CHECK(other.code == 2);
  CHECK(other.output.find("its container is not the scene's (outlet 0.4 m against 0.299 m)") !=
        std::string::npos);
  CHECK(!fs::exists(d / "cmp2"));
  // Analyze takes it as a realization.
  const auto an = cli("analyze " + (d / "imp").string() + " --out " + (d / "an").string());
  INFO(an.output);
  CHECK(an.code == 0);
}

TEST_CASE("import and detect: bad input gets one line naming the problem and exit 2, nothing written",
          "[lab][app][robust]") {
  const fs::path d = temp_dir("lab_bad");
  auto refused = [&](const std::string& args, const std::string& says) {
    const auto r = cli(args);
    INFO(args << "\n" << r.output);
    CHECK(r.code == 2);
    CHECK(r.output.find(says) != std::string::npos);
    CHECK(test::count_of(r.output, "\n") == 1);
    CHECK(!fs::exists(d / "out"));
  };
  const std::string tracks = (d / "t.csv").string(),
                    geo = " --geometry " + kScene + " --out " + (d / "out").string();
  std::ofstream(tracks) << "frame,particle,x\n0,1,0.1\n";
  refused("import " + tracks + geo,
          "no column for y (looked for y, y_m, POSITION_Y; name it with --columns y=COLUMN)");
  std::ofstream(tracks) << "t,particle,x,y\n0,1,0.1,0.5\n0,1,0.2,0.5\n0.1,1,0.1,0.5\n";
  refused("import " + tracks + geo, "particle 1 appears twice at t = 0 s");
  std::ofstream(tracks) << "t,particle,x,y\n0,1,5,0.5\n0.1,1,5,0.5\n";
  refused("import " + tracks + geo, ":2: particle 1 at (5, 0.5) m lies outside the container");
  std::ofstream(tracks) << "frame,particle,x,y\n0,1,0.1,0.5\n1,1,0.1,0.5\n";
  refused("import " + tracks + geo, "give the frame rate with --fps");
  std::ofstream(tracks) << "t,particle,x,y\n0,1,0.1,nan\n";
  refused("import " + tracks + geo, ":2: column y is 'nan', not a finite number");
  // The geometry as a preset's name, as run and record take a scene (the file's own error comes next).
  refused("import " + tracks + " --geometry paper --out " + (d / "out").string(), ":2: column y is 'nan'");
  refused("import " + tracks + " --geometry nosuch --out " + (d / "out").string(),
          "nosuch: no such scene file, and no preset scene of that name (presets: ");
  refused("import " + tracks + geo + " --columns id=TrackID",
          "--columns id=TrackID: the file has no column 'TrackID'");
  std::ofstream(d / "movie.mp4") << "not a movie\n";
  refused("detect " + (d / "movie.mp4").string() + " --scale 0.004 --origin 400,600 --geometry " + kScene +
              " --out " + (d / "out" / "t.csv").string(),
          "cannot be decoded as a video");
  fs::create_directories(d / "frames");
  std::ofstream(d / "frames" / "a.png") << "x";
  refused("detect " + (d / "frames").string() + " --geometry " + kScene + " --out " +
              (d / "out" / "t.csv").string(),
          "no calibration: give --scale and --origin, or --points");
  // Polygons are not found as disks quietly: the species is named, with the way out.
  refused("detect " + (d / "frames").string() + " --scale 0.004 --origin 400,600 --geometry " +
              std::string(SILOSCOPE_SOURCE_DIR) + "/assets/scenes/pentagons.toml --out " +
              (d / "out" / "t.csv").string(),
          "species.pentagons.sides = 5: detect finds disks only");
  refused("detect " + (d / "frames").string() +
              " --scale 0.004 --origin 400,600 --geometry pentagons --out " + (d / "out" / "t.csv").string(),
          "species.pentagons.sides = 5: detect finds disks only");
}

TEST_CASE("round trip: a filmed recording's grains, clogs and arches come back through detect and import",
          "[lab][app][heavy]") {
  const fs::path d = temp_dir("lab_roundtrip");
  REQUIRE(cli("record " + kScene +
              " --seed 3 --duration 8 --camera window:-1.4,-0.4,1.4,1.6 --size 1280x720 --overlay none "
              "--arch-halo off --quiet --out " +
              (d / "truth").string())
              .code == 0);
  // A clean camera: every whole disk found where it is.
  const app::RoundTripRow clean = app::round_trip(d / "truth", 0, 0, 3, d / "t0.csv");
  CHECK(clean.recall >= 0.995);
  CHECK(clean.precision >= 0.995);
  CHECK(clean.error_median_d <= 0.01);
  CHECK(clean.error_p95_d <= 0.06);
  CHECK(clean.switches_per_1000 <= 2);
  REQUIRE(clean.true_clogs >= 2);
  CHECK(clean.matched_clogs == clean.true_clogs);
  CHECK(clean.found_clogs == clean.true_clogs);
  CHECK(clean.start_error_s <= 0.05);
  CHECK(clean.end_error_s <= 0.1);
  REQUIRE(clean.arches_compared >= 1);
  CHECK(clean.member_recall >= 0.99);
  CHECK(clean.member_precision >= 0.99);
  CHECK(clean.span_error_d <= 0.02);
  CHECK(clean.theta_error_deg <= 2);
  // The clean camera's tracks (trackpy's names, as detect writes them) import and open in the inspector at a
  // clog's arch.
  app::Calibration cal;
  core::Model model;
  std::string why;
  REQUIRE(app::movie_calibration(d / "truth.mp4", cal, model, why));
  const auto imp =
      cli("import " + (d / "t0.csv").string() + " --geometry " + (d / "truth" / "metadata.toml").string() +
          " --scale " + std::to_string(cal.scale) + " --origin " + std::to_string(cal.origin_x) + "," +
          std::to_string(cal.origin_y) + " --quiet --out " + (d / "imp").string());
  INFO(imp.output);
  REQUIRE(imp.code == 0);
  std::ofstream(d / "s.txt") << "goto clog 1 arch\nprint\n";
  const auto ins = cli("inspect " + (d / "imp").string() + " --script " + (d / "s.txt").string());
  INFO(ins.output);
  CHECK(ins.code == 0);
  // At the arch from its formation: the clog confirmed or its arch forming, and the arch's members listed.
  CHECK((ins.output.find("clog 1 open") != std::string::npos ||
         ins.output.find("clog 1 forming") != std::string::npos));
  CHECK(ins.output.find("arch [") != std::string::npos);
  CHECK(ins.output.find("arch []") == std::string::npos);
  // Camera level 2 (blur, noise, light, perspective) and 2 % of the detections dropped.
  const app::RoundTripRow noisy = app::round_trip(d / "truth", 2, 0.02, 3, d / "t2.csv");
  CHECK(noisy.recall >= 0.96);
  CHECK(noisy.precision >= 0.99);
  CHECK(noisy.error_median_d <= 0.06);
  CHECK(noisy.switches_per_1000 <= 5);
  CHECK(noisy.matched_clogs == noisy.true_clogs);
  CHECK(noisy.start_error_s <= 0.05);
  REQUIRE(noisy.arches_compared >= 1);
  CHECK(noisy.member_recall >= 0.9);
  CHECK(noisy.member_precision >= 0.9);
  CHECK(noisy.span_error_d <= 0.05);
}

TEST_CASE("import: a broken track is joined, a short gap filled, a changed frame rate counted", "[lab]") {
  const fs::path d = temp_dir("lab_tracks");
  // Three grains resting on the hopper's walls for 12 frames; grain 2's id changes to 7 at frame 6; grain 3
  // is not detected in frames 3 and 4; frames 0-5 come every 1/30 s, then every 1/20 s.
  std::ofstream out(d / "t.csv");
  out << "t,id,x,y,r\n";
  double t = 0;
  for (int k = 0; k < 12; ++k) {
    out << t << ",1,-0.3,1.0,0.065\n";
    out << t << "," << (k < 6 ? 2 : 7) << ",0.0,1.2,0.065\n";
    if (k != 3 && k != 4) out << t << ",3," << 0.1 + 0.01 * k << ",0.9,0.065\n";
    t += k < 5 ? 1.0 / 30 : 1.0 / 20;
  }
  out.close();
  const auto r =
      cli("import " + (d / "t.csv").string() + " --geometry " + kScene + " --out " + (d / "run").string());
  INFO(r.output);
  REQUIRE(r.code == 0);
  const std::string meta = slurp(d / "run" / "metadata.toml");
  CHECK(meta.find("tracks = 4") != std::string::npos);
  CHECK(meta.find("grains = 3") != std::string::npos);
  CHECK(meta.find("ids_joined = 1") != std::string::npos);
  CHECK(meta.find("positions_interpolated = 2") != std::string::npos);
  CHECK(meta.find("frame_interval_changes = 5") != std::string::npos);  // the median is 1/20 s
  // The filled positions lie on the line between the detections around the gap.
  io::Trajectory traj(d / "run" / "trajectory.sstraj");
  REQUIRE(traj.size() == 12);
  const core::Frame f3 = traj.frame(3);
  bool found = false;
  for (const auto& p : f3.particles)
    found = found || (std::fabs(p.x - 0.13) < 1e-5 && std::fabs(p.y - 0.9) < 1e-5);
  CHECK(found);
}

TEST_CASE(
    "detect: a siloscope movie filmed with its overlay gives its grains (the box and legend are no grains)",
    "[lab][app][heavy]") {
  const fs::path d = temp_dir("lab_overlay");
  // The default overlay: the information box with its legend's disks, the scale bar, the arch's halo and
  // line.
  REQUIRE(cli("record " + kScene +
              " --seed 3 --duration 2 --camera window:-1.4,-0.4,1.4,1.6 --size 1280x720 --quiet --out " +
              (d / "truth").string())
              .code == 0);
  const app::RoundTripRow r = app::round_trip(d / "truth", 0, 0, 3, d / "t.csv");
  INFO("recall " << r.recall << ", precision " << r.precision << ", error " << r.error_median_d << " d");
  CHECK(r.recall >= 0.995);
  CHECK(r.precision >= 0.995);
  CHECK(r.error_median_d <= 0.01);
}

namespace {

// A film of grains resting on a square lattice in the paper's silo, touching (2 r apart), each moved by up
// to 1e-4 m each frame, as tracks "t,id,x,y,r" in metres: `frames` frames at 30 per second.
void write_resting(const fs::path& csv, int frames) {
  std::ofstream out(csv);
  out << "t,id,x,y,r\n";
  unsigned state = 12345;
  auto jitter = [&] {
    state = state * 1103515245u + 12345u;
    return 1e-4 * (static_cast<double>(state >> 16 & 0x7fff) / 0x7fff - 0.5);
  };
  char line[96];
  for (int k = 0; k < frames; ++k)
    for (int row = 0; row < 20; ++row)
      for (int col = 0; col < 7; ++col) {
        std::snprintf(line, sizeof line, "%.6f,%d,%.6f,%.6f,0.065\n", k / 30.0, row * 7 + col,
                      -0.39 + 0.13 * col + jitter(), 1.5 + 0.13 * row + jitter());
        out << line;
      }
}

// The peak resident memory of `siloscope ARGS`, kB (the child's own, from wait4); -1 when it failed.
long peak_kb(const std::vector<std::string>& args) {
  const pid_t pid = fork();
  if (pid == 0) {
    if (!freopen("/dev/null", "w", stdout) || !freopen("/dev/null", "w", stderr)) _exit(126);
    std::vector<char*> argv{const_cast<char*>(test::kBin.c_str())};
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execv(test::kBin.c_str(), argv.data());
    _exit(127);
  }
  int status = 0;
  rusage use{};
  wait4(pid, &status, 0, &use);
  return WIFEXITED(status) && WEXITSTATUS(status) == 0 ? use.ru_maxrss : -1;
}

}  // namespace

// Issue 54: import's memory does not grow with the film: the detections, the tracks' points and the paths
// are kept on disk (io/spill.h). Held in memory, 12 000 frames more of 140 grains took some 130 MB more.
TEST_CASE("import: a film eight times as long takes no more memory", "[lab][heavy]") {
  const fs::path d = temp_dir("lab_memory");
  write_resting(d / "short.csv", 1800);  // 1 minute
  write_resting(d / "long.csv", 14400);  // 8 minutes: 2 million rows
  const long short_kb =
      peak_kb({"import", (d / "short.csv").string(), "--geometry", kScene, "--out", (d / "short").string()});
  const long long_kb =
      peak_kb({"import", (d / "long.csv").string(), "--geometry", kScene, "--out", (d / "long").string()});
  INFO("peak memory: 1 minute " << short_kb / 1024 << " MB, 8 minutes " << long_kb / 1024 << " MB");
  REQUIRE(short_kb > 0);
  REQUIRE(long_kb > 0);
  CHECK(long_kb - short_kb < 40 * 1024);
  CHECK(long_kb < 500 * 1024);
  // The long film's run is whole: every frame, every grain.
  io::Trajectory traj(d / "long" / "trajectory.sstraj");
  CHECK(traj.size() == 14400);
  CHECK(traj.frame(14399).particles.size() == 140);
  // Nothing left beside the output: the files the detections were kept in had no names.
  long entries = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(d)) ++entries;
  CHECK(entries == 4);  // the two films and the two runs
}
