// siloscope breaking RUN --out DIR: the kick that breaks each arrested clog's arch (sim/breaking.h), one
// row per clog in DIR/breaking.csv with the arch's descriptors and load, beside DIR/metadata.toml (the run's
// scene, the test's options, the version). Clogs run in parallel, one copy of the state per try.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <exception>
#include <mutex>
#include <thread>

#include "app/services/cli.h"
#include "core/error.h"
#include "core/format.h"
#include "core/interrupt.h"
#include "io/metadata.h"
#include "io/output.h"
#include "io/run.h"
#include "sim/breaking.h"

namespace app {

namespace {

struct BreakingOptions {
  std::string run, out;
  std::vector<int> clogs;  // rows of clogs.csv (empty: every arrested clog)
  int jobs = 0;            // 0: every core
  bool force = false;
  std::string kick = "uniform";
  sim::BreakOptions test;
};

constexpr const char* kHeader =
    "clog,t_s,outcome,grains,span_m,aspect_rise_over_half_span,theta_max_deg,defects,load_N,held_N,"
    "dv_held_m_s,dv_broke_m_s,trials\n";

std::string row(const sim::BreakResult& r) {
  auto g = [](double v) { return std::isnan(v) ? std::string() : core::format_g(v, 6); };
  const bool measured = r.outcome == "broken" || r.outcome == "held";
  return std::to_string(r.clog) + "," + g(r.t) + "," + r.outcome + "," + std::to_string(r.arch.size()) + "," +
         g(r.shape.span) + "," + g(r.shape.aspect) + "," + g(r.shape.theta_max_deg) + "," +
         std::to_string(r.shape.defects) + "," + g(r.load_N) + "," + g(r.held_N) + "," +
         (measured ? g(r.dv_held) : "") + "," + (r.outcome == "broken" ? g(r.dv_broke) : "") + "," +
         std::to_string(r.trials) + "\n";
}

// The clogs to test: the rows asked for (each must be an arrested clog), or every arrested one.
std::vector<int> clogs_to_test(const BreakingOptions& o, const core::Events& ev) {
  std::vector<int> rows = o.clogs;
  if (rows.empty()) {
    for (size_t k = 0; k < ev.clogs.size(); ++k)
      if (ev.clogs[k].arrested) rows.push_back(static_cast<int>(k) + 1);
    return rows;
  }
  for (int k : rows) {
    if (k < 1 || static_cast<size_t>(k) > ev.clogs.size())
      throw core::InputError("--clog " + std::to_string(k) + ": the run has " +
                             std::to_string(ev.clogs.size()) + " clogs (1 to " +
                             std::to_string(ev.clogs.size()) + ")");
    if (!ev.clogs[static_cast<size_t>(k) - 1].arrested)
      throw core::InputError(
          "--clog " + std::to_string(k) +
          ": that clog was never arrested (the outlet never came to rest): nothing to break");
  }
  return rows;
}

std::vector<sim::BreakResult> test_all(const BreakingOptions& o, const core::Model& model,
                                       const core::Events& ev, const std::vector<int>& rows) {
  std::vector<sim::BreakResult> results(rows.size());
  std::atomic<size_t> next{0}, done{0};
  std::exception_ptr failure;
  std::mutex m;
  auto work = [&] {
    for (size_t k; (k = next++) < rows.size();) {
      try {
        const int c = rows[k];
        results[k] = sim::break_clog(model, ev.clogs[static_cast<size_t>(c) - 1], c, o.test);
        std::lock_guard<std::mutex> lock(m);
        std::fprintf(stderr, "clog %d: %s (%d tries), %zu of %zu\n", c, results[k].outcome.c_str(),
                     results[k].trials, ++done, rows.size());
      } catch (...) {
        std::lock_guard<std::mutex> lock(m);
        if (!failure) failure = std::current_exception();
        next = rows.size();
      }
    }
  };
  const int jobs = std::max(1, o.jobs > 0 ? o.jobs : static_cast<int>(std::thread::hardware_concurrency()));
  std::vector<std::thread> pool;
  for (int j = 0; j < std::min<int>(jobs, static_cast<int>(rows.size())); ++j) pool.emplace_back(work);
  for (auto& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
  return results;
}

int breaking(BreakingOptions o) {
  o.test.random = o.kick == "random";
  const io::Run run = io::Run::open(o.run, "breaking", io::Run::kEvents);
  const core::Model& model = run.model();
  if (model.setup.drive.vibrating())
    throw core::InputError(o.run + ": the scene vibrates its container; the break test kicks a still one");
  if (!(o.test.dv_first > 0) || !(o.test.dv_max >= o.test.dv_first))
    throw core::InputError("--dv-first " + core::format_g(o.test.dv_first) + " --dv-max " +
                           core::format_g(o.test.dv_max) + ": expected 0 < FIRST <= MAX (m/s)");
  const std::vector<int> rows = clogs_to_test(o, run.events());
  const io::fs::path out = io::output_path(o.out);
  io::check_not_input(out, {run.dir()}, "break test");
  io::OutputDir dir(out.string(), o.force, io::DirKind::Analysis);
  const std::vector<sim::BreakResult> results = test_all(o, model, run.events(), rows);
  std::string csv = kHeader;
  for (const auto& r : results) csv += row(r);
  io::write_file_atomic(dir.file("breaking.csv"), csv);
  io::RunInfo info{command_line(),
                   {{"run", run.dir().filename().string()},
                    {"kick", o.kick},
                    {"settle_s", o.test.settle},
                    {"window_s", o.test.window},
                    {"dv_first_m_s", o.test.dv_first},
                    {"dv_max_m_s", o.test.dv_max},
                    {"bisections", static_cast<long>(o.test.bisections)},
                    {"clogs_tested", static_cast<long>(rows.size())}},
                   {},
                   {}};
  io::write_file_atomic(dir.file(io::run_file::kMetadata), io::metadata_toml(model, info));
  dir.commit();
  long broken = 0;
  for (const auto& r : results) broken += r.outcome == "broken";
  std::printf("%zu arrested clogs tested, %ld broken within %.2f m/s -> %s/breaking.csv\n", results.size(),
              broken, o.test.dv_max, out.c_str());
  return 0;
}

}  // namespace

void define_breaking_command(CLI::App& command, Action& action) {
  auto o = std::make_shared<BreakingOptions>();
  CLI::App* cmd = &command;
  cmd->add_option("run", o->run, "a run or recording directory of a scene whose container stands still")
      ->required();
  cmd->add_option("--out", o->out, "the output directory (breaking.csv, metadata.toml)")->required();
  cmd->add_option("--clog", o->clogs, "only these clogs (rows of clogs.csv, from 1; each arrested)");
  cmd->add_option("--settle", o->test.settle, "s with no drive before the kick")
      ->check(number_in(0, 10, "s"))
      ->capture_default_str();
  cmd->add_option(
         "--window", o->test.window,
         "s in which an exit means the clog broke, from when the lifted grains are back down (2 DV / g)")
      ->check(number_in(0.05, 10, "s"))
      ->capture_default_str();
  cmd->add_option("--dv-first", o->test.dv_first, "m/s, the first kick tried (doubled until one breaks)")
      ->check(number_in(1e-4, 10, "m/s"))
      ->capture_default_str();
  cmd->add_option("--dv-max", o->test.dv_max, "m/s, the strongest kick tried")
      ->check(number_in(1e-4, 100, "m/s"))
      ->capture_default_str();
  cmd->add_option("--bisections", o->test.bisections, "halvings of the bracket once a kick broke the clog")
      ->check(whole_number(0, 30))
      ->capture_default_str();
  cmd->add_option(
         "--kick", o->kick,
         "uniform: every grain lifted by DV at once; random: the scene's kick law as velocity changes "
         "up to DV (each grain its own, plus one shared)")
      ->check(CLI::IsMember({"uniform", "random"}))
      ->capture_default_str();
  cmd->add_option("--jobs", o->jobs, "clogs tested at once (0: every core)")->check(whole_number(0, 1024));
  cmd->add_flag("--force", o->force, "replace an earlier break test's directory");
  cmd->callback([o, &action] { action = [o] { return breaking(*o); }; });
}

}  // namespace app
