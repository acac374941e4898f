// The command frame (app/services/commands.h): every row of the command table, present and future, answers
// --help and --version, is named in the usage line, and stops on Ctrl-C with exit 130 and nothing
// half-written, whether the signal comes before it starts or while it works. The rows are read from the table
// itself: a new command is covered without a line here (its example must run on the fixtures below).
#include <catch2/catch.hpp>

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <thread>

#include "app/services/commands.h"
#include "helpers.h"
#include "io/manifest.h"
#include "io/metadata.h"

extern char** environ;

namespace fs = std::filesystem;

namespace {

const std::string kSource = SILOSCOPE_SOURCE_DIR;

// The inputs the table's examples name, made once: a recording, a run without a trajectory, a tracks file,
// an inspector script, and the committed paper campaign's analysis.
struct Fixtures {
  fs::path dir;
  std::map<std::string, std::string> values;
  Fixtures() {
    dir = test::temp_dir("frame_fixtures");
    const std::string rec = (dir / "rec").string(), run = (dir / "run").string();
    // One panel, no overlay: a movie detect calibrates by itself.
    REQUIRE(test::cli("record " + test::kScene +
                      " --duration 20 --size 640x360 --camera outlet --overlay none --quiet --out " + rec)
                .code == 0);
    REQUIRE(test::cli("run " + test::kScene + " --duration 8 --seed 1 --quiet --out " + run).code == 0);
    REQUIRE(test::cli("detect " + rec + ".mp4 --frames 0:60 --quiet --out " + (dir / "tracks.csv").string())
                .code == 0);
    fs::create_directories(dir / "results");
    REQUIRE(test::cli("run " + test::kScene + " --duration 3 --seed 2 --quiet --out " +
                      (dir / "results" / "a").string())
                .code == 0);
    std::ofstream(dir / "clip.txt") << "export clip-{frame}.mp4 0 150 1920x1080 30\n";
    values = {{"{scene}", test::kScene},
              {"{recording}", rec},
              {"{run}", run},
              {"{campaign}", kSource + "/assets/campaigns/quick.toml"},
              {"{results}", (dir / "results").string()},
              {"{analysis}", kSource + "/docs/campaigns/paper/analysis"},
              {"{video}", rec + ".mp4"},
              {"{tracks}", (dir / "tracks.csv").string()},
              {"{script}", (dir / "clip.txt").string()}};
  }
};

Fixtures& fixtures() {
  static Fixtures f;
  return f;
}

// The example's words with the placeholders filled in; {out} is `out`.
std::vector<std::string> example_args(const app::Command& c, const fs::path& out) {
  std::vector<std::string> args;
  std::istringstream words(c.example);
  for (std::string w; words >> w;) {
    for (const auto& [key, value] : fixtures().values)
      for (size_t at; (at = w.find(key)) != std::string::npos;) w.replace(at, key.size(), value);
    for (size_t at; (at = w.find("{out}")) != std::string::npos;) w.replace(at, 5, out.string());
    args.push_back(w);
  }
  return args;
}

// Start the binary with `args` in `cwd`; with `blocked`, SIGINT is blocked in the child from the start, so a
// signal sent at once waits for the frame to unblock it.
pid_t start(const std::vector<std::string>& args, const fs::path& cwd, bool blocked) {
  std::vector<std::string> argv = {test::kBin};
  argv.insert(argv.end(), args.begin(), args.end());
  std::vector<char*> cargs;
  for (auto& a : argv) cargs.push_back(a.data());
  cargs.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addchdir_np(&actions, cwd.c_str());
  const std::string log = (cwd / "log.txt").string();
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  sigset_t mask;
  sigemptyset(&mask);
  if (blocked) sigaddset(&mask, SIGINT);
  posix_spawnattr_setsigmask(&attr, &mask);
  posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETSIGMASK);
  pid_t pid = 0;
  REQUIRE(posix_spawn(&pid, cargs[0], &actions, &attr, cargs.data(), environ) == 0);
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attr);
  return pid;
}

// The CPU seconds (user + system) of a process and the children it runs now (a figure script works in a
// child), from /proc; -1 once the process has exited.
double cpu_seconds(pid_t pid) {
  const std::string proc = "/proc/" + std::to_string(pid);
  std::ifstream in(proc + "/stat");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const size_t close = text.rfind(')');
  if (close == std::string::npos) return -1;
  std::istringstream rest(text.substr(close + 2));
  std::string field;
  std::vector<std::string> f;
  while (rest >> field) f.push_back(field);
  if (f.size() < 13 || f[0] == "Z") return -1;
  double cpu = (std::stod(f[11]) + std::stod(f[12])) / static_cast<double>(sysconf(_SC_CLK_TCK));
  std::ifstream children(proc + "/task/" + std::to_string(pid) + "/children");
  for (pid_t child; children >> child;) cpu += std::max(0.0, cpu_seconds(child));
  return cpu;
}

// Exit code of the child, waiting at most `seconds`; -1 (and the child killed) when it did not end.
int wait_for(pid_t pid, double seconds) {
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  int status = 0;
  while (std::chrono::steady_clock::now() < until) {
    if (waitpid(pid, &status, WNOHANG) == pid)
      return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  kill(pid, SIGKILL);
  waitpid(pid, &status, 0);
  return -1;
}

// What a stopped command may leave in `dir`: its log, and outputs that are whole (a directory whose
// manifest verifies: record and run keep what they filmed, marked interrupted). Returns what is wrong.
std::string leftovers(const fs::path& dir) {
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    for (const char* tmp : {".partial", ".tiles-", ".frame-resim-", ".old-", ".tmp", ".table-", ".key-"})
      if (name.find(tmp) != std::string::npos) return "left " + e.path().string();
  }
  for (const auto& e : fs::directory_iterator(dir)) {
    if (!e.is_directory()) continue;
    if (fs::exists(e.path() / "campaign.toml")) {  // a sweep's results: each finished realization whole
      if (!fs::exists(e.path() / "runs")) continue;
      const std::string runs = leftovers(e.path() / "runs");
      if (!runs.empty()) return runs;
      continue;
    }
    if (e.path().filename() == "runs" || e.path().filename().string()[0] == 'p') {  // a sweep's points
      const std::string inner = leftovers(e.path());
      if (!inner.empty()) return inner;
      continue;
    }
    io::Manifest m;
    if (!io::read_manifest(e.path(), m)) return e.path().string() + " has no manifest: half-written";
    const std::string why = io::manifest_mismatch(e.path(), m);
    if (!why.empty()) return e.path().string() + ": " + why;
  }
  return "";
}

std::string slurp_log(const fs::path& dir) {
  return test::slurp(dir / "log.txt");
}

}  // namespace

TEST_CASE("every command of the table answers --help and --version and is in the usage line",
          "[app][frame][heavy]") {
  const std::string version = io::version_string();
  const auto usage = test::cli("");
  CHECK(usage.code == 2);
  for (const app::Command& c : app::command_table()) {
    INFO(c.name);
    const auto v = test::cli(std::string(c.name) + " --version");
    CHECK(v.code == 0);
    CHECK_THAT(v.output, Catch::Contains(version));
    const auto h = test::cli(std::string(c.name) + " --help");
    CHECK(h.code == 0);
    CHECK_THAT(h.output, Catch::Contains(c.help));
    CHECK_THAT(usage.output, Catch::Contains(c.name));
    // A wrong option: exit 2, naming the command's own help.
    const auto bad = test::cli(std::string(c.name) + " --no-such-option");
    CHECK(bad.code == 2);
    CHECK_THAT(bad.output, Catch::Contains(std::string("siloscope ") + c.name + " --help"));
  }
}

TEST_CASE("every command stops on Ctrl-C with exit 130 and nothing half-written", "[app][frame][slow]") {
  (void)fixtures();
  for (const app::Command& c : app::command_table()) {
    INFO(c.name << ": " << c.example);
    // A signal waiting before the command starts: it runs nothing.
    {
      const fs::path d = test::temp_dir(std::string("sigint_early_") + c.name);
      const pid_t pid = start(example_args(c, d / "out"), d, true);
      kill(pid, SIGINT);
      const int code = wait_for(pid, 20);
      INFO(slurp_log(d));
      CHECK(code == 130);
      CHECK_FALSE(fs::exists(d / "out"));
      CHECK(leftovers(d).empty());
    }
    if (!c.long_running) continue;
    // While it works: once it has spent 0.3 s of CPU, it stops within seconds and cleans up.
    const fs::path d = test::temp_dir(std::string("sigint_work_") + c.name);
    const pid_t pid = start(example_args(c, d / "out"), d, false);
    double cpu = 0;
    for (int k = 0; k < 3000 && (cpu = cpu_seconds(pid)) >= 0 && cpu < 0.3; ++k)
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    REQUIRE(cpu >= 0.3);  // still working: the example is long enough to be interrupted
    const auto sent = std::chrono::steady_clock::now();
    kill(pid, SIGINT);
    const int code = wait_for(pid, 30);
    const double took = std::chrono::duration<double>(std::chrono::steady_clock::now() - sent).count();
    INFO(slurp_log(d));
    CHECK(code == 130);
    CHECK(took < 10);
    CHECK(leftovers(d) == "");
  }
}
