// The terminal: Ctrl-C handling and a one-line progress display.
#pragma once

#include <chrono>
#include <string>

namespace app {

// Ctrl-C / SIGTERM: the first raises core's interrupt flag (core/interrupt.h), which the long loops poll; a
// second one terminates at once. Installed by the command frame before any command runs.
void install_interrupt_handler();
bool interrupted();

// A one-line progress bar on stderr when it is a terminal; silent otherwise (CI logs stay clean). Every
// update() polls Ctrl-C (throws core::Interrupted): a loop that reports progress stops when asked. A command
// that ends an interrupted run its own way (run and record keep what they filmed, marked interrupted; sweep
// passes the signal to its workers) passes `throws_on_interrupt` false and polls interrupted() itself.
class Progress {
 public:
  Progress(std::string label, double total, bool enabled = true, bool throws_on_interrupt = true);
  void update(double done, const std::string& extra = "");
  void finish();

 private:
  std::string label_;
  double total_;
  bool enabled_, throws_;
  std::chrono::steady_clock::time_point start_, last_;
};

}  // namespace app
