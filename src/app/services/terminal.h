// The terminal: Ctrl-C handling and a one-line progress display.
#pragma once

#include <chrono>
#include <string>

namespace app {

// Ctrl-C / SIGTERM: the first sets a flag the long loops poll; a second one terminates at once.
void install_interrupt_handler();
bool interrupted();

// A one-line progress bar on stderr when it is a terminal; silent otherwise (CI logs stay clean).
class Progress {
 public:
  Progress(std::string label, double total, bool enabled = true);
  void update(double done, const std::string& extra = "");
  void finish();

 private:
  std::string label_;
  double total_;
  bool enabled_;
  std::chrono::steady_clock::time_point start_, last_;
};

}  // namespace app
