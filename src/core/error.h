// Error types shared by every layer. The application maps them to exit codes:
// InputError (a bad scene, argument or file from the user) exits 2, OutputBusy 75, Unstable 3,
// RuntimeFault 1.
#pragma once

#include <stdexcept>
#include <string>

namespace core {

// Something the user gave us is wrong. The message names the field, the value and what is allowed.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Something went wrong while running (I/O failure, unstable integration, encoder error).
class RuntimeFault : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The health monitor stopped the run: the integration broke its bounds (an overlap, a disk outside the
// container or too fast). Deterministic: the same scene, seed and numerics stop again, so a campaign records
// the realization as refused instead of retrying it (exit 3).
class Unstable : public RuntimeFault {
 public:
  using RuntimeFault::RuntimeFault;
};

// Another process is writing the same output right now (exit 75, EX_TEMPFAIL: try again later).
class OutputBusy : public InputError {
 public:
  using InputError::InputError;
};

}  // namespace core
