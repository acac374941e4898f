// siloscope bench record: what filming costs against simulating. In one process, alternating, `run` (no
// video), `record` at 720p30 and at 1080p30 of the same scene and duration, each repeated; prints the median
// wall times, their ratios to `run` (the targets are ratios, which a shared, noisy machine can still
// compare), the per-frame time of each recording stage, PNG frames per second at 1080p, and writes CSV.
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include <toml++/toml.h>

#include "analysis/stats.h"
#include "app/services/cli.h"
#include "app/services/process.h"
#include "app/services/run_outputs.h"
#include "app/services/terminal.h"
#include "core/error.h"
#include "core/format.h"
#include "io/metadata.h"
#include "io/output.h"
#include "io/run.h"

namespace app {

namespace {
namespace fs = std::filesystem;

const char* kHeader =
    "case,repeat,wall_s,ratio_to_run,frames,ms_sim,ms_draw,ms_readback,ms_convert,ms_encode,ms_png";

struct RecordBenchOptions {
  SceneOptions scene;
  int repeats = 3;
  std::string csv, binary;  // binary: another siloscope to time (e.g. an older build), default this one
};

struct Case {
  std::string name;
  std::vector<std::string> args;
};

int bench_record(const RecordBenchOptions& o) {
  if (!o.csv.empty()) io::check_destination(o.csv, true, "CSV file", io::OutputKind::Csv, kHeader, false);
  const double duration = o.scene.duration.value_or(20.0);
  if (!(duration > 0 && duration <= 600)) throw core::InputError("--duration must be in (0, 600] s");
  const std::string scene =
      o.scene.path.empty() ? (share_dir() / "scenes" / "paper.toml").string() : o.scene.path;
  if (o.binary.empty()) o.scene.load();  // validate before any work (another binary validates its own scenes)
  std::error_code ec;
  const fs::path self = o.binary.empty() ? fs::path(self_exe()) : fs::path(o.binary);
  if (!o.binary.empty() && ::access(o.binary.c_str(), X_OK) != 0)
    throw core::InputError("--binary " + o.binary + ": not an executable file");
  const fs::path tmp = fs::temp_directory_path() / ("siloscope_bench_record_" + std::to_string(::getpid()));
  fs::create_directories(tmp);
  auto args = [&](const char* command, double seconds, std::vector<std::string> extra) {
    std::vector<std::string> a = {self.string(), command,      scene,
                                  "--quiet",     "--duration", core::format_g(seconds)};
    for (const auto& s : o.scene.overrides) a.insert(a.end(), {"--set", s});
    a.insert(a.end(), extra.begin(), extra.end());
    return a;
  };
  const std::vector<Case> cases = {
      {"run", args("run", duration, {})},
      {"record_720p30", args("record", duration, {"--size", "1280x720", "--fps", "30"})},
      {"record_1080p30", args("record", duration, {"--size", "1920x1080", "--fps", "30"})},
      // PNG frames per second at 1080p: a shorter clip (each frame is a file).
      {"png_1080p", args("record", std::min(duration, 4.0),
                         {"--size", "1920x1080", "--fps", "30", "--png-every", "1", "--no-movie"})},
  };
  std::map<std::string, std::vector<double>> walls;
  std::map<std::string, std::map<std::string, std::vector<double>>> stage;
  std::string csv = std::string(kHeader) + "\n";
  std::vector<std::string> rows;
  for (int k = 0; k < o.repeats; ++k) {
    for (const auto& c : cases) {
      const fs::path out = tmp / (c.name + "_" + std::to_string(k));
      std::vector<std::string> argv = c.args;
      argv.insert(argv.end(), {"--out", out.string()});
      const auto t0 = std::chrono::steady_clock::now();
      const int status = run_process(argv);
      const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      if (status != 0) {
        fs::remove_all(tmp, ec);
        throw core::RuntimeFault("bench record: `" + c.name + "` (" + argv[1] + " " + scene + ") failed");
      }
      walls[c.name].push_back(wall);
      std::string row = c.name + "," + std::to_string(k) + "," + core::format_g(wall, 5) + ",";
      if (c.name != "run") {
        const io::Run rec = io::Run::open(out, "bench record");
        const toml::table& t = rec.metadata();
        for (const char* s : {"sim", "draw", "readback", "convert", "encode", "png"})
          stage[c.name][s].push_back(t["run"][std::string("ms_per_frame_") + s].value_or(0.0));
        row += "%RATIO%," + std::to_string(t["run"]["frames"].value_or<std::int64_t>(0));
        for (const char* s : {"sim", "draw", "readback", "convert", "encode", "png"})
          row += "," + core::format_g(stage[c.name][s].back(), 4);
      } else {
        row += "%RATIO%,0,,,,,,";
      }
      rows.push_back(row);
      fs::remove_all(out, ec);
      fs::remove(fs::path(out.string() + ".mp4"), ec);
    }
  }
  fs::remove_all(tmp, ec);
  const double run_wall = analysis::median(walls["run"]);
  std::printf("siloscope %s, bench record of %s: %s, %g s of discharge, medians of %d\n",
              io::version_string().c_str(), self.c_str(), scene.c_str(), duration, o.repeats);
  std::printf("%-16s %10s %12s %9s %9s %11s %10s %10s %8s\n", "case", "wall [s]", "x run", "sim", "draw",
              "readback", "convert", "encode", "png");
  std::printf("%-16s %10s %12s %9s %9s %11s %10s %10s %8s\n", "", "", "", "ms/frame", "ms/frame", "ms/frame",
              "ms/frame", "ms/frame", "ms/frame");
  for (const auto& c : cases) {
    const double w = analysis::median(walls[c.name]);
    std::printf("%-16s %10.2f %12.2f", c.name.c_str(), w, c.name == "png_1080p" ? NAN : w / run_wall);
    for (const char* s : {"sim", "draw", "readback", "convert", "encode", "png"})
      std::printf(" %9.2f", c.name == "run" ? NAN : analysis::median(stage[c.name][s]));
    std::printf("\n");
  }
  std::printf(
      "targets: record_1080p30 <= 1.4x run, record_720p30 <= 1.2x run (ratios of medians of this run)\n");
  for (auto& r : rows) {
    const std::string name = r.substr(0, r.find(','));
    const double w = std::stod(r.substr(r.find(',', r.find(',') + 1) + 1));
    r.replace(r.find("%RATIO%"), 7, name == "png_1080p" ? "" : core::format_g(w / run_wall, 4));
    csv += r + "\n";
  }
  if (!o.csv.empty()) {
    io::write_file_atomic(o.csv, csv);
    std::printf("written %s\n", o.csv.c_str());
  }
  return 0;
}
}  // namespace

void add_bench_record_command(CLI::App& bench, Action& action) {
  auto o = std::make_shared<RecordBenchOptions>();
  auto* cmd =
      bench.add_subcommand("record", "filming cost: run vs record at 720p and 1080p (ratios), per stage");
  o->scene.add_to(*cmd, false);
  cmd->add_option("--repeats", o->repeats, "repeats of each case (medians)")
      ->check(whole_number(1, 100))
      ->capture_default_str();
  cmd->add_option("--csv", o->csv, "CSV output (one row per case and repeat)");
  cmd->add_option("--binary", o->binary, "time another siloscope binary (e.g. an older build) the same way");
  cmd->callback([o, &action] { action = [o] { return bench_record(*o); }; });
}

}  // namespace app
