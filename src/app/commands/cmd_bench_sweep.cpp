// siloscope bench sweep CAMPAIGN: the same campaign with 1 and with N workers into fresh directories; prints
// the throughput of each (realizations per wall minute) and their ratio, and writes CSV.
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>

#include "app/services/cli.h"
#include "app/services/process.h"
#include "app/services/run_outputs.h"
#include "app/services/terminal.h"
#include "core/error.h"
#include "io/manifest.h"
#include "io/metadata.h"
#include "io/output.h"

namespace app {

namespace {
namespace fs = std::filesystem;

struct SweepBenchOptions {
  std::string campaign, csv;
  int workers = 2;
};

int bench_sweep(const SweepBenchOptions& o) {
  if (o.workers < 2) throw core::InputError("--workers must be >= 2 (compared with 1)");
  if (!o.csv.empty())
    io::check_destination(o.csv, true, "CSV file", io::OutputKind::Csv, "workers,realizations,wall_s", false);
  std::error_code ec;
  const fs::path tmp = fs::temp_directory_path() / ("siloscope_bench_sweep_" + std::to_string(::getpid()));
  double wall[2] = {0, 0};
  long runs[2] = {0, 0};
  const int workers[2] = {1, o.workers};
  for (int i = 0; i < 2; ++i) {
    const fs::path dir = tmp / ("w" + std::to_string(workers[i]));
    const auto t0 = std::chrono::steady_clock::now();
    const int status = run_process({self_exe(), "sweep", o.campaign, "--quiet", "--no-analyze", "--workers",
                                    std::to_string(workers[i]), "--results", dir.string()});
    wall[i] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (status != 0) {
      fs::remove_all(tmp, ec);
      throw core::RuntimeFault("bench sweep: the sweep with " + std::to_string(workers[i]) +
                               " workers failed");
    }
    for (const auto& e : fs::recursive_directory_iterator(dir / "runs"))
      runs[i] += e.path().filename() == io::kMetadataFile;
  }
  fs::remove_all(tmp, ec);
  const double tp1 = 60 * runs[0] / wall[0], tpn = 60 * runs[1] / wall[1];
  std::printf("siloscope %s, bench sweep %s\n%-10s %12s %14s %22s\n", io::version_string().c_str(),
              o.campaign.c_str(), "workers", "realizations", "wall [s]", "realizations per min");
  std::printf("%-10d %12ld %14.1f %22.2f\n%-10d %12ld %14.1f %22.2f\n", 1, runs[0], wall[0], tp1, o.workers,
              runs[1], wall[1], tpn);
  std::printf("throughput ratio %d / 1 workers: %.2f (target >= 1.9 for 2)\n", o.workers, tpn / tp1);
  if (!o.csv.empty())
    io::write_file_atomic(o.csv, "workers,realizations,wall_s\n1," + std::to_string(runs[0]) + "," +
                                     std::to_string(wall[0]) + "\n" + std::to_string(o.workers) + "," +
                                     std::to_string(runs[1]) + "," + std::to_string(wall[1]) + "\n");
  return 0;
}
}  // namespace

void add_bench_sweep_command(CLI::App& bench, Action& action) {
  auto o = std::make_shared<SweepBenchOptions>();
  auto* cmd = bench.add_subcommand("sweep", "throughput of a campaign with 1 and N workers");
  cmd->add_option("campaign", o->campaign, "campaign file")->required();
  cmd->add_option("--workers", o->workers, "workers to compare with 1")
      ->check(whole_number(1, 256))
      ->capture_default_str();
  cmd->add_option("--csv", o->csv, "CSV output");
  cmd->callback([o, &action] { action = [o] { return bench_sweep(*o); }; });
}

}  // namespace app
