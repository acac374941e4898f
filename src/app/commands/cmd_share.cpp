// siloscope share RUN --out run.html: a recorded or imported run as one self-contained HTML page (or, with
// --embed, a fragment for a slide deck or a page) that a browser opens with no network and no server: play,
// scrub, jump from clog to clog, the arch drawn from its formation, click a grain (app/services/share_page.h,
// the viewer in src/viewer/, docs/share.md).
#include <cstdio>
#include <filesystem>
#include <memory>

#include "app/services/cli.h"
#include "app/services/looks.h"
#include "app/services/process.h"
#include "app/services/share_page.h"
#include "core/error.h"
#include "core/format.h"
#include "core/interrupt.h"
#include "io/output.h"
#include "io/run.h"

namespace app {

namespace {
namespace fs = std::filesystem;

struct ShareCommand {
  std::string run, out;
  bool force = false;
  ShareOptions share;
  LookOptions looks;  // the run's own look unless given
};

int share(const ShareCommand& o) {
  const io::Run run = io::Run::open(o.run, "share", io::Run::kTrajectory);
  const fs::path out = io::output_path(o.out);
  if (out.extension() != ".html" && out.extension() != ".htm")
    throw core::InputError("--out " + o.out + ": the page is an .html file");
  io::check_not_input(out, {run.file(io::run_file::kTrajectory), run.file(io::run_file::kMetadata)}, "page");
  io::OutputLock lock(out);
  io::check_destination(out, o.force, "share", io::OutputKind::Page);
  LookOptions looks = o.looks;
  looks.inherit(run.metadata());
  const Look look = looks.resolve(run.model());
  const SharePage page = share_page(run, look, o.share, share_dir() / "viewer");
  core::throw_if_interrupted();  // a Ctrl-C while the page was assembled: nothing is written
  io::write_output(out, page.html);
  std::printf("%ld frames, %.2f MB (frames %.2f MB packed, %.2f MB deflated) -> %s\n", page.frames,
              page.html.size() / 1e6, page.raw_bytes / 1e6, page.data_bytes / 1e6, out.c_str());
  return 0;
}
}  // namespace

void define_share_command(CLI::App& command, Action& action) {
  auto o = std::make_shared<ShareCommand>();
  CLI::App* cmd = &command;
  cmd->add_option("run", o->run,
                  "a recording or imported run (with its trajectory.sstraj), or a trajectory file")
      ->required();
  cmd->add_option("--out", o->out, "the page to write, .html (one file: no network, no server needed)")
      ->required();
  cmd->add_option("--from", o->share.from, "the first time to include, s")->capture_default_str();
  cmd->add_option("--to", o->share.to, "the last time to include, s (default: the run's end)");
  cmd->add_option("--stride", o->share.stride, "include every N-th frame (long runs)")->capture_default_str();
  cmd->add_flag(
      "--embed", o->share.embed,
      "write a fragment to paste into a slide deck or a page, sized by its container, instead of a page");
  cmd->add_flag("--force", o->force, "replace a page siloscope share wrote earlier");
  o->looks.add_to(*cmd);
  cmd->callback([o, &action] { action = [o] { return share(*o); }; });
}

}  // namespace app
