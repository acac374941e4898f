// Helpers shared by the tests that run the real `siloscope` binary or touch files.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace test {

inline const std::string kBin = SILOSCOPE_BINARY;
inline const std::string kScene = std::string(SILOSCOPE_SOURCE_DIR) + "/assets/scenes/paper.toml";

struct Result {
  int code;
  std::string output;  // stdout and stderr
};

// Run `siloscope ARGS`, capturing its output and exit code.
inline Result cli(const std::string& args) {
  FILE* p = popen((kBin + " " + args + " 2>&1").c_str(), "r");
  if (!p) return {-1, "popen failed"};
  std::string out;
  char buf[4096];
  while (size_t n = fread(buf, 1, sizeof buf, p)) out.append(buf, n);
  const int status = pclose(p);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status), out};
}

// Run a shell command, returning its exit code.
inline int sh(const std::string& cmd) {
  const int status = std::system(cmd.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// The test directories of this process, removed when it exits normally (set SILOSCOPE_KEEP_TEST_DIRS=1 to
// keep them for a look after a failure).
struct TempDirs {
  std::vector<std::filesystem::path> dirs;
  ~TempDirs() {
    if (std::getenv("SILOSCOPE_KEEP_TEST_DIRS")) return;
    std::error_code ec;
    for (const auto& d : dirs) std::filesystem::remove_all(d, ec);
  }
};
inline TempDirs& temp_dirs() {
  static TempDirs t;
  return t;
}

// A fresh, empty directory under the system's temporary directory, unique to this process: two suites running
// at once on one machine (a developer's loop beside CI) never share one.
inline std::filesystem::path temp_dir(const std::string& name) {
  auto d = std::filesystem::temp_directory_path() /
           ("siloscope_test_" + name + "_" + std::to_string(static_cast<long>(::getpid())));
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  temp_dirs().dirs.push_back(d);
  return d;
}

// How many times `what` occurs in `text` (overlapping occurrences counted).
inline long count_of(const std::string& text, const std::string& what) {
  long c = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++c;
  return c;
}

inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Makes an output directory one written before manifests (as older versions did): its manifest removed and
// the line of its metadata.toml that declares one taken out (without it, the missing manifest is refused).
inline void strip_manifest(const std::filesystem::path& dir) {
  std::filesystem::remove(dir / "manifest.toml");
  std::string meta = slurp(dir / "metadata.toml");
  const std::string line = "manifest = \"manifest.toml\"\n";
  const size_t at = meta.find(line);
  if (at == std::string::npos) return;
  meta.erase(at, line.size());
  std::ofstream(dir / "metadata.toml", std::ios::binary) << meta;
}

}  // namespace test

#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <thread>

namespace test {

// Start `siloscope record` of a long discharge into OUT (stdout and stderr discarded) and return once its
// movie has grown past 20 kB: frames are being encoded. Returns the child's pid.
inline pid_t start_long_record(const std::string& out) {
  pid_t pid = fork();
  if (pid == 0) {
    if (!freopen("/dev/null", "w", stdout) || !freopen("/dev/null", "w", stderr)) _exit(126);
    execl(kBin.c_str(), kBin.c_str(), "record", kScene.c_str(), "--duration", "120", "--set", "settle_time=2",
          "--size", "320x240", "--out", out.c_str(), "--quiet", static_cast<char*>(nullptr));
    _exit(127);
  }
  const std::string partial = out + ".mp4.partial";
  for (int i = 0; i < 200; ++i) {
    std::error_code ec;
    if (std::filesystem::exists(partial, ec) && std::filesystem::file_size(partial, ec) > 20000) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return pid;
}

// Send `sig` and wait; returns the wait status.
inline int signal_and_wait(pid_t pid, int sig) {
  kill(pid, sig);
  int status = 0;
  waitpid(pid, &status, 0);
  return status;
}

}  // namespace test
