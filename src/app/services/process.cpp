#include "app/services/process.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>
#include <csignal>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <thread>

#include "core/error.h"
#include "core/interrupt.h"

extern char** environ;

namespace app {

namespace fs = std::filesystem;

std::string self_exe() {
  std::error_code ec;
  const fs::path p = fs::read_symlink("/proc/self/exe", ec);
  return ec ? std::string("siloscope") : p.string();
}

fs::path share_dir() {
  const fs::path bin = fs::path(self_exe()).parent_path();
  std::error_code ec;
  for (const fs::path& candidate : {bin / "share" / "siloscope", bin / ".." / "share" / "siloscope"})
    if (fs::is_directory(candidate / "figures", ec)) return fs::weakly_canonical(candidate, ec);
  throw core::RuntimeFault(
      "siloscope's shared files (figures, python, scenes) are not beside the binary: looked in " +
      (bin / "share/siloscope").string() + " and " + (bin / "../share/siloscope").string() +
      " (build with cmake, or install with cmake --install)");
}

std::string script_path(const std::string& name) {
  return (share_dir() / "figures" / name).string();
}

pid_t spawn(const std::vector<std::string>& argv, const std::string& cwd, const std::string& log,
            bool own_group) {
  if (argv.empty()) throw core::RuntimeFault("spawn: no command");
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  if (!cwd.empty()) posix_spawn_file_actions_addchdir_np(&actions, cwd.c_str());
  if (!log.empty()) {
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                     0644);
    posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  }
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  if (own_group) {
    posix_spawnattr_setpgroup(&attr, 0);
    posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETPGROUP);
  }
  pid_t pid = 0;
  const int r = posix_spawnp(&pid, args[0], &actions, &attr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attr);
  if (r != 0) throw core::RuntimeFault("cannot start " + argv[0] + ": " + std::strerror(r));
  return pid;
}

int wait_child(pid_t pid, bool retry_on_interrupt) {
  // Polled rather than blocking: a Ctrl-C that lands after the last check and before a blocking waitpid()
  // would otherwise wait for the child to finish (a figure script: seconds) and be lost with it.
  int status = 0;
  for (;;) {
    if (!retry_on_interrupt && core::interrupt_requested()) return -1;
    const pid_t r = ::waitpid(pid, &status, WNOHANG);
    if (r == pid) break;
    if (r < 0 && errno != EINTR) return -1;
    if (r == 0) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
  return -1;
}

int run_process(const std::vector<std::string>& argv, const std::string& cwd, const std::string& log) {
  // The child has a process group of its own, so a Ctrl-C at the terminal reaches this process alone (a
  // Python child would die printing a traceback); on Ctrl-C this process ends the child and stops, even if
  // the child had just finished: nothing it made is kept.
  const pid_t pid = spawn(argv, cwd, log, true);
  const int status = wait_child(pid, false);
  if (!core::interrupt_requested()) return status;
  if (status == -1) {  // not reaped yet (a finished child is a zombie until then: its pid is still ours)
    ::kill(pid, SIGTERM);
    wait_child(pid, true);
  }
  throw core::Interrupted();
}

int run_python(const std::string& script, const std::vector<std::string>& args) {
  std::vector<std::string> argv = {::access("/usr/bin/python3", X_OK) == 0 ? "/usr/bin/python3" : "python3",
                                   script};
  argv.insert(argv.end(), args.begin(), args.end());
  return run_process(argv);
}

std::string python_interpreter() {
  return ::access("/usr/bin/python3", X_OK) == 0 ? "/usr/bin/python3" : "python3";
}

}  // namespace app
