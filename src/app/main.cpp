// siloscope: clogging in a vibrated 2D hopper (Carlevaro et al., Granular Matter 24, 2022).
// Exit codes: 0 success, 1 a fault while running, 2 bad input (arguments, scene, files), 130 interrupted.
#include <cerrno>
#include <cstdio>
#include <cstring>

#include "app/services/cli.h"
#include "app/services/process.h"
#include "app/services/run_outputs.h"
#include "app/services/terminal.h"
#include "core/error.h"
#include "io/metadata.h"

int main(int argc, char** argv) {
  app::set_command_line(argc, argv);
  CLI::App cli{"siloscope: simulate, film and measure clogging arches in a vibrated hopper"};
  cli.set_version_flag("--version", io::version_string());
  cli.require_subcommand(1);
  app::Action action;
  app::add_run_command(cli, action);
  app::add_record_command(cli, action);
  app::add_bench_command(cli, action);
  app::add_analyze_command(cli, action);
  app::add_sweep_command(cli, action);
  app::add_figures_command(cli, action);
  app::add_export_command(cli, action);
  app::add_scene_command(cli, action);
  app::add_gallery_command(cli, action);
  app::add_timeline_command(cli, action);
  app::add_claims_command(cli, action);
  app::add_inspect_command(cli, action);
  app::add_import_command(cli, action);
  app::add_detect_command(cli, action);
  // A misspelt command: name the nearest one (CLI11 says only that a subcommand is required).
  if (argc > 1 && argv[1][0] != '-') {
    const std::string given = argv[1];
    std::string best;
    size_t best_d = 3;  // at most two edits away
    for (const auto* sub : cli.get_subcommands({})) {
      const size_t d = app::edit_distance(given, sub->get_name());
      if (d == 0) best.clear(), best_d = 0;
      if (d < best_d) best_d = d, best = sub->get_name();
    }
    if (best_d > 0) {
      std::fprintf(stderr, "siloscope: '%s' is not a command%s (see siloscope --help)\n", given.c_str(),
                   best.empty() ? "" : ("; did you mean '" + best + "'?").c_str());
      return 2;
    }
  }
  // What was printed must have reached standard output (a full disk, a closed pipe): otherwise the command
  // did not do what it said, whatever it computed.
  auto printed = [](int rc) {
    if (std::fflush(stdout) == 0 && !std::ferror(stdout)) return rc;
    std::fprintf(stderr, "siloscope: error: cannot write to standard output (%s): what was printed is lost\n",
                 std::strerror(errno));
    return rc == 0 ? 1 : rc;
  };
  try {
    cli.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return printed(cli.exit(e));
  } catch (const CLI::CallForAllHelp& e) {
    return printed(cli.exit(e));
  } catch (const CLI::CallForVersion& e) {
    return printed(cli.exit(e));
  } catch (const CLI::ParseError& e) {
    std::fprintf(
        stderr,
        "siloscope: %s\nusage: siloscope "
        "{run,record,inspect,live,frame,filmstrip,sweep,analyze,figures,claims,gallery,timeline,export,scene,"
        "bench} ... (see "
        "siloscope --help)\n",
        e.what());
    return 2;
  }
  try {
    return printed(action());
  } catch (const core::OutputBusy& e) {
    std::fprintf(stderr, "siloscope: busy: %s\n", e.what());
    return 75;
  } catch (const core::InputError& e) {
    std::fprintf(stderr, "siloscope: error: %s\n", e.what());
    return 2;
  } catch (const core::Unstable& e) {
    std::fprintf(stderr, "siloscope: failed: %s\n", e.what());
    return 3;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "siloscope: failed: %s\n", e.what());
    return 1;
  }
}
