#include "sim/clog.h"

namespace sim {

void ClogTracker::close(double t, core::ClogEnd how) {
  if (how == core::ClogEnd::Rule || t - last_ >= min_gap_) clogs_.push_back({last_, t, how, arrested_});
  last_ = t;
  arrested_ = false;
}

void ClogTracker::on_exit(double t) {
  // An arrested outlet cannot restart on its own: a kick broke it. Otherwise the jam was transient.
  close(t, arrested_ ? core::ClogEnd::Vibration : core::ClogEnd::Spontaneous);
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
