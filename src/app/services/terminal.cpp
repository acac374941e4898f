// The terminal: Ctrl-C handling and the progress line.
#include "app/services/terminal.h"

#include <unistd.h>

#include <atomic>
#include <csignal>
#include <cstdio>
#include <cstdlib>

#include "core/interrupt.h"

namespace app {

namespace {
std::atomic<int> g_signals{0};
void on_signal(int sig) {
  core::raise_interrupt();
  if (g_signals.fetch_add(1) >= 1) {
    std::signal(sig, SIG_DFL);
    std::raise(sig);
  }
}
}  // namespace

void install_interrupt_handler() {
  // No SA_RESTART: a blocking call returns EINTR, so a wait for a child or a sleep ends at once.
  struct sigaction sa = {};
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = 0;
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
  // A parent may have started us with these signals blocked (some job runners do): Ctrl-C must still work. A
  // signal already pending is delivered here, before any work starts.
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGINT);
  sigaddset(&set, SIGTERM);
  sigprocmask(SIG_UNBLOCK, &set, nullptr);
}

bool interrupted() {
  return core::interrupt_requested();
}

Progress::Progress(std::string label, double total, bool enabled, bool throws_on_interrupt)
    : label_(std::move(label)),
      total_(total),
      enabled_(enabled && ::isatty(STDERR_FILENO)),
      throws_(throws_on_interrupt) {
  start_ = last_ = std::chrono::steady_clock::now();
}

void Progress::update(double done, const std::string& extra) {
  if (throws_) core::throw_if_interrupted();  // every long loop reports its progress: there it stops
  if (!enabled_) return;
  auto now = std::chrono::steady_clock::now();
  if (now - last_ < std::chrono::milliseconds(200)) return;
  last_ = now;
  double elapsed = std::chrono::duration<double>(now - start_).count();
  double frac = total_ > 0 ? std::min(1.0, done / total_) : 1.0;
  double eta = frac > 0 ? elapsed * (1 - frac) / frac : 0;
  constexpr int kWidth = 30;
  std::string bar(static_cast<size_t>(frac * kWidth), '#');
  bar.resize(kWidth, '.');
  std::fprintf(stderr, "\r%s [%s] %5.1f%%  %s  ETA %4.0f s ", label_.c_str(), bar.c_str(), 100 * frac,
               extra.c_str(), eta);
  std::fflush(stderr);
}

void Progress::finish() {
  if (enabled_) std::fprintf(stderr, "\n");
}

}  // namespace app
