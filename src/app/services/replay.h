// A run seen again: played back from its trajectory beside a live simulation (record --compare-run), or
// simulated again from its metadata where it kept no trajectory (frame, gallery), checked against the events
// it recorded.
#pragma once

#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "app/services/session.h"
#include "core/frame.h"
#include "core/model.h"
#include "io/run.h"

namespace app {

// A recorded or imported run played back beside a live simulation (record --compare-run): its frames by
// time, on the simulation's clock, from its trajectory. The clock of both starts when the outlet opens (an
// imported run: its first frame).
class Replay {
 public:
  // RUN: a run or recording directory (with trajectory.sstraj) or the file. Throws core::InputError naming
  // it.
  explicit Replay(const std::string& run);
  // The last frame at or before t (the first before the run's first frame, the last after its end).
  core::Frame at(double t);
  const core::Model& model() const { return run_.model(); }
  std::string name() const { return run_.name(); }
  bool imported() const { return run_.imported(); }

 private:
  io::Run run_;
  long k_ = 0;
};

// Simulates `run` again from its metadata (runs are deterministic) up to `until` s, with frames by `clock` to
// `sinks`, and checks that it gives the run's own exits and rule removals up to there: another build or
// physics is refused (core::RuntimeFault naming the first event that differs). Progress on a terminal under
// `label`; Ctrl-C stops it (core::Interrupted).
void resimulate(const io::Run& run, double until, const FrameClock& clock, const std::vector<Sink*>& sinks,
                const std::string& label);
// The same, with sinks made for the re-simulated world once it stands (a trajectory's header needs its
// grains' radii).
using SinksFor = std::function<std::vector<Sink*>(const sim::Silo&)>;
void resimulate(const io::Run& run, double until, const FrameClock& clock, const SinksFor& sinks_for,
                const std::string& label);

// Throws core::RuntimeFault naming the first exit or long-lasting arch of the recorded run up to t_end (s)
// that the events `again` of its re-simulation do not repeat.
void check_replayed_events(const io::Run& run, const core::Events& again, double t_end);

// Why two containers differ (an empty string: the same within a millimetre): the comparison shows one
// geometry filmed the same way.
std::string container_difference(const core::Geometry& a, const core::Geometry& b);

}  // namespace app
