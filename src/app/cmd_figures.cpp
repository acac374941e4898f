// siloscope figures DIR: the paper's figures from a campaign's tidy CSV, drawn by matplotlib
// (src/figures/figures.py) so users can restyle them without touching C++.
#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "app/common.h"
#include "core/format.h"
#include "core/error.h"
#include "io/metadata.h"

namespace app {

namespace {
namespace fs = std::filesystem;

struct FiguresOptions {
  std::string dir, out;
};


int figures(const FiguresOptions& o) {
  // DIR may be a campaign's results directory (with analysis/) or an analysis directory itself.
  fs::path src = o.dir;
  if (!fs::exists(src / "points.csv") && fs::exists(src / "analysis" / "points.csv")) src /= "analysis";
  if (!fs::exists(src / "points.csv"))
    throw core::InputError("figures: " + o.dir + " holds no points.csv (run `siloscope analyze` or `sweep` first)");
  fs::path out = o.out.empty() ? src.parent_path() / "figures" : fs::path(o.out);
  const char* env = std::getenv("SILOSCOPE_FIGURES_SCRIPT");
  fs::path script = env ? env : SILOSCOPE_FIGURES_SCRIPT;
  if (!fs::exists(script)) throw core::InputError("figures: the script " + script.string() + " is missing");
  if (std::system((python_interpreter() + " -c 'import matplotlib' 2>/dev/null").c_str()) != 0)
    throw core::RuntimeFault("figures: python3 with matplotlib is needed (Debian: apt-get install python3-matplotlib)");
  // Drawn into a temporary directory, moved into place when complete.
  fs::path tmp = out;
  tmp += ".partial";
  std::error_code ec;
  fs::remove_all(tmp, ec);
  std::string cmd = python_interpreter() + " " + core::shell_quote(script.string()) + " " + core::shell_quote(src.string()) + " " + core::shell_quote(tmp.string());
  int status = std::system(cmd.c_str());
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    fs::remove_all(tmp, ec);
    throw core::RuntimeFault("figures: the matplotlib script failed (" + cmd + ")");
  }
  fs::remove_all(out, ec);
  fs::rename(tmp, out, ec);
  if (ec) throw core::RuntimeFault("figures: cannot move " + tmp.string() + " to " + out.string() + ": " + ec.message());
  std::printf("figures in %s\n", out.c_str());
  return 0;
}
}  // namespace

void add_figures_command(CLI::App& app, Action& action) {
  auto o = std::make_shared<FiguresOptions>();
  auto* cmd = app.add_subcommand("figures", "the paper's figures (PNG, SVG, PDF) from a campaign's tidy CSV");
  cmd->set_version_flag("--version", io::version_string());
  cmd->add_option("dir", o->dir, "a sweep's results directory, or an analysis directory (points.csv)")->required();
  cmd->add_option("--out", o->out, "output directory (default: next to the analysis, figures/)");
  cmd->callback([o, &action] { action = [o] { return figures(*o); }; });
}

}  // namespace app
