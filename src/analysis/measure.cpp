#include "analysis/measure.h"

#include <algorithm>
#include <cmath>

namespace analysis {

AvalancheEnd avalanche_end_for(const core::Scene& s) {
  const bool driven = s.kick_impulse_max > 0 || s.vibration_gamma > 0 || s.vibration_amplitude > 0;
  return driven ? AvalancheEnd::Gaps : AvalancheEnd::Held;
}

const char* avalanche_end_name(AvalancheEnd e) {
  return e == AvalancheEnd::Held ? "held" : "gaps";
}

Measurements measure(const core::Events& ev, double duration, double clog_min_gap, int n_species,
                     AvalancheEnd end) {
  Measurements m;
  m.avalanche_end = end;
  m.duration = duration;
  m.exits_by_species.assign(static_cast<size_t>(std::max(1, n_species)), 0);
  std::vector<core::ExitEvent> within;
  for (const auto& e : ev.exits) {
    if (e.t > duration) continue;
    within.push_back(e);
    ++m.exits;
    ++(e.species == core::Species::Original ? m.exits_original : m.exits_added);
    const size_t k = static_cast<size_t>(core::species_index(e.species));
    if (k >= m.exits_by_species.size()) m.exits_by_species.resize(k + 1, 0);
    ++m.exits_by_species[k];
  }
  m.q = duration > 0 ? m.exits / duration : NAN;
  m.q_tilde = duration > 0 ? m.exits_original / duration : NAN;
  m.chi_eff = m.exits > 0 ? static_cast<double>(m.exits_added) / m.exits : NAN;
  long added = 0, members = 0;
  for (const auto& a : ev.arches) {
    if (a.t > duration) continue;
    ++m.long_arches;
    members += static_cast<long>(a.ids.size());
    added += static_cast<long>(a.species.size()) -
             std::count(a.species.begin(), a.species.end(), core::Species::Original);
  }
  m.long_arches_per_minute = duration > 0 ? 60.0 * m.long_arches / duration : NAN;
  m.added_per_long_arch = m.long_arches > 0 ? static_cast<double>(added) / m.long_arches : NAN;
  m.members_per_long_arch = m.long_arches > 0 ? static_cast<double>(members) / m.long_arches : NAN;
  for (const auto& c : ev.clogs) {
    if (c.start > duration) continue;
    ++m.clogs;
    switch (c.ended_by) {
      case core::ClogEnd::Spontaneous:
        ++m.clogs_spontaneous;
        break;
      case core::ClogEnd::Vibration:
        ++m.clogs_vibration;
        break;
      case core::ClogEnd::Rule:
        ++m.clogs_rule;
        break;
      case core::ClogEnd::RunEnd:
        ++m.clogs_run_end;
        break;
    }
  }
  long decided = m.clogs_vibration + m.clogs_rule;
  m.fraction_broken_by_vibration = decided > 0 ? static_cast<double>(m.clogs_vibration) / decided : NAN;
  for (double g : original_gaps(within)) {
    ++m.lapses;
    m.lapses_ge_1s += g >= 1.0;
    m.lapses_ge_2s += g >= 2.0;
  }
  const std::vector<double> sizes = avalanche_sizes(within, ev.clogs, clog_min_gap, end);
  m.avalanches = static_cast<long>(sizes.size());
  double sum = 0;
  for (double s : sizes) sum += s;
  m.avalanche_mean = sizes.empty() ? NAN : sum / static_cast<double>(sizes.size());
  return m;
}

std::vector<double> original_gaps(const std::vector<core::ExitEvent>& exits) {
  std::vector<double> gaps;
  double last = NAN;
  for (const auto& e : exits) {
    if (e.species != core::Species::Original) continue;
    if (!std::isnan(last)) gaps.push_back(e.t - last);
    last = e.t;
  }
  return gaps;
}

std::vector<double> avalanche_sizes(const std::vector<core::ExitEvent>& exits, double min_gap) {
  std::vector<double> sizes;
  long current = 0;
  double last = NAN;
  for (const auto& e : exits) {
    if (!std::isnan(last) && e.t - last >= min_gap) {
      sizes.push_back(static_cast<double>(current));
      current = 0;
    }
    ++current;
    last = e.t;
  }
  return sizes;  // `current`, the avalanche the run's end cut short, is left out
}

std::vector<double> avalanche_sizes(const std::vector<core::ExitEvent>& exits,
                                    const std::vector<core::ClogEvent>& clogs, double min_gap,
                                    AvalancheEnd end) {
  if (end == AvalancheEnd::Gaps) return avalanche_sizes(exits, min_gap);
  // Each held clog starts at its avalanche's last exit (clogs.csv rounds times to the millisecond; the next
  // exit is at least min_gap later, so half of it tells the two apart).
  std::vector<double> sizes;
  size_t k = 0;
  for (const auto& c : clogs) {
    if (c.ended_by == core::ClogEnd::Spontaneous) continue;
    long n = 0;
    while (k < exits.size() && exits[k].t <= c.start + 0.5 * min_gap) ++k, ++n;
    if (n == 0) continue;  // no exit before it: beyond the analysed exits, or at the opening (as with Gaps)
    sizes.push_back(static_cast<double>(n));
  }
  return sizes;  // the exits after the last held clog, cut short by the run's end, are left out
}

std::vector<double> survival(std::vector<double> gaps, const std::vector<double>& taus) {
  std::sort(gaps.begin(), gaps.end());
  std::vector<double> out;
  out.reserve(taus.size());
  for (double tau : taus) {
    if (gaps.empty()) {
      out.push_back(NAN);
      continue;
    }
    auto it = std::lower_bound(gaps.begin(), gaps.end(), tau);  // first gap >= tau
    out.push_back(static_cast<double>(gaps.end() - it) / static_cast<double>(gaps.size()));
  }
  return out;
}

}  // namespace analysis
