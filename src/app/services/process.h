// Child processes and the files siloscope ships beside its binary. Processes start from an argument vector
// (posix_spawn, no shell: no quoting, no injection through a path or title); the figure scripts, the Python
// package and the preset scenes are found relative to the binary: SHARE = BINDIR/share/siloscope in a build
// tree, BINDIR/../share/siloscope once installed (`cmake --install`), so a build can be installed or moved.
#pragma once

#include <sys/types.h>

#include <filesystem>
#include <string>
#include <vector>

namespace app {

// This binary's own path.
std::string self_exe();

// siloscope's shared files (figures/, python/, scenes/, campaigns/); throws core::RuntimeFault naming where
// it looked when there is none.
std::filesystem::path share_dir();
// A figure script: SHARE/figures/NAME.
std::string script_path(const std::string& name);

// Start argv (argv[0] a path, or a name looked up on PATH) in `cwd` (empty: this one) with stdout and stderr
// to `log` (empty: inherited), in a process group of its own if `own_group` (a terminal's Ctrl-C then
// reaches only this process, which decides what the child is told). Returns the child's pid; throws
// core::RuntimeFault if it cannot start.
pid_t spawn(const std::vector<std::string>& argv, const std::string& cwd = "", const std::string& log = "",
            bool own_group = false);
// Wait for a child: its exit code, 128 + the signal that ended it, or -1 if interrupted (Ctrl-C while
// waiting, when !retry_on_interrupt).
int wait_child(pid_t pid, bool retry_on_interrupt = true);
// Start and wait; on Ctrl-C the child is ended (SIGTERM) and core::Interrupted thrown.
int run_process(const std::vector<std::string>& argv, const std::string& cwd = "",
                const std::string& log = "");

// Debian's python3 (where python3-matplotlib installs) with the script and its arguments; stdout and stderr
// inherited. Returns the exit code.
int run_python(const std::string& script, const std::vector<std::string>& args);

// Debian's python3 (where python3-matplotlib installs), even when another python3 comes first on PATH.
std::string python_interpreter();

}  // namespace app
