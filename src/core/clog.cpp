#include "core/clog.h"

#include "core/arch.h"

#include <algorithm>
#include <cmath>

namespace core {

void ClogTracker::open(double t, core::StepEvents& out) {
  state_.open = true;
  state_.number = static_cast<int>(clogs_.size()) + 1;
  state_.start = last_;
  state_.arrested = arrested_;
  state_.arch = gap_arch_;
  state_.arch_changes = 0;
  formed_now(t);
  candidate_.clear();
  out.clogs_opened.push_back(state_.number);
}

void ClogTracker::see_arch(double t, const std::vector<int>& arch) {
  if (arch.empty()) return;  // no arch found now: what was seen stands (contacts flicker)
  if (seen_arch_.empty() || !core::same_grains(arch, seen_arch_)) seen_since_ = t;
  seen_arch_ = arch;
  // Each member's unbroken run: kept for those still in it, started now for those new to it.
  std::vector<std::pair<int, double>> next;
  for (int id : arch) {
    double since = t;
    for (const auto& [m, s] : member_since_)
      if (m == id) since = s;
    next.push_back({id, since});
  }
  member_since_ = std::move(next);
}

void ClogTracker::formed_now(double t) {
  if (state_.arch.empty()) {
    state_.formed = NAN;
    state_.arrival.clear();
    return;
  }
  const bool seen = !seen_arch_.empty() && core::same_grains(state_.arch, seen_arch_);
  // Not before the clog's start (an arch seen while the last grain left below it formed with the clog).
  state_.formed = std::max(last_, seen ? std::min(seen_since_, t) : t);
  // Members by the check they arrived at; ties (arrived together) left to right, as the arch lists them.
  std::vector<std::pair<double, int>> order;
  for (size_t k = 0; k < state_.arch.size(); ++k) {
    double since = state_.formed;
    for (const auto& [m, s] : member_since_)
      if (m == state_.arch[k] && seen) since = s;
    order.push_back({since, static_cast<int>(k)});
  }
  std::stable_sort(order.begin(), order.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  state_.arrival.clear();
  for (const auto& [since, k] : order) state_.arrival.push_back(state_.arch[static_cast<size_t>(k)]);
}

void ClogTracker::close(double t, core::ClogEnd how, core::StepEvents& out) {
  if (how == core::ClogEnd::Rule || t - last_ >= min_gap_) {
    // A gap that qualifies as a clog always opened one first (in this very step if need be), so that every
    // row of clogs.csv has its opening in the events.
    if (!state_.open) open(t, out);
    clogs_.push_back({last_, t, how, arrested_, state_.formed, state_.arrival});
    out.clogs_closed.push_back(clogs_.back());
  }
  last_ = t;
  arrested_ = false;
  state_.open = false;
  state_.arrested = false;
  state_.arch.clear();
  state_.formed = NAN;
  state_.arrival.clear();
  gap_arch_.clear();
  candidate_.clear();
  seen_arch_.clear();
  member_since_.clear();
}

void ClogTracker::on_exit(double t, core::StepEvents& out) {
  // An arrested outlet does not restart on its own while a drive acts: the drive broke it. Otherwise the jam
  // was transient (or, without any drive, the arch collapsed by itself).
  close(t, arrested_ && driven_ ? core::ClogEnd::Vibration : core::ClogEnd::Spontaneous, out);
}

void ClogTracker::hold_arch(double t, const std::vector<int>& arch) {
  if (arch.empty()) return;  // no arch found now: the one held stays (contacts flicker)
  if (state_.arch.empty()) {
    state_.arch = arch;
    // The clog's arch formed once: at its confirmation, or at the first arch found after it (none stood
    // then). A replacement or an arch found again after a drop does not move it.
    if (std::isnan(state_.formed)) formed_now(t);
    return;
  }
  if (core::same_grains(arch, state_.arch)) {
    state_.arch = arch;  // the same grains (their left-to-right order as it is now)
    candidate_.clear();
    return;
  }
  // A different set of grains: replace the held arch when it is seen twice in a row.
  if (!candidate_.empty() && core::same_grains(arch, candidate_)) {
    state_.arch = arch;
    ++state_.arch_changes;
    candidate_.clear();
  } else {
    candidate_ = arch;
  }
}

void ClogTracker::on_rest_check(double t, bool outlet_at_rest, const std::vector<int>& arch) {
  // Only a gap that has lasted long enough to be a clog can be arrested; during flow the outlet is never at
  // rest.
  if (outlet_at_rest && t - last_ > 0) arrested_ = true;
  see_arch(t, arch);
  if (!state_.open) {
    if (!arch.empty()) gap_arch_ = arch;
    return;
  }
  state_.arrested = arrested_;
  hold_arch(t, arch);
}

double ClogTracker::rule_due_in(double t) const {
  if (timeout_ <= 0) return INFINITY;
  return std::max(0.0, timeout_ - (t - last_));
}

void ClogTracker::on_rule(double t, const core::ArchEvent& removed, core::StepEvents& out) {
  out.rule_removed.push_back(removed);
  close(t, core::ClogEnd::Rule, out);
}

void ClogTracker::finish(double t, core::StepEvents& out) {
  if (t - last_ >= min_gap_) {
    if (!state_.open) open(t, out);
    clogs_.push_back({last_, t, core::ClogEnd::RunEnd, arrested_, state_.formed, state_.arrival});
    out.clogs_closed.push_back(clogs_.back());
  }
  state_.open = false;
}

}  // namespace core
