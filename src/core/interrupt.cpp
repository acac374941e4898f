#include "core/interrupt.h"

#include <atomic>

namespace core {

namespace {
std::atomic<bool> g_interrupt{false};
static_assert(std::atomic<bool>::is_always_lock_free, "a signal handler sets it");
}  // namespace

void raise_interrupt() noexcept {
  g_interrupt.store(true);
}

bool interrupt_requested() noexcept {
  return g_interrupt.load();
}

void throw_if_interrupted() {
  if (g_interrupt.load()) throw Interrupted();
}

}  // namespace core
