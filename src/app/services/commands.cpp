// The command frame (app/services/commands.h): what every subcommand gets without asking.
#include "app/services/commands.h"

#include <cerrno>
#include <cstdio>
#include <cstring>

#include "app/services/terminal.h"
#include "core/error.h"
#include "core/interrupt.h"
#include "io/metadata.h"

namespace app {

namespace {

// "{run,record,...}": the table's names, for the usage line.
std::string command_names() {
  std::string names;
  for (const Command& c : command_table()) names += (names.empty() ? "" : ",") + std::string(c.name);
  return "{" + names + "}";
}

// --version on a command and every command under it (bench's own subcommands too).
void add_version_flags(CLI::App& cmd) {
  cmd.set_version_flag("--version", io::version_string());
  for (CLI::App* sub : cmd.get_subcommands({})) add_version_flags(*sub);
}

// A misspelt command: the nearest name (CLI11 says only that a subcommand is required). Returns the message,
// empty when `given` is a command.
std::string misspelt(const std::string& given) {
  std::string best;
  size_t best_d = 3;  // at most two edits away
  for (const Command& c : command_table()) {
    const size_t d = edit_distance(given, c.name);
    if (d == 0) return "";
    if (d < best_d) best_d = d, best = c.name;
  }
  return "'" + given + "' is not a command" + (best.empty() ? "" : "; did you mean '" + best + "'?") +
         " (see siloscope --help)";
}

// What was printed must have reached standard output (a full disk, a closed pipe): otherwise the command did
// not do what it said, whatever it computed.
int printed(int rc) {
  if (std::fflush(stdout) == 0 && !std::ferror(stdout)) return rc;
  std::fprintf(stderr, "siloscope: error: cannot write to standard output (%s): what was printed is lost\n",
               std::strerror(errno));
  return rc == 0 ? 1 : rc;
}

// The parsed command's path ("bench record"), for the usage line of a command's own error.
std::string parsed_path(CLI::App& cli) {
  std::string path;
  for (CLI::App* app = &cli;;) {
    const auto subs = app->get_subcommands();
    if (subs.empty()) break;
    app = subs.front();
    path += (path.empty() ? "" : " ") + app->get_name();
  }
  return path;
}

// A table row's example as a reader would type it: its placeholders as typical paths.
std::string readable_example(std::string text) {
  static const std::pair<const char*, const char*> kNames[] = {
      {"{scene}", "paper"},           {"{recording}", "recordings/demo"},
      {"{run}", "runs/s1"},           {"{campaign}", "assets/campaigns/quick.toml"},
      {"{results}", "results/quick"}, {"{analysis}", "analysis"},
      {"{video}", "film.mp4"},        {"{tracks}", "tracks.csv"},
      {"{script}", "session.txt"},    {"{out}", "out"}};
  for (const auto& [key, name] : kNames)
    for (size_t at; (at = text.find(key)) != std::string::npos;)
      text.replace(at, std::string(key).size(), name);
  return text;
}

int interrupted_exit() {
  std::fprintf(stderr, "siloscope: interrupted: stopped before finishing; nothing half-written is left\n");
  return 130;
}

// The command, its errors mapped to exit codes.
int run_action(const Action& action) {
  try {
    return printed(action());
  } catch (const core::Interrupted&) {
    return interrupted_exit();
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
    // A fault may have been caused by the interrupt itself (a child ended, a write cut short).
    if (core::interrupt_requested()) return interrupted_exit();
    std::fprintf(stderr, "siloscope: failed: %s\n", e.what());
    return 1;
  }
}

}  // namespace

int run_command_line(int argc, char** argv) {
  // First of all: from here on Ctrl-C is a request every command honours (a signal already pending is
  // delivered now, and then nothing starts).
  install_interrupt_handler();
  set_command_line(argc, argv);
  CLI::App cli{"siloscope: simulate, film and measure clogging arches in a vibrated hopper"};
  cli.set_version_flag("--version", io::version_string());
  cli.require_subcommand(1);
  Action action;
  for (const Command& c : command_table()) {
    CLI::App* sub = cli.add_subcommand(c.name, c.help);
    c.define(*sub, action);
    add_version_flags(*sub);
    sub->footer("Example: siloscope " + readable_example(c.example));
  }
  if (argc > 1 && argv[1][0] != '-') {
    const std::string message = misspelt(argv[1]);
    if (!message.empty()) {
      std::fprintf(stderr, "siloscope: %s\n", message.c_str());
      return 2;
    }
  }
  try {
    cli.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return printed(cli.exit(e));
  } catch (const CLI::CallForAllHelp& e) {
    return printed(cli.exit(e));
  } catch (const CLI::CallForVersion& e) {
    return printed(cli.exit(e));
  } catch (const CLI::ParseError& e) {
    const std::string path = parsed_path(cli);
    if (path.empty())
      std::fprintf(stderr, "siloscope: %s\nusage: siloscope %s ... (see siloscope --help)\n", e.what(),
                   command_names().c_str());
    else
      std::fprintf(stderr, "siloscope %s: %s\nusage: siloscope %s ... (see siloscope %s --help)\n",
                   path.c_str(), e.what(), path.c_str(), path.c_str());
    return 2;
  }
  if (core::interrupt_requested()) return interrupted_exit();
  return run_action(action);
}

}  // namespace app
