// The user's Ctrl-C (SIGINT) or a SIGTERM, seen by every layer: the application's signal handler raises the
// flag (app/services/terminal.h), and every long loop, in whatever layer it runs (a simulation, a video's
// frames, a script's snapshots, a track file's rows), polls it and stops by throwing Interrupted. Whatever
// the loop was building is then removed by its owner's destructor (io::OutputDir, temporary files), and the
// command exits 130 with nothing half-written.
#pragma once

#include <stdexcept>

namespace core {

// A long operation stopped at the user's request (exit 130).
class Interrupted : public std::runtime_error {
 public:
  Interrupted() : std::runtime_error("interrupted") {}
  using std::runtime_error::runtime_error;
};

// Raised once by a signal handler (async-signal-safe: a lock-free atomic).
void raise_interrupt() noexcept;
bool interrupt_requested() noexcept;
// Throws Interrupted when the flag is up; for long loops, once per item of work.
void throw_if_interrupted();

}  // namespace core
