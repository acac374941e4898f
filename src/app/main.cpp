// siloscope: clogging in a vibrated 2D hopper (Carlevaro et al., Granular Matter 24, 2022). Every subcommand
// is a row of app/commands/table.cpp; the frame around them (help, version, exit codes, Ctrl-C) is
// app/services/commands.cpp.
#include "app/services/commands.h"

int main(int argc, char** argv) {
  return app::run_command_line(argc, argv);
}
