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
         "avalanches,avalanche_mean";
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
         core::format_g(m.avalanche_mean);
}

std::vector<double> survival_taus(const core::Scene& s) {
  std::vector<double> taus;
  const int n = static_cast<int>(std::ceil((s.clog_timeout + 1.0) / 0.05));
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

std::string summary_text(const Measurements& m) {
  char b[1024];
  std::snprintf(b, sizeof b,
                "discharge   %.1f s: %ld exits (%ld original, %ld added)\n"
                "Q           %.3f /s   Q~ (originals) %.3f /s   chi_eff %.3f\n"
                "long arches %ld (%.2f per minute), %.2f added disks per arch, %.2f members per arch\n"
                "clogs       %ld >= clog_min_gap: %ld spontaneous, %ld broken by vibration, %ld by the rule, "
                "%ld open at the end\n",
                m.duration, m.exits, m.exits_original, m.exits_added, m.q, m.q_tilde, m.chi_eff,
                m.long_arches, m.long_arches_per_minute, m.added_per_long_arch, m.members_per_long_arch,
                m.clogs, m.clogs_spontaneous, m.clogs_vibration, m.clogs_rule, m.clogs_run_end);
  std::string out = b;
  char h[256];
  std::snprintf(h, sizeof h, "health      %s: %.2f%% of disks in flight on average, %ld warnings\n",
                m.health_warnings > 0 ? "UNHEALTHY (--unsafe warnings)"
                : m.ballistic         ? "WARNING ballistic (the kicks throw disks above the column)"
                                      : "ok",
                100.0 * m.airborne_fraction, m.health_warnings);
  return out + h;
}

}  // namespace analysis
