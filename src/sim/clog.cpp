#include "sim/clog.h"

namespace sim {

void ClogTracker::close(double t, core::ClogEnd how) {
  if (how == core::ClogEnd::Rule || t - last_ >= min_gap_) clogs_.push_back({last_, t, how, arrested_});
  last_ = t;
  arrested_ = false;
}

void ClogTracker::on_exit(double t) {
  // An arrested outlet does not restart on its own while a drive acts: the drive broke it. Otherwise the jam
  // was transient (or, without any drive, the arch collapsed by itself).
  close(t, arrested_ && driven_ ? core::ClogEnd::Vibration : core::ClogEnd::Spontaneous);
}

void ClogTracker::on_rest_check(double t, bool outlet_at_rest) {
  // Only a gap that has lasted long enough to be a clog can be arrested; during flow the outlet is never at
  // rest.
  if (outlet_at_rest && t - last_ > 0) arrested_ = true;
}

void ClogTracker::on_rule(double t) {
  close(t, core::ClogEnd::Rule);
}

void ClogTracker::finish(double t) {
  if (t - last_ >= min_gap_) clogs_.push_back({last_, t, core::ClogEnd::RunEnd, arrested_});
}

}  // namespace sim
