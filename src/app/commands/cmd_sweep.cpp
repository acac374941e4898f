// siloscope sweep CAMPAIGN.toml: run every realization of a campaign on all local cores, resumably; or, with
// --emit-jobs, write the same commands as a job list for GNU parallel and a SLURM array script.
//
// Each realization is one `siloscope run` process writing its own directory atomically, so a crash loses at
// most the realizations in flight, a rerun skips what is finished, and results do not depend on how the work
// was split (seeds come from the campaign, not from the worker).
//
// Over 400 lines because resuming, status and the local worker pool share the campaign's on-disk layout,
// which is kept private to this file; the job list and SLURM script of --emit-jobs are in sweep_jobs.cpp.
#include <fcntl.h>
#include <spawn.h>
#include <sys/file.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <thread>

#include <toml++/toml.h>

#include "app/commands/sweep_jobs.h"
#include "app/services/campaign.h"
#include "app/services/cli.h"
#include "app/services/process.h"
#include "app/services/run_outputs.h"
#include "app/services/terminal.h"
#include "core/error.h"
#include "core/format.h"
#include "core/median.h"
#include "io/manifest.h"
#include "io/metadata.h"
#include "io/output.h"
#include "io/run.h"

extern char** environ;

namespace app {

namespace {
namespace fs = std::filesystem;

struct SweepOptions {
  std::string campaign, results, binary;
  int workers = 0;
  int up_to = 0;             // run only realizations 0..up_to-1 of every point (0: all)
  double task_minutes = 30;  // --emit-jobs: the target length of one array task
  int max_array = 1000;      // --emit-jobs: at most this many array tasks (SLURM's MaxArraySize is 1001)
  bool emit_jobs = false, dry_run = false, no_analyze = false, quiet = false, status = false;
};

using Job = SweepJob;

// Holds an exclusive lock on RESULTS/.lock for the life of the sweep.
class ResultsLock {
 public:
  explicit ResultsLock(const fs::path& dir) {
    fd_ = ::open((dir / ".lock").c_str(), O_CREAT | O_RDWR | O_CLOEXEC, 0644);  // workers must not inherit it
    if (fd_ < 0 || ::flock(fd_, LOCK_EX | LOCK_NB) != 0)
      throw core::InputError("results directory " + dir.string() + " is in use by another sweep");
  }
  ~ResultsLock() {
    if (fd_ >= 0) ::close(fd_);
  }

 private:
  int fd_ = -1;
};

// A campaign file without its `realizations = N` line: raising (or lowering) the number of realizations keeps
// every seed and directory of the realizations already run, so such a change may resume the same results.
std::string without_realizations(const std::string& text) {
  std::string out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    size_t a = line.find_first_not_of(" \t");
    if (a != std::string::npos && line.compare(a, 12, "realizations") == 0) continue;
    out += line + "\n";
  }
  return out;
}

// Prepare the results directory: the campaign file it belongs to, the scene of each point. Refuses a
// directory that holds a different campaign.
// A run directory under construction: NAME.partial-PID. Its PID is alive while a run is writing it.
bool partial_is_live(const fs::path& p) {
  const std::string name = p.filename().string();
  const pid_t pid = static_cast<pid_t>(std::atol(name.substr(name.rfind('-') + 1).c_str()));
  return pid > 0 && ::kill(pid, 0) == 0;
}

// The campaign.toml a results directory was made for ("" if none). The same campaign when the text differs
// at most in `realizations`, or when it parses to the same seed and the same points in the same order (a
// comment, key order or spacing changed): their seeds and directories are then those already run. Anything
// else is refused, naming the difference.
std::string stamped_campaign(const Campaign& c, const fs::path& dir) {
  const fs::path stamp = dir / "campaign.toml";
  if (!fs::exists(stamp)) return "";
  core::check_text_file(stamp.string(), "campaign file", "");
  std::ifstream in(stamp);
  std::string old((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (without_realizations(old) == without_realizations(c.text)) return old;
  auto refuse = [&](const std::string& why) {
    return core::InputError("results directory " + dir.string() + " holds another campaign: " + why +
                            " (its campaign.toml against " + c.path +
                            "); choose another --results directory");
  };
  Campaign prev;
  try {
    prev = parse_campaign(old, c.path);  // anchored where the campaign file is: its scene path is relative
  } catch (const core::InputError& e) {
    // The results' own copy is what failed to parse (cut or edited), not the campaign file given: named so.
    std::string why = e.what();
    if (why.rfind(c.path, 0) == 0) why = stamp.string() + why.substr(c.path.size());
    throw core::InputError(
        "results directory " + dir.string() + ": its copy of the campaign does not parse (" + why +
        "): cut or edited after sweep wrote it? Restore it (a copy of the campaign file the results were "
        "made with) or choose another --results directory");
  }
  if (prev.seed != c.seed)
    throw refuse("seed " + std::to_string(prev.seed) + " there, " + std::to_string(c.seed) + " here");
  if (prev.points.size() != c.points.size())
    throw refuse(std::to_string(prev.points.size()) + " points there, " + std::to_string(c.points.size()) +
                 " here");
  for (size_t p = 0; p < c.points.size(); ++p)
    if (prev.points[p].label != c.points[p].label)
      throw refuse("point " + std::to_string(p) + " is " + prev.points[p].label + " there, " +
                   c.points[p].label + " here");
  std::fprintf(stderr, "siloscope: %s was edited without changing its points or seeds; resuming\n",
               c.path.c_str());
  return old;
}

// Each point's scene as its realizations ran (scenes/pNNN.toml) must be the scene the campaign gives now:
// an edited base scene would otherwise mix two scenes in one point. Compared as parsed scenes, key by key.
void check_point_scenes(const Campaign& c, const fs::path& dir) {
  for (size_t p = 0; p < c.points.size(); ++p) {
    char name[32];
    std::snprintf(name, sizeof name, "p%03zu.toml", p);
    const fs::path f = dir / "scenes" / name;
    if (!fs::exists(f)) continue;
    const auto was = core::scene_values(core::load_scene(f.string()));
    const auto now = core::scene_values(c.points[p].scene);
    for (const auto& [key, value] : now) {
      const auto it = was.find(key);
      if (key == "seed" || (it != was.end() && it->second == value)) continue;
      throw core::InputError("results directory " + dir.string() + ": point " +
                             std::string(name).substr(0, 4) + " (" + c.points[p].label + ") ran with " + key +
                             " = " + (it == was.end() ? std::string("(absent)") : it->second) +
                             ", the campaign now gives " + value +
                             " (its base scene or grid changed since); choose another --results "
                             "directory, or put the scene back");
    }
  }
}

void prepare_results(const Campaign& c, const fs::path& dir) {
  std::error_code ec;
  fs::create_directories(dir / "scenes", ec);
  if (ec) throw core::InputError("results directory " + dir.string() + ": cannot create it: " + ec.message());
  const bool restamp = stamped_campaign(c, dir) != c.text;
  check_point_scenes(c, dir);
  if (restamp) io::write_file_atomic(dir / "campaign.toml", c.text);
  for (size_t p = 0; p < c.points.size(); ++p) {
    char name[32];
    std::snprintf(name, sizeof name, "p%03zu.toml", p);
    std::string text = "# siloscope sweep: point " + std::to_string(p) + " of campaign " + c.name + ": " +
                       c.points[p].label + "\n" + core::scene_toml(c.points[p].scene);
    io::write_file_atomic(dir / "scenes" / name, text);
  }
  // Runs of an earlier sweep that was killed (kill -9) may still be going: wait for those (they will finish
  // their directories), and remove the leftovers of the dead ones.
  if (!fs::exists(dir / "runs")) return;
  std::vector<fs::path> partial;
  for (const auto& e : fs::recursive_directory_iterator(dir / "runs", ec))
    if (e.path().filename().string().find(".partial-") != std::string::npos) partial.push_back(e.path());
  for (const auto& p : partial) {
    bool said = false;
    while (partial_is_live(p) && fs::exists(p)) {
      if (!said)
        std::fprintf(stderr, "siloscope: waiting for a realization left running by an earlier sweep (%s)\n",
                     p.filename().c_str());
      said = true;
      std::this_thread::sleep_for(std::chrono::milliseconds(200));
    }
    fs::remove_all(p, ec);
  }
}

// Where a realization the health monitor refused is recorded (next to where its run would be).
fs::path refused_marker(const fs::path& dir, const Job& j) {
  return dir / (j.dir + ".refused.toml");
}

// Realization-major: every point gets its k-th realization before any gets its (k+1)-th, so a campaign
// stopped at any moment has nearly the same number of realizations at every point. Realizations recorded as
// refused count as settled (`refused` of `done`).
std::vector<Job> pending_jobs(const Campaign& c, const fs::path& dir, const std::string& binary, int up_to,
                              size_t& done, size_t& refused) {
  std::vector<Job> jobs;
  done = refused = 0;
  const int last = up_to > 0 ? std::min(up_to, c.realizations) : c.realizations;
  for (int k = 0; k < last; ++k) {
    for (size_t p = 0; p < c.points.size(); ++p) {
      Job j{p, k, "runs/" + c.run_dir(p, k), {}, ""};
      if (fs::exists(dir / j.dir / io::run_file::kMetadata)) {
        // Finished: counted only while it holds what siloscope wrote (a cut, edited or half-copied run would
        // be believed done and then refused by analyze, or worse, analysed).
        try {
          io::verify_manifest(dir / j.dir, "sweep: realization");
        } catch (const core::InputError& e) {
          throw core::InputError(std::string(e.what()) + "; remove " + (dir / j.dir).string() +
                                 " to run that realization again");
        }
        ++done;
        continue;
      }
      if (fs::exists(refused_marker(dir, j))) {
        ++done, ++refused;
        continue;
      }
      char scene[48];
      std::snprintf(scene, sizeof scene, "scenes/p%03zu.toml", p);
      j.argv = {binary,
                "run",
                scene,
                "--seed",
                std::to_string(c.realization_seed(p, k)),
                "--quiet",
                "--record-refusal",
                "--out",
                j.dir};
      if (c.trajectory_fps > 0) {
        j.argv.push_back("--trajectory-fps");
        j.argv.push_back(core::format_g(c.trajectory_fps));
      }
      for (const auto& a : j.argv) j.line += (j.line.empty() ? "" : " ") + core::shell_quote(a);
      jobs.push_back(j);
    }
  }
  return jobs;
}

// A span of time for a person: "40 s", "12 min", "4.2 h".
std::string span_text(double seconds) {
  char b[32];
  if (seconds < 90)
    std::snprintf(b, sizeof b, "%.0f s", seconds);
  else if (seconds < 5400)
    std::snprintf(b, sizeof b, "%.0f min", seconds / 60);
  else
    std::snprintf(b, sizeof b, "%.1f h", seconds / 3600);
  return b;
}

// sweep --status: how far a campaign has got, read from its results directory alone (while a sweep runs, or
// after SLURM array tasks on other machines), and what is left in hours. Writes nothing.
int print_status(const Campaign& c, const fs::path& dir, int up_to, int workers) {
  if (!fs::is_directory(dir / "runs") || !fs::exists(dir / "campaign.toml"))
    throw core::InputError("--results " + dir.string() + ": no results of campaign " + c.name +
                           " there yet (start it with `siloscope sweep " + c.path + "`)");
  stamped_campaign(c, dir);
  const int last = up_to > 0 ? std::min(up_to, c.realizations) : c.realizations;
  size_t finished = 0, refused = 0;
  std::vector<int> per_point(c.points.size(), 0), refused_at(c.points.size(), 0);
  std::vector<double> walls;
  for (size_t p = 0; p < c.points.size(); ++p)
    for (int k = 0; k < last; ++k) {
      const fs::path run = dir / "runs" / c.run_dir(p, k);
      if (fs::exists(run / io::run_file::kMetadata)) {
        ++finished, ++per_point[p];
        if (double w = realization_wall_s(run / io::run_file::kMetadata); w > 0) walls.push_back(w);
      } else if (fs::exists(run.string() + ".refused.toml")) {
        ++refused, ++per_point[p], ++refused_at[p];
      }
    }
  std::vector<std::string> running;
  size_t dead = 0;
  std::error_code ec;
  for (const auto& e : fs::recursive_directory_iterator(dir / "runs", ec)) {
    const std::string name = e.path().filename().string();
    if (name.find(".partial-") == std::string::npos) continue;
    const std::string rel = fs::relative(e.path(), dir).string();
    if (partial_is_live(e.path()))
      running.push_back(rel.substr(0, rel.find(".partial-")));
    else
      ++dead;
  }
  std::sort(running.begin(), running.end());
  const size_t total = c.points.size() * static_cast<size_t>(last);
  const size_t settled = finished + refused, left = total - settled;
  std::printf(
      "campaign %s in %s: %zu points x %d realizations of %g s%s\n", c.name.c_str(), dir.c_str(),
      c.points.size(), last, c.duration,
      last < c.realizations
          ? (" (--up-to " + std::to_string(last) + " of " + std::to_string(c.realizations) + ")").c_str()
          : "");
  std::printf("  settled   %zu of %zu (%.1f%%): %zu finished, %zu refused by the health monitor\n", settled,
              total, 100.0 * static_cast<double>(settled) / static_cast<double>(total), finished, refused);
  std::string now;
  for (const auto& r : running) now += (now.empty() ? " (" : ", ") + r;
  std::printf(
      "  running   %zu%s%s\n", running.size(), now.empty() ? "" : (now + ")").c_str(),
      dead ? (", and " + std::to_string(dead) + " left by killed runs (removed when the next sweep starts)")
                 .c_str()
           : "");
  const auto [lo, hi] = std::minmax_element(per_point.begin(), per_point.end());
  const size_t fewest = static_cast<size_t>(lo - per_point.begin());
  if (*lo == *hi)
    std::printf("  per point %d settled at every point\n", *lo);
  else
    std::printf("  per point %d to %d settled; fewest at p%03zu %s\n", *lo, *hi, fewest,
                c.points[fewest].label.c_str());
  std::string where;
  for (size_t p = 0; p < c.points.size(); ++p)
    if (refused_at[p] > 0) {
      char b[48];
      std::snprintf(b, sizeof b, "p%03zu: %d", p, refused_at[p]);
      where += (where.empty() ? "" : ", ") + std::string(b);
    }
  if (!where.empty()) std::printf("  refused   %s (runs/pNNN/*.refused.toml)\n", where.c_str());
  if (left == 0) {
    std::printf("  complete  every realization is settled\n");
    return 0;
  }
  if (walls.empty()) {
    std::printf("  time      no finished realization records its wall time yet; no estimate\n");
    return 0;
  }
  const double median = core::median(walls);
  const double core_s = static_cast<double>(left) * median;
  std::printf("  time      median %.1f s wall per realization (settling + discharge; %zu finished runs)\n",
              median, walls.size());
  std::printf("  left      %zu realizations: about %s of one core, %s on %d workers\n", left,
              span_text(core_s).c_str(), span_text(core_s / workers).c_str(), workers);
  return 0;
}

pid_t spawn_job(const Job& j, const fs::path& dir) {
  // The command a job list holds, run from the results directory (no shell), its output kept in logs/.
  char log[64];
  std::snprintf(log, sizeof log, "logs/p%03zu_r%03d.log", j.point, j.index);
  return spawn(j.argv, dir.string(), log);
}

// Run the jobs on `workers` processes: a worker per job, its output in logs/; a refusal by the health monitor
// is counted, a failure named in `failures`; Ctrl-C is passed on to the workers (their finished runs stay).
void run_jobs(const std::vector<Job>& jobs, const fs::path& dir, int workers, bool quiet, size_t done,
              size_t total, size_t& refused, std::vector<std::string>& failures) {
  Progress progress("sweep", static_cast<double>(jobs.size()), !quiet, false);
  std::map<pid_t, size_t> running;
  size_t next = 0, finished = 0;
  bool forwarded = false;
  while (next < jobs.size() || !running.empty()) {
    if (interrupted() && !forwarded) {
      // Ctrl-C from a terminal reaches the workers already; a signal sent to the sweep alone is passed on.
      for (const auto& [pid, job] : running) ::kill(pid, SIGINT);
      forwarded = true;
    }
    while (!interrupted() && next < jobs.size() && static_cast<int>(running.size()) < workers) {
      running[spawn_job(jobs[next], dir)] = next;
      ++next;
    }
    // Polled: a signal landing just before a blocking wait would be passed on only when a worker ends.
    int status = 0;
    pid_t pid = ::waitpid(-1, &status, WNOHANG);
    if (pid == 0) {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
      continue;
    }
    if (pid < 0) {
      if (errno == EINTR) continue;
      break;
    }
    auto it = running.find(pid);
    if (it == running.end()) continue;
    const size_t job_index = it->second;
    const Job& j = jobs[job_index];
    running.erase(it);
    bool ok = WIFEXITED(status) && WEXITSTATUS(status) == 0;
    // A realization an orphan of an earlier (killed) sweep still owns: its run holds the output's lock (exit
    // 75) or finished it first (the directory exists). Adopt the orphan's result, or wait for it and run
    // again.
    if (!ok && !interrupted() && fs::exists(dir / j.dir / io::run_file::kMetadata)) ok = true;
    if (!ok && !interrupted() && WIFEXITED(status) && WEXITSTATUS(status) == 75) {
      if (!quiet)
        std::fprintf(stderr,
                     "\nsiloscope: %s is still being written by an earlier sweep's process; waiting\n",
                     j.dir.c_str());
      std::this_thread::sleep_for(std::chrono::milliseconds(300));
      if (fs::exists(dir / j.dir / io::run_file::kMetadata)) {
        ok = true;
      } else {
        running[spawn_job(j, dir)] = job_index;  // the orphan may have died: try again
        continue;
      }
    }
    // Exit 3: the health monitor refused the realization and the run recorded it (--record-refusal).
    const bool unstable = !ok && !interrupted() && WIFEXITED(status) && WEXITSTATUS(status) == 3 &&
                          fs::exists(refused_marker(dir, j));
    if (unstable) {
      ++refused;
      if (!quiet)
        std::fprintf(stderr, "\nsiloscope: realization %s refused by the health monitor (recorded in %s)\n",
                     j.dir.c_str(), refused_marker(dir, j).c_str());
    } else if (!ok && !interrupted()) {
      char log[64];
      std::snprintf(log, sizeof log, "logs/p%03zu_r%03d.log", j.point, j.index);
      failures.push_back(j.dir + " (exit " +
                         std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status)) +
                         ", see " + (dir / log).string() + ")");
      std::fprintf(stderr, "\nsiloscope: realization %s failed; the others go on\n", failures.back().c_str());
    }
    ++finished;
    char extra[64];
    std::snprintf(extra, sizeof extra, "%zu/%zu realizations", done + finished, total);
    progress.update(static_cast<double>(finished), extra);
  }
  progress.finish();
}

int sweep(const SweepOptions& o) {
  Campaign c = load_campaign(o.campaign);
  const fs::path dir = fs::absolute(o.results.empty() ? fs::path("results") / c.name : fs::path(o.results));
  const std::string binary = o.binary.empty() ? self_exe() : o.binary;
  if (o.dry_run) {
    std::printf("campaign %s: %zu points x %d realizations of %g s\n", c.name.c_str(), c.points.size(),
                c.realizations, c.duration);
    for (size_t p = 0; p < c.points.size(); ++p)
      std::printf("  p%03zu  %-48s mu = %.6g A*m^2  first seed %llu\n", p, c.points[p].label.c_str(),
                  c.points[p].scene.mu, static_cast<unsigned long long>(c.realization_seed(p, 0)));
    return 0;
  }
  const int workers =
      o.workers > 0 ? o.workers : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  if (o.status) return print_status(c, dir, o.up_to, workers);
  std::error_code ec;
  // A directory that holds something but no campaign.toml is not a campaign's results: writing there would
  // mix realizations into a user's files (a leftover .lock of a sweep that died at once is no content).
  if (fs::is_directory(dir, ec) && !fs::exists(dir / "campaign.toml", ec))
    for (const auto& e : fs::directory_iterator(dir, ec))
      if (e.path().filename() != ".lock")
        throw core::InputError("--results " + dir.string() +
                               " is not empty and holds no campaign.toml, so it "
                               "is not this campaign's results (it holds " +
                               e.path().filename().string() + "); choose a new or empty directory");
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir))
    throw core::InputError("--results " + dir.string() + ": cannot create directory: " + ec.message());
  ResultsLock lock(dir);
  prepare_results(c, dir);
  fs::create_directories(dir / "logs");
  size_t done = 0, refused = 0;
  std::vector<Job> jobs = pending_jobs(c, dir, binary, o.up_to, done, refused);
  const size_t total =
      c.points.size() * static_cast<size_t>(o.up_to > 0 ? std::min(o.up_to, c.realizations) : c.realizations);
  if (o.emit_jobs) {
    emit_jobs(c, dir, jobs, o.task_minutes, o.max_array);
    return 0;
  }
  if (!o.quiet)
    std::printf(
        "campaign %s: %zu points x %d realizations; %zu finished (%zu refused by the health monitor: "
        "runs/*/*.refused.toml), %zu to run on %d workers -> %s\n",
        c.name.c_str(), c.points.size(), c.realizations, done, refused, jobs.size(), workers, dir.c_str());

  std::vector<std::string> failures;
  run_jobs(jobs, dir, workers, o.quiet, done, total, refused, failures);
  if (refused > 0)
    std::fprintf(
        stderr,
        "siloscope: %zu realizations refused by the health monitor (runs/*/*.refused.toml; not rerun, "
        "counted by analyze as n_refused)\n",
        refused);
  if (interrupted()) {
    std::fprintf(stderr, "siloscope: sweep interrupted; finished realizations are kept, rerun to resume\n");
    return 130;
  }
  if (!failures.empty()) {
    std::fprintf(stderr, "siloscope: %zu of %zu realizations failed:\n", failures.size(), jobs.size());
    for (const auto& f : failures) std::fprintf(stderr, "  %s\n", f.c_str());
    return 1;
  }
  if (!o.no_analyze)
    analyze_runs({(dir / "runs").string()}, (dir / "analysis").string(), true, o.quiet, false, false,
                 c.extra_point_keys());
  return 0;
}
}  // namespace

void define_sweep_command(CLI::App& command, Action& action) {
  auto o = std::make_shared<SweepOptions>();
  CLI::App* cmd = &command;
  cmd->add_option("campaign", o->campaign, "campaign file, e.g. assets/campaigns/quick.toml")->required();
  cmd->add_option("--results", o->results, "results directory (default: results/NAME)");
  cmd->add_option("--workers", o->workers, "parallel realizations (default: all cores)")
      ->check(whole_number(1, 4096));
  cmd->add_option("--up-to", o->up_to,
                  "run only the first K realizations of every point (a first pass over the whole grid)")
      ->check(whole_number(1, 1000000));
  auto* emit = cmd->add_flag("--emit-jobs", o->emit_jobs,
                             "write jobs.txt (GNU parallel) and jobs.slurm (SLURM array) instead of running");
  cmd->add_option("--task-minutes", o->task_minutes,
                  "with --emit-jobs: realizations per array task to fill this many minutes at the finished "
                  "ones' median wall time")
      ->capture_default_str()
      ->check(number_in(0.1, 10000, "minutes"))
      ->needs(emit);
  cmd->add_option("--max-array", o->max_array,
                  "with --emit-jobs: at most this many array tasks (SLURM's default MaxArraySize is 1001)")
      ->capture_default_str()
      ->check(whole_number(1, 100000000))
      ->needs(emit);
  cmd->add_option("--binary", o->binary, "siloscope binary named in job lists (default: this one)");
  auto* dry = cmd->add_flag("--dry-run", o->dry_run, "print the expanded grid and seeds, run nothing");
  cmd->add_flag("--status", o->status,
                "how far the campaign in --results has got and the hours left; runs and writes nothing")
      ->excludes(dry)
      ->excludes(emit);
  cmd->add_flag("--no-analyze", o->no_analyze, "do not aggregate into RESULTS/analysis at the end");
  cmd->add_flag("--quiet", o->quiet, "print nothing but errors");
  cmd->callback([o, &action] { action = [o] { return sweep(*o); }; });
}

}  // namespace app
