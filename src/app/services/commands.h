// The command frame: every subcommand is one row of a table (its name, its one-line help, how it defines its
// options and what it runs, and an example invocation), and one frame around them gives every command the
// same --help, --version, usage line, exit codes, Ctrl-C handling and messages. A new command is a new row;
// the frame's guarantees, and the tests that hold them (tests/app/test_frame.cpp), cover it without another
// line.
//
// Exit codes: 0 success, 1 a fault while running, 2 bad input (arguments, scene, files), 3 the health monitor
// stopped a run, 75 the output is being written by another process, 130 interrupted (Ctrl-C or SIGTERM:
// nothing half-written is left).
#pragma once

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

#include "app/services/cli.h"

namespace app {

struct Command {
  const char* name;
  const char* help;  // one line, as --help lists it
  // Adds the command's options to `cmd` (the frame made it with the name and help) and, once parsed, sets
  // `action` to what it runs.
  void (*define)(CLI::App& cmd, Action& action);
  // A typical invocation, for the reference pages and the frame's tests. Placeholders: {scene} (a preset
  // scene file), {recording} (a recording directory), {run} (a run directory without a trajectory),
  // {campaign} (a campaign file), {results} (a sweep's results directory), {analysis} (analyze's output),
  // {video} (a movie file), {tracks} (a tracks CSV), {out} (a path that does not exist yet), {script} (an
  // inspector script).
  const char* example;
  // The example keeps working for seconds (a simulation, a re-simulation, a long export): the frame's test
  // interrupts it mid-work and expects exit 130 within seconds and nothing half-written.
  bool long_running;
};

// Every subcommand, in the order --help lists them.
const std::vector<Command>& command_table();

// The whole program: parse argv against the table, run the command inside the frame, return the exit code.
int run_command_line(int argc, char** argv);

}  // namespace app
