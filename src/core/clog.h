// Clog bookkeeping, independent of the physics: exit gaps, the clog open now and its arch, how each clog
// ended, and when the clog_timeout rule is due. Times in seconds since the aperture opened. This is the one
// place that decides these things: the simulation's step reports them (core/events.h) and everything else
// reads the report.
#pragma once

#include <cmath>
#include <utility>
#include <vector>

#include "core/events.h"
#include "core/frame.h"

namespace core {

class ClogTracker {
 public:
  // `driven`: kicks or a vibrating container act on the grains. Without a drive nothing breaks a clog from
  // outside: an arrested clog that flows again collapsed by itself, and is spontaneous.
  ClogTracker(double min_gap, double timeout, bool driven = true)
      : min_gap_(min_gap), timeout_(timeout), driven_(driven) {}

  // Each call that ends or opens something adds it to `out` (the step's report).
  // A particle left through the aperture at time t.
  void on_exit(double t, core::StepEvents& out);
  // Called just before each kick: whether the outlet is arrested (a blocking arch stands and every disk near
  // the outlet moved less than arrest_shift radii over the arrest_hold seconds before the kick). Judging the
  // arrest by displacement over a window that ends before the kick, not by speed, keeps it independent of the
  // kick's own velocity change: a clog that was arrested and then flows again was broken by a kick, at any
  // kick strength. `arch`: the blocking arch found at this check (core::blocks_outlet), or empty.
  void on_rest_check(double t, bool outlet_at_rest, const std::vector<int>& arch);
  // After the step's exits and rule at time t: opens a clog when the gap has reached clog_min_gap, with the
  // arch `find_arch()` finds then (a blocking arch or empty: the last check's arch of this gap is kept).
  template <class FindArch>
  void on_step_end(double t, FindArch find_arch, core::StepEvents& out) {
    if (state_.open || t - last_ < min_gap_) return;
    std::vector<int> now = find_arch();
    if (!now.empty()) {
      see_arch(t, now);
      gap_arch_ = std::move(now);
    }
    open(t, out);
  }
  // The rule is due when nothing has exited (and the rule has not fired) for `timeout`; never when the rule
  // is off (timeout 0: clogs end only by the drive or the end of the run).
  bool rule_due(double t) const { return timeout_ > 0 && t - last_ >= timeout_ - 1e-9; }
  // Seconds until rule_due (0 when due; infinity with the rule off).
  double rule_due_in(double t) const;
  // The rule fired at t, removing `removed`: the current clog ends, a new gap starts.
  void on_rule(double t, const core::ArchEvent& removed, core::StepEvents& out);
  // The run ended at t: an open clog is recorded as censored.
  void finish(double t, core::StepEvents& out);

  double since_last(double t) const { return t - last_; }
  void set_driven(bool driven) { driven_ = driven; }
  void set_timeout(double timeout) { timeout_ = timeout; }  // s; 0: the rule off
  bool arrested() const { return arrested_; }
  const core::ClogState& state() const { return state_; }
  const std::vector<core::ClogEvent>& clogs() const { return clogs_; }

 private:
  void close(double t, core::ClogEnd how, core::StepEvents& out);
  void open(double t, core::StepEvents& out);
  void hold_arch(double t, const std::vector<int>& arch);
  // Formation: which grains the checks have seen standing as the arch without a break, since when, and since
  // when each grain has been in it. Passive: nothing here changes when a clog opens or ends.
  void see_arch(double t, const std::vector<int>& arch);
  void formed_now(double t);  // the held arch's formation and arrival order from what was seen
  std::vector<int> seen_arch_;
  double seen_since_ = NAN;
  std::vector<std::pair<int, double>> member_since_;  // grain, first check of its unbroken run in the arch
  double min_gap_, timeout_;
  bool driven_;
  double last_ = 0;        // last exit, rule firing, or the opening
  bool arrested_ = false;  // the outlet came to rest since last_
  core::ClogState state_;
  std::vector<int> gap_arch_;   // the last arch a check found during this gap (before the clog opened)
  std::vector<int> candidate_;  // a different arch found once during the open clog (replaces at the 2nd)
  std::vector<core::ClogEvent> clogs_;
};

}  // namespace core
