// siloscope bench roundtrip: detect and import validated without lab data. A siloscope recording (its
// trajectory and events are the truth) is filmed without overlays; each camera level adds blur, noise, uneven
// light, a slight perspective and dropped detections (vision::add_camera); detect, link and import run on it;
// the table says what came back (app/services/roundtrip.h), one row per level, with the cost of detection.
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "app/services/cli.h"
#include "app/services/process.h"
#include "app/services/roundtrip.h"
#include "core/error.h"
#include "core/format.h"
#include "io/metadata.h"
#include "io/output.h"

namespace app {

namespace {
namespace fs = std::filesystem;

struct RoundTripOptions {
  std::string tolerances = "0,0.02,0.05,0.1,0.2,0.3,0.5";
  std::string scene = "", camera = "window:-1.4,-0.4,1.4,1.6", size = "1920x1080", levels = "0,1,2,3",
              work = "", csv;
  std::uint64_t seed = 3;
  double duration = 8, drop = 0.01, tolerance = 0.1;
};

constexpr const char* kHeader =
    "level,drop,frames,recall,precision,error_median_d,error_p95_d,id_switches,switches_per_1000,true_clogs,"
    "found_clogs,matched_clogs,start_error_s,end_error_s,arches_compared,member_recall,member_precision,"
    "span_error_d,rise_error_d,theta_error_deg,detect_s_per_frame";

std::string csv_row(const RoundTripRow& r) {
  auto g = [](double v) { return core::format_g(v, 5); };
  return g(r.level) + "," + g(r.drop) + "," + std::to_string(r.frames) + "," + g(r.recall) + "," +
         g(r.precision) + "," + g(r.error_median_d) + "," + g(r.error_p95_d) + "," +
         std::to_string(r.id_switches) + "," + g(r.switches_per_1000) + "," + std::to_string(r.true_clogs) +
         "," + std::to_string(r.found_clogs) + "," + std::to_string(r.matched_clogs) + "," +
         g(r.start_error_s) + "," + g(r.end_error_s) + "," + std::to_string(r.arches_compared) + "," +
         g(r.member_recall) + "," + g(r.member_precision) + "," + g(r.span_error_d) + "," +
         g(r.rise_error_d) + "," + g(r.theta_error_deg) + "," + g(r.detect_s_per_frame);
}

int bench_roundtrip(const RoundTripOptions& o) {
  std::vector<double> levels;
  {
    std::stringstream ss(o.levels);
    std::string item;
    while (std::getline(ss, item, ',')) {
      char* end = nullptr;
      const double v = std::strtod(item.c_str(), &end);
      if (item.empty() || *end || !(v >= 0 && v <= 10))
        throw core::InputError("--levels '" + o.levels + "': '" + item +
                               "' is not a camera level from 0 to 10");
      levels.push_back(v);
    }
  }
  if (!(o.drop >= 0 && o.drop * levels.back() < 1))
    throw core::InputError("--drop " + core::format_g(o.drop) +
                           ": expected a fraction per level, below 1 at every level");
  if (o.work.empty()) throw core::InputError("--work: a directory for the recording and the tracks");
  if (!o.csv.empty()) io::check_destination(o.csv, true, "CSV file", io::OutputKind::Csv, kHeader, false);
  const fs::path work = io::output_path(o.work, "--work");
  fs::create_directories(work);
  const fs::path rec = work / "truth";
  const std::string scene = o.scene.empty() ? (share_dir() / "scenes" / "paper.toml").string() : o.scene;
  std::printf("siloscope %s, bench roundtrip: %s, seed %llu, %g s, camera %s at %s, no overlays\n",
              io::version_string().c_str(), fs::path(scene).filename().c_str(),
              static_cast<unsigned long long>(o.seed), o.duration, o.camera.c_str(), o.size.c_str());
  const int status =
      run_process({self_exe(), "record", scene, "--seed", std::to_string(o.seed), "--duration",
                   core::format_g(o.duration), "--camera", o.camera, "--size", o.size, "--overlay", "none",
                   "--arch-halo", "off", "--out", rec.string(), "--force", "--quiet"});
  if (status != 0)
    throw core::RuntimeFault("bench roundtrip: recording the ground truth failed (exit " +
                             std::to_string(status) + ")");
  std::string csv = std::string(kHeader) + "\n";
  std::printf("%5s %5s | %6s %6s %7s %7s %6s | %5s %5s %7s %7s | %6s %6s %6s %6s %6s | %8s\n", "level",
              "drop", "recall", "prec", "err_d", "p95_d", "sw/1k", "clogs", "found", "dstart", "dend",
              "m_rec", "m_prec", "span_d", "rise_d", "theta", "s/frame");
  for (double level : levels) {
    const RoundTripRow r = round_trip(rec, level, o.drop * level, o.seed,
                                      work / ("tracks_level_" + core::format_g(level) + ".csv"), o.tolerance);
    std::printf(
        "%5g %5.3f | %6.4f %6.4f %7.4f %7.4f %6.2f | %5ld %5ld %7.3f %7.3f | %6.3f %6.3f %6.3f %6.3f %6.1f | "
        "%8.4f\n",
        r.level, r.drop, r.recall, r.precision, r.error_median_d, r.error_p95_d, r.switches_per_1000,
        r.true_clogs, r.found_clogs, r.start_error_s, r.end_error_s, r.member_recall, r.member_precision,
        r.span_error_d, r.rise_error_d, r.theta_error_deg, r.detect_s_per_frame);
    std::fflush(stdout);
    csv += csv_row(r) + "\n";
  }
  std::printf(
      "(grains: whole disks in the picture, per frame; clogs matched by start within 0.25 s; arches at the "
      "import's arch frame; err in diameters)\n");
  // The contact tolerance: the same tracks of the clean camera imported with each gap.
  std::printf(
      "\ncontact tolerance (the first and last levels' tracks imported again):\n%5s %9s | %5s %5s | %10s "
      "%10s | %8s %8s %8s | %6s %6s "
      "%6s %6s\n",
      "level", "tolerance", "clogs", "found", "arch_true", "arch_found", "clogged", "w_arch", "flow_arch",
      "m_rec", "m_prec", "span_d", "theta");
  std::string tol_csv =
      "level,contact_tolerance,true_clogs,found_clogs,matched_clogs,arch_frames_true,arch_frames_found,"
      "frames_clogged,clogged_with_arch,flowing_with_arch,"
      "member_recall,member_precision,span_error_d,theta_error_deg\n";
  std::vector<double> tol_levels = {levels.front()};
  if (levels.back() != levels.front()) tol_levels.push_back(levels.back());
  for (double level : tol_levels) {
    std::stringstream ts(o.tolerances);
    for (std::string item; std::getline(ts, item, ',');) {
      char* end = nullptr;
      const double tol = std::strtod(item.c_str(), &end);
      if (item.empty() || *end || !(tol >= 0 && tol <= 0.5))
        throw core::InputError("--tolerances '" + o.tolerances + "': '" + item +
                               "' is not a gap from 0 to 0.5");
      const RoundTripRow r = round_trip(rec, level, o.drop * level, o.seed,
                                        work / ("tracks_level_" + core::format_g(level) + ".csv"), tol, true);
      std::printf("%5g %9g | %5ld %5ld | %10ld %10ld | %8ld %8ld %8ld | %6.3f %6.3f %6.3f %6.1f\n", level,
                  tol, r.true_clogs, r.found_clogs, r.arch_frames_true, r.arch_frames_found, r.frames_clogged,
                  r.clogged_with_arch, r.flowing_with_arch, r.member_recall, r.member_precision,
                  r.span_error_d, r.theta_error_deg);
      std::fflush(stdout);
      auto g = [](double v) { return core::format_g(v, 5); };
      tol_csv += g(level) + "," + g(tol) + "," + std::to_string(r.true_clogs) + "," +
                 std::to_string(r.found_clogs) + "," + std::to_string(r.matched_clogs) + "," +
                 std::to_string(r.arch_frames_true) + "," + std::to_string(r.arch_frames_found) + "," +
                 std::to_string(r.frames_clogged) + "," + std::to_string(r.clogged_with_arch) + "," +
                 std::to_string(r.flowing_with_arch) + "," + g(r.member_recall) + "," +
                 g(r.member_precision) + "," + g(r.span_error_d) + "," + g(r.theta_error_deg) + "\n";
    }
  }
  if (!o.csv.empty()) {
    io::write_file_atomic(o.csv, csv);
    fs::path tol_path = o.csv;
    tol_path.replace_extension(".tolerance.csv");
    io::write_file_atomic(tol_path, tol_csv);
    std::printf("written %s and %s\n", o.csv.c_str(), tol_path.c_str());
  }
  return 0;
}
}  // namespace

void add_bench_roundtrip_command(CLI::App& bench, Action& action) {
  auto o = std::make_shared<RoundTripOptions>();
  auto* cmd = bench.add_subcommand(
      "roundtrip", "detect and import against a recording's own truth, at several camera levels");
  cmd->add_option("--scene", o->scene, "the scene to record (default: the paper's)");
  cmd->add_option("--seed", o->seed, "its seed");
  cmd->add_option("--duration", o->duration, "simulated seconds");
  cmd->add_option("--camera", o->camera,
                  "a single-panel camera (default window:-1.4,-0.4,1.4,1.6: the hopper's outlet half)");
  cmd->add_option("--size", o->size, "the movie's size");
  cmd->add_option("--levels", o->levels,
                  "camera levels, e.g. 0,1,2,3 (blur 0.6 L px, noise 6 L grey levels, light "
                  "falling 12 L %, corners moved 0.1 L %)");
  cmd->add_option("--drop", o->drop,
                  "detections dropped at random, per level (default 0.01: 1 % at level 1)");
  cmd->add_option("--contact-tolerance", o->tolerance, "import's contact gap, fraction of a diameter");
  cmd->add_option("--tolerances", o->tolerances,
                  "contact gaps to import the first level's tracks with again (sensitivity; default "
                  "0,0.02,0.05,0.1,0.2,0.3,0.5)");
  cmd->add_option("--work", o->work, "directory for the recording and the tracks (created)")->required();
  cmd->add_option("--csv", o->csv, "write the table as CSV here");
  cmd->callback([o, &action] { action = [o] { return bench_roundtrip(*o); }; });
}

}  // namespace app
