// Clog bookkeeping, independent of the physics: exit gaps, clogs and how each ended, and when the
// clog_timeout rule is due. Times in seconds since the aperture opened.
#pragma once

#include <vector>

#include "core/frame.h"

namespace sim {

class ClogTracker {
 public:
  // `driven`: kicks or a vibrating container act on the grains. Without a drive nothing breaks a clog from
  // outside: an arrested clog that flows again collapsed by itself, and is spontaneous.
  ClogTracker(double min_gap, double timeout, bool driven = true)
      : min_gap_(min_gap), timeout_(timeout), driven_(driven) {}

  // A particle left through the aperture at time t.
  void on_exit(double t);
  // Called just before each kick: whether the outlet is arrested (a blocking arch stands and every disk near
  // the outlet moved less than arrest_shift radii over the arrest_hold seconds before the kick). Judging the
  // arrest by displacement over a window that ends before the kick, not by speed, keeps it independent of the
  // kick's own velocity change: a clog that was arrested and then flows again was broken by a kick, at any
  // kick strength.
  void on_rest_check(double t, bool outlet_at_rest);
  // The rule is due when nothing has exited (and the rule has not fired) for `timeout`; never when the rule
  // is off (timeout 0: clogs end only by the drive or the end of the run).
  bool rule_due(double t) const { return timeout_ > 0 && t - last_ >= timeout_ - 1e-9; }
  // The rule fired at t: the current clog ends, a new gap starts.
  void on_rule(double t);
  // The run ended at t: an open clog is recorded as censored.
  void finish(double t);

  double since_last(double t) const { return t - last_; }
  void set_driven(bool driven) { driven_ = driven; }
  bool arrested() const { return arrested_; }
  const std::vector<core::ClogEvent>& clogs() const { return clogs_; }

 private:
  void close(double t, core::ClogEnd how);
  double min_gap_, timeout_;
  bool driven_;
  double last_ = 0;        // last exit, rule firing, or the opening
  bool arrested_ = false;  // the outlet came to rest since last_
  std::vector<core::ClogEvent> clogs_;
};

}  // namespace sim
