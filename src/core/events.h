// What happened, as the simulation's step reports it: the one source every picture, file and window reads
// (the movie's slow motion, freezes and captions, the look-aheads, the trajectory, the inspector). Nothing
// outside core::ClogTracker decides when a clog opens, which arch blocks it, or when the rule is due.
#pragma once

#include <cmath>
#include <vector>

#include "core/frame.h"

namespace core {

// The clog open now, if any. A clog opens when the exit gap reaches clog_min_gap (the gap clogs.csv records
// as a clog); it closes at the next exit, when the rule removes its arch, or at the end of the run. Every
// clog that opens is one row of clogs.csv, in the same order (`number`).
struct ClogState {
  bool open = false;
  int number = 0;         // 1-based row of clogs.csv of the open clog (the last one when none is open)
  double start = 0;       // s, the last exit before the gap (clogs.csv's start_s)
  bool arrested = false;  // the outlet has been found at rest during this clog
  // Its blocking arch, members left to right, from the arch checks at each kick period while the clog is
  // open (and at its opening). The same arch is the same set of grains: a check that finds no arch (contacts
  // flicker under vibration) keeps it; a different set replaces it only when two consecutive checks agree
  // on it. Empty until a check finds one (an outlet blocked by grains resting on the floor has none).
  std::vector<int> arch;
  int arch_changes = 0;  // how often the arch was replaced during this clog
  // When the clog's arch formed (s; NaN while none) and its members in the order they arrived (ClogEvent).
  double formed = NAN;
  std::vector<int> arrival;
};

// What one step did, or, merged (append), what a run of steps did. Times in s since the opening.
struct StepEvents {
  std::vector<ExitEvent> exits;         // grains that left through the outlet
  std::vector<int> clogs_opened;        // numbers of the clogs that opened
  std::vector<ArchEvent> rule_removed;  // the rule fired and removed these arches (rows of arches.csv)
  std::vector<ClogEvent> clogs_closed;  // clogs that closed (rows of clogs.csv, in order)
  // After the last step: seconds until the rule falls due if no grain leaves before (infinity with the
  // rule off).
  double rule_due_in = INFINITY;

  bool empty() const {
    return exits.empty() && clogs_opened.empty() && rule_removed.empty() && clogs_closed.empty();
  }
  void clear() {
    exits.clear();
    clogs_opened.clear();
    rule_removed.clear();
    clogs_closed.clear();
    rule_due_in = INFINITY;
  }
  // `later` happened after this: lists are concatenated, the state is later's.
  void append(const StepEvents& later) {
    exits.insert(exits.end(), later.exits.begin(), later.exits.end());
    clogs_opened.insert(clogs_opened.end(), later.clogs_opened.begin(), later.clogs_opened.end());
    rule_removed.insert(rule_removed.end(), later.rule_removed.begin(), later.rule_removed.end());
    clogs_closed.insert(clogs_closed.end(), later.clogs_closed.begin(), later.clogs_closed.end());
    rule_due_in = later.rule_due_in;
  }
};

}  // namespace core
