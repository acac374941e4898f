// Tidy CSV of measurements: one row per realization (summary.csv), one row per (realization, tau) for the
// survival function (survival.csv). Scene keys that define a campaign point come first in every row.
#pragma once

#include <string>
#include <vector>

#include "analysis/measure.h"
#include "core/scene.h"
#include "core/setup.h"

namespace analysis {

// Scene keys written in front of every tidy row.
const std::vector<std::string>& point_keys();

std::string summary_header();
std::string summary_row(const core::Scene& s, const Measurements& m);

// One row per species of a run: species,count,number_fraction,exits,q_per_s,exit_fraction.
std::string species_csv(const core::Setup& st, const Measurements& m);

// The tau grid of survival functions: 0 to clog_timeout + 1 s in steps of 0.05 s (clog rule off: to 30 s).
std::vector<double> survival_taus(const core::Scene& s);
std::string survival_csv(const core::Scene& s, const std::vector<core::ExitEvent>& exits);

// A human-readable summary for the terminal: the shorthand's original and added disks, or each species by its
// name; the clog rule's line says when it is off.
std::string summary_text(const Measurements& m, const std::vector<std::string>& names = {"original", "added"},
                         bool clog_rule = true);

}  // namespace analysis
