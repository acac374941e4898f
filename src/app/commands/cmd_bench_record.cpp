// siloscope bench record: what filming costs against simulating. In one process, alternating, `run` (no
// video), `record` at 720p30 and at 1080p30 of the same scene and duration, and a PNG sequence at 1080p, each
// repeated; prints the median wall times, their ratios to `run` (the targets are ratios, which a shared,
// noisy machine can still compare), the per-frame time of each recording stage, and writes CSV.
//   --binary OLD   the same cases with another build in the same run, interleaved: each stage new / old.
//   --reference F  each stage against the figures committed in docs/filming/reference.csv (by default, when
//                  run from a clone): a stage 1.5x slower than its reference is flagged, and the command
//                  exits 1, so the change that slows filming is caught in the session that makes it.
//   --elements     the draw stage with each overlay element, force chains, trails and notes on, at 720p and
//                  1080p: what each part of a look costs.
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
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
#include "core/interrupt.h"
#include "io/csv_table.h"
#include "io/metadata.h"
#include "io/output.h"
#include "io/run.h"

namespace app {

namespace {
namespace fs = std::filesystem;

const char* kHeader =
    "binary,case,repeat,wall_s,ratio_to_run,frames,ms_sim,ms_draw,ms_readback,ms_convert,ms_encode,ms_png";
const char* kStages[] = {"sim", "draw", "readback", "convert", "encode", "png"};
constexpr double kSlowed = 1.5;  // a stage this many times its reference is a regression

struct RecordBenchOptions {
  SceneOptions scene;
  int repeats = 3;
  std::string csv, binary, reference;
  bool elements = false;
};

struct Case {
  std::string name;
  std::vector<std::string> args;  // after the binary
};

// Medians of one binary's cases: wall times and per-frame stages.
struct Timings {
  std::map<std::string, std::vector<double>> walls;
  std::map<std::string, std::map<std::string, std::vector<double>>> stages;
  double wall(const std::string& c) const {
    const auto it = walls.find(c);
    return it == walls.end() ? NAN : analysis::median(it->second);
  }
  double stage(const std::string& c, const std::string& s) const {
    const auto it = stages.find(c);
    if (it == stages.end() || !it->second.count(s)) return NAN;
    return analysis::median(it->second.at(s));
  }
};

// Runs one case with `binary` into `out`: its wall time, and (a recording) its stages from its metadata.
void time_case(const fs::path& binary, const Case& c, const fs::path& out, Timings& t, std::string& row) {
  std::vector<std::string> argv = {binary.string()};
  argv.insert(argv.end(), c.args.begin(), c.args.end());
  argv.insert(argv.end(), {"--out", out.string()});
  const auto t0 = std::chrono::steady_clock::now();
  const int status = run_process(argv);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (status != 0)
    throw core::RuntimeFault("bench record: `" + c.name + "` with " + binary.string() + " failed (exit " +
                             std::to_string(status) + ")");
  t.walls[c.name].push_back(wall);
  row += c.name + "," + "%REPEAT%," + core::format_g(wall, 5) + ",%RATIO%,";
  if (c.args.front() == "run") {
    row += "0,,,,,,";
  } else {
    const io::Run rec = io::Run::open(out, "bench record");
    const toml::table& m = rec.metadata();
    row += std::to_string(m["run"]["frames"].value_or<std::int64_t>(0));
    for (const char* s : kStages) {
      const double v = m["run"][std::string("ms_per_frame_") + s].value_or(0.0);
      t.stages[c.name][s].push_back(v);
      row += "," + core::format_g(v, 4);
    }
  }
  std::error_code ec;
  fs::remove_all(out, ec);
  fs::remove(fs::path(out.string() + ".mp4"), ec);
  fs::remove(io::output_record_path(fs::path(out.string() + ".mp4")), ec);
}

void print_table(const std::string& who, const std::vector<Case>& cases, const Timings& t) {
  std::printf("%s\n%-16s %10s %8s %9s %9s %11s %10s %10s %8s\n", who.c_str(), "case", "wall [s]", "x run",
              "sim", "draw", "readback", "convert", "encode", "png");
  std::printf("%-16s %10s %8s %9s %9s %11s %10s %10s %8s\n", "", "", "", "ms/frame", "ms/frame", "ms/frame",
              "ms/frame", "ms/frame", "ms/frame");
  const double run_wall = t.wall("run");
  for (const auto& c : cases) {
    const double w = t.wall(c.name);
    std::printf("%-16s %10.2f %8.2f", c.name.c_str(), w, c.name == "png_1080p" ? NAN : w / run_wall);
    for (const char* s : kStages) std::printf(" %9.2f", t.stage(c.name, s));
    std::printf("\n");
  }
}

}  // namespace

// A stage against its committed reference: "" when within kSlowed, else the flag's text (app/commands tests).
std::string slowed_stage(const std::string& name, const std::string& stage, double measured,
                         double reference) {
  if (!(reference > 0) || !(measured > 0) || measured <= kSlowed * reference) return "";
  char text[200];
  std::snprintf(text, sizeof text, "SLOWED: %s %s %.2f ms/frame against %.2f committed (%.1fx, limit %.1fx)",
                name.c_str(), stage.c_str(), measured, reference, measured / reference, kSlowed);
  return text;
}

namespace {

// Each stage of this build against docs/filming/reference.csv (case,stage,ms_per_frame,machine,commit): the
// flags printed; returns how many stages are slowed.
int compare_with_reference(const std::string& path, const std::vector<Case>& cases, const Timings& t) {
  const io::CsvTable ref = io::CsvTable::read(path, "filming reference");
  std::printf("against %s (%s, %s):\n", path.c_str(), ref.rows() ? ref.text(0, "machine").c_str() : "-",
              ref.rows() ? ref.text(0, "commit").c_str() : "-");
  int slowed = 0;
  for (size_t r = 0; r < ref.rows(); ++r) {
    const std::string name = ref.text(r, "case"), stage = ref.text(r, "stage");
    bool known = false;
    for (const auto& c : cases) known = known || c.name == name;
    if (!known) continue;
    const double measured = stage == "wall_ratio" ? t.wall(name) / t.wall("run") : t.stage(name, stage);
    const double reference = ref.num(r, "ms_per_frame");
    const std::string flag = slowed_stage(name, stage, measured, reference);
    std::printf("  %-16s %-10s %8.2f against %8.2f  %s\n", name.c_str(), stage.c_str(), measured, reference,
                flag.empty() ? "ok" : "SLOWED");
    if (!flag.empty()) std::fprintf(stderr, "siloscope: %s\n", flag.c_str()), ++slowed;
  }
  return slowed;
}

// --elements: the draw stage of 4 s recordings with one look at a time, at 720p and 1080p.
int bench_elements(const RecordBenchOptions& o, const fs::path& self, const std::string& scene,
                   const fs::path& tmp) {
  const std::vector<std::pair<std::string, std::vector<std::string>>> looks = {
      {"none", {"--overlay", "none"}},
      {"time", {"--overlay", "time"}},
      {"counts", {"--overlay", "counts"}},
      {"rate", {"--overlay", "rate"}},
      {"timer", {"--overlay", "timer"}},
      {"arch", {"--overlay", "arch"}},
      {"legend", {"--overlay", "legend"}},
      {"scale", {"--overlay", "scale"}},
      {"events", {"--overlay", "events"}},
      {"zoombox", {"--overlay", "zoombox"}},
      {"plot", {"--overlay", "plot"}},
      {"colorbar", {"--overlay", "colorbar", "--color", "speed"}},
      {"ids", {"--overlay", "ids"}},
      {"all (default)", {"--overlay", "all"}},
      {"all+plot", {"--overlay", "all+plot"}},
      {"force chains", {"--overlay", "all", "--force-chains", "2"}},
      {"trails", {"--overlay", "all", "--track", "1,2,3,4,5,6,7,8,9,10"}},
      {"annotations",
       {"--overlay", "all", "--annotate", "0:4:0,0.3:the outlet", "--annotate", "1:3:0.3,1:x"}},
  };
  std::string csv = "look,size,repeat,ms_draw\n";
  std::printf("siloscope %s, draw stage per look (ms per frame, medians of %d; 4 s of %s)\n",
              io::version_string().c_str(), o.repeats, scene.c_str());
  std::printf("%-16s %10s %10s\n", "look", "720p", "1080p");
  for (const auto& [name, args] : looks) {
    std::printf("%-16s", name.c_str());
    for (const char* size : {"1280x720", "1920x1080"}) {
      std::vector<double> ms;
      for (int k = 0; k < o.repeats; ++k) {
        core::throw_if_interrupted();
        Case c{name, {"record", scene, "--quiet", "--duration", "4", "--size", size}};
        c.args.insert(c.args.end(), args.begin(), args.end());
        Timings t;
        std::string row;
        time_case(self, c, tmp / "look", t, row);
        ms.push_back(t.stage(name, "draw"));
        csv +=
            "\"" + name + "\"," + size + "," + std::to_string(k) + "," + core::format_g(ms.back(), 4) + "\n";
      }
      std::printf(" %10.2f", analysis::median(ms));
      std::fflush(stdout);
    }
    std::printf("\n");
  }
  if (!o.csv.empty()) io::write_file_atomic(o.csv, csv);
  return 0;
}

int bench_record(const RecordBenchOptions& o) {
  if (!o.csv.empty()) io::check_destination(o.csv, true, "CSV file", io::OutputKind::Csv, "", false);
  const double duration = o.scene.duration.value_or(20.0);
  if (!(duration > 0 && duration <= 600)) throw core::InputError("--duration must be in (0, 600] s");
  const std::string scene =
      o.scene.path.empty() ? (share_dir() / "scenes" / "paper.toml").string() : o.scene.path;
  o.scene.load();  // validated before any work
  if (!o.binary.empty() && ::access(o.binary.c_str(), X_OK) != 0)
    throw core::InputError("--binary " + o.binary + ": not an executable file");
  std::string reference = o.reference == "none" ? "" : o.reference;
  if (o.reference.empty() && fs::exists("docs/filming/reference.csv"))
    reference = "docs/filming/reference.csv";
  if (!reference.empty() && !fs::exists(reference))
    throw core::InputError("--reference " + reference +
                           ": no such file (docs/filming/reference.csv of a clone)");
  const fs::path self = self_exe();
  const fs::path tmp = fs::temp_directory_path() / ("siloscope_bench_record_" + std::to_string(::getpid()));
  fs::create_directories(tmp);
  struct Cleanup {
    fs::path p;
    ~Cleanup() {
      std::error_code ec;
      fs::remove_all(p, ec);
    }
  } cleanup{tmp};
  if (o.elements) return bench_elements(o, self, scene, tmp);
  auto args = [&](const char* command, double seconds, std::vector<std::string> extra) {
    std::vector<std::string> a = {command, scene, "--quiet", "--duration", core::format_g(seconds)};
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
  // This build and the other interleaved, case by case: both see the same moments of a shared machine.
  std::vector<fs::path> binaries = {self};
  if (!o.binary.empty()) binaries.push_back(o.binary);
  std::vector<Timings> timings(binaries.size());
  std::vector<std::vector<std::string>> rows(binaries.size());
  for (int k = 0; k < o.repeats; ++k)
    for (const auto& c : cases)
      for (size_t b = 0; b < binaries.size(); ++b) {
        std::string row = (b == 0 ? "this," : "other,");
        time_case(binaries[b], c, tmp / c.name, timings[b], row);
        rows[b].push_back(row.replace(row.find("%REPEAT%"), 8, std::to_string(k)));
      }
  std::printf("siloscope %s, bench record: %s, %g s of discharge, medians of %d\n",
              io::version_string().c_str(), scene.c_str(), duration, o.repeats);
  print_table("this build: " + self.string(), cases, timings[0]);
  if (binaries.size() > 1) {
    print_table("other build: " + o.binary, cases, timings[1]);
    std::printf("this / other, medians of this run:\n%-16s %8s", "case", "x run");
    for (const char* s : kStages) std::printf(" %9s", s);
    std::printf("\n");
    for (const auto& c : cases) {
      const double rr = (timings[0].wall(c.name) / timings[0].wall("run")) /
                        (timings[1].wall(c.name) / timings[1].wall("run"));
      std::printf("%-16s %8.2f", c.name.c_str(), c.name == "run" ? 1.0 : rr);
      for (const char* s : kStages)
        std::printf(" %9.2f", timings[0].stage(c.name, s) / timings[1].stage(c.name, s));
      std::printf("\n");
    }
  }
  std::printf(
      "targets: record_1080p30 <= 1.4x run, record_720p30 <= 1.2x run (ratios of medians of this run)\n");
  int slowed = 0;
  if (!reference.empty()) slowed = compare_with_reference(reference, cases, timings[0]);
  if (!o.csv.empty()) {
    std::string csv = std::string(kHeader) + "\n";
    for (size_t b = 0; b < binaries.size(); ++b)
      for (auto r : rows[b]) {
        const std::string name = r.substr(r.find(',') + 1, r.find(',', r.find(',') + 1) - r.find(',') - 1);
        const double ratio = timings[b].wall(name) / timings[b].wall("run");
        r.replace(r.find("%RATIO%"), 7, name == "png_1080p" ? "" : core::format_g(ratio, 4));
        csv += r + "\n";
      }
    io::write_file_atomic(o.csv, csv);
    std::printf("written %s\n", o.csv.c_str());
  }
  return slowed > 0 ? 1 : 0;
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
  cmd->add_option("--binary", o->binary,
                  "another siloscope binary (e.g. an older build) timed in the same run, case by case");
  cmd->add_option(
      "--reference", o->reference,
      "the committed per-stage figures (default: docs/filming/reference.csv when run from a clone); "
      "a stage over 1.5x its reference is flagged and the command exits 1");
  cmd->add_flag("--elements", o->elements,
                "the draw stage per overlay element, force chains, trails and notes, at 720p and 1080p");
  cmd->callback([o, &action] { action = [o] { return bench_record(*o); }; });
}

}  // namespace app
