#include "analysis/tidy.h"
#include "core/format.h"

#include <cmath>
#include <cstdio>

namespace analysis {

namespace {
std::string point_values(const core::Scene& s) {
  std::string out;
  for (const auto& k : point_keys()) {
    std::string v = core::field_text(s, *core::find_field(k));
    if (!v.empty() && v.front() == '"') v = v.substr(1, v.size() - 2);
    out += v + ",";
  }
  return out;
}
}  // namespace

const std::vector<std::string>& point_keys() {
  static const std::vector<std::string> keys = {"size_ratio", "chi", "mu", "kick_impulse_max", "seed"};
  return keys;
}

std::string summary_header() {
  std::string h;
  for (const auto& k : point_keys()) h += k + ",";
  return h +
         "duration_s,exits,exits_original,exits_added,q_per_s,q_tilde_per_s,chi_eff,long_arches,"
         "long_arches_per_min,added_per_long_arch,members_per_long_arch,clogs,clogs_spontaneous,clogs_"
         "vibration,"
         "clogs_rule,clogs_run_end,fraction_broken_by_vibration,airborne_fraction,ballistic,health_warnings,"
         "avalanches,avalanche_mean,lapses,lapses_ge_1s,lapses_ge_2s";
}

std::string summary_row(const core::Scene& s, const Measurements& m) {
  return point_values(s) + core::format_g(m.duration) + "," + std::to_string(m.exits) + "," +
         std::to_string(m.exits_original) + "," + std::to_string(m.exits_added) + "," + core::format_g(m.q) +
         "," + core::format_g(m.q_tilde) + "," + core::format_g(m.chi_eff) + "," +
         std::to_string(m.long_arches) + "," + core::format_g(m.long_arches_per_minute) + "," +
         core::format_g(m.added_per_long_arch) + "," + core::format_g(m.members_per_long_arch) + "," +
         std::to_string(m.clogs) + "," + std::to_string(m.clogs_spontaneous) + "," +
         std::to_string(m.clogs_vibration) + "," + std::to_string(m.clogs_rule) + "," +
         std::to_string(m.clogs_run_end) + "," + core::format_g(m.fraction_broken_by_vibration) + "," +
         core::format_g(m.airborne_fraction) + "," + (m.ballistic ? "1" : "0") + "," +
         std::to_string(m.health_warnings) + "," + std::to_string(m.avalanches) + "," +
         core::format_g(m.avalanche_mean) + "," + std::to_string(m.lapses) + "," +
         std::to_string(m.lapses_ge_1s) + "," + std::to_string(m.lapses_ge_2s);
}

std::string species_csv(const core::Setup& st, const Measurements& m) {
  std::string out = "species,count,number_fraction,exits,q_per_s,exit_fraction\n";
  for (size_t k = 0; k < st.species.size(); ++k) {
    const long exits = k < m.exits_by_species.size() ? m.exits_by_species[k] : 0;
    out += st.species[k].name + "," + std::to_string(st.species[k].count) + "," +
           core::format_g(static_cast<double>(st.species[k].count) / st.n_total) + "," +
           std::to_string(exits) + "," + core::format_g(m.duration > 0 ? exits / m.duration : NAN) + "," +
           core::format_g(m.exits > 0 ? static_cast<double>(exits) / m.exits : NAN) + "\n";
  }
  return out;
}

std::vector<double> survival_taus(const core::Scene& s) {
  std::vector<double> taus;
  const double top = s.clog_timeout > 0 ? s.clog_timeout + 1.0 : 30.0;
  const int n = static_cast<int>(std::ceil(top / 0.05));
  for (int i = 0; i <= n; ++i) taus.push_back(0.05 * i);
  return taus;
}

std::string survival_csv(const core::Scene& s, const std::vector<core::ExitEvent>& exits) {
  std::string out;
  for (const auto& k : point_keys()) out += k + ",";
  out += "tau_s,survival,gaps\n";
  const auto gaps = original_gaps(exits);
  const auto taus = survival_taus(s);
  const auto p = survival(gaps, taus);
  const std::string pv = point_values(s);
  for (size_t i = 0; i < taus.size(); ++i)
    out +=
        pv + core::format_g(taus[i]) + "," + core::format_g(p[i]) + "," + std::to_string(gaps.size()) + "\n";
  return out;
}

std::string summary_text(const Measurements& m, const std::vector<std::string>& names, bool clog_rule) {
  const bool shorthand = names.size() == 2 && names[0] == "original" && names[1] == "added";
  std::string exits;
  if (shorthand) {
    exits = std::to_string(m.exits_original) + " original, " + std::to_string(m.exits_added) + " added";
  } else {
    for (size_t k = 0; k < names.size(); ++k)
      exits += (k ? ", " : "") + std::to_string(k < m.exits_by_species.size() ? m.exits_by_species[k] : 0) +
               " " + names[k];
  }
  auto num = [](double v, const char* fmt) {
    if (std::isnan(v)) return std::string("-");
    char b[32];
    std::snprintf(b, sizeof b, fmt, v);
    return std::string(b);
  };
  const std::string first = shorthand ? "originals" : names.empty() ? "first species" : names[0];
  std::string out = "discharge   " + num(m.duration, "%.1f") + " s: " + std::to_string(m.exits) + " exits (" +
                    exits + ")\n";
  out += "Q           " + num(m.q, "%.3f") + " /s   Q~ (" + first + ") " + num(m.q_tilde, "%.3f") +
         " /s   chi_eff " + (m.exits > 0 ? num(m.chi_eff, "%.3f") : std::string("- (no exits)")) + "\n";
  if (!clog_rule)
    out += "long arches none: the clog rule is off (clogs end only by the drive or the end of the run)\n";
  else if (m.long_arches == 0)
    out += "long arches none (the clog rule never fired)\n";
  else
    out += "long arches " + std::to_string(m.long_arches) + " (" + num(m.long_arches_per_minute, "%.2f") +
           " per minute), " + num(m.added_per_long_arch, "%.2f") +
           (shorthand ? " added disks" : " grains not " + first) + " per arch, " +
           num(m.members_per_long_arch, "%.2f") + " members per arch\n";
  out += "clogs       " + std::to_string(m.clogs) +
         " >= clog_min_gap: " + std::to_string(m.clogs_spontaneous) + " spontaneous, " +
         std::to_string(m.clogs_vibration) + " broken by vibration, " + std::to_string(m.clogs_rule) +
         " by the rule, " + std::to_string(m.clogs_run_end) + " open at the end\n";
  if (!m.drain_outcome.empty())
    out += "drain       " +
           (m.drain_outcome == "emptied" ? "emptied at " + num(m.drain_end_s, "%.2f") + " s"
            : m.drain_outcome == "jammed"
                ? "jammed at " + num(m.drain_end_s, "%.2f") + " s with " + std::to_string(m.drain_remaining) +
                      " grains left"
                : "still draining at the end: " + std::to_string(m.drain_remaining) +
                      " grains left (a longer duration, or clog_timeout > 0 to declare a jam)") +
           "\n";
  char h[256];
  std::snprintf(h, sizeof h, "health      %s: %.2f%% of grains in flight on average, %ld warnings\n",
                m.health_warnings > 0 ? "UNHEALTHY (--unsafe warnings)"
                : m.ballistic
                    ? "WARNING ballistic (grains thrown clear of the free surface: the drive is too strong)"
                    : "ok",
                100.0 * m.airborne_fraction, m.health_warnings);
  return out + h;
}

}  // namespace analysis
