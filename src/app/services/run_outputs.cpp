// A run's outputs, written the same way by run and record: events, measurements, metadata, the trajectory's
// header.
#include "app/services/run_outputs.h"

#include <cmath>
#include "io/run.h"

#include "analysis/tidy.h"
#include "core/arch.h"
#include "core/format.h"
#include "io/events_csv.h"
#include "io/output.h"
#include "io/trajectory.h"
#include "sim/silo.h"

namespace app {

analysis::Measurements measure_run(const sim::Silo& h, double duration) {
  analysis::Measurements m =
      analysis::measure(h.events(), duration, h.scene().clog_min_gap,
                        static_cast<int>(h.setup().species.size()), analysis::avalanche_end_for(h.scene()));
  m.health_warnings = h.health_warnings();
  m.airborne_fraction = h.airborne().mean();
  m.ballistic = h.ballistic();
  if (h.scene().drain) {
    m.drain_outcome = h.drain().outcome;
    m.drain_end_s = h.drain().end_s;
    m.drain_remaining = h.drain().remaining;
  }
  return m;
}

std::string arch_shapes_csv(const core::Events& ev, const std::vector<double>& radii) {
  std::string out =
      "t_s,grains,span_m,rise_m,aspect_rise_over_half_span,half_span_over_rise,theta_max_deg,defects,"
      "bead_angle_sd_deg,load_N,held_N,weight_N,imbalance\n";
  for (const auto& a : ev.arches) {
    std::vector<core::Vec2> pos(radii.size());
    std::vector<int> local;
    std::vector<double> r;
    for (size_t k = 0; k < a.ids.size() && k < a.x.size(); ++k) {
      local.push_back(static_cast<int>(k));
      pos[k] = {a.x[k], a.y[k]};
      r.push_back(radii[static_cast<size_t>(a.ids[k])]);
    }
    pos.resize(local.size());
    const core::ArchDescriptors d = core::arch_descriptors(local, pos, r);
    auto g = [](double v) { return core::format_g(v, 6); };
    auto n = [&](double v) { return std::isnan(v) ? std::string() : g(v); };  // not measured: empty
    out += g(a.t) + "," + std::to_string(d.grains) + "," + g(d.span) + "," + g(d.rise) + "," + g(d.aspect) +
           "," + g(d.inverse_aspect) + "," + g(d.theta_max_deg) + "," + std::to_string(d.defects) + "," +
           g(d.angle_sd_deg) + "," + n(a.load_N) + "," + n(a.held_N) + "," + n(a.weight_N) + "," +
           n(a.imbalance) + "\n";
  }
  return out;
}

analysis::Measurements write_run_outputs(const std::filesystem::path& dir, const sim::Silo& h,
                                         double duration, io::RunInfo info) {
  const core::Scene& scene = h.scene();
  const analysis::Measurements m = measure_run(h, duration);
  io::write_events(dir, h.events(), h.setup().species_names());
  // The arch literature's descriptors of each removed arch, beside arches.csv (whose bytes the paper's golden
  // events fix).
  io::write_file_atomic(dir / io::run_file::kArchShapes, arch_shapes_csv(h.events(), h.radii()));
  // Each clog's arch from its formation (the first check it stood), its confirmation and its members in the
  // order they arrived: what the movie and the inspector show from formation on.
  io::write_file_atomic(dir / io::run_file::kArchFormation,
                        arch_formation_csv(h.events(), scene.clog_min_gap));
  io::write_file_atomic(dir / "species.csv", analysis::species_csv(h.setup(), m));
  io::write_file_atomic(dir / "summary.csv",
                        analysis::summary_header() + "\n" + analysis::summary_row(scene, m) + "\n");
  io::write_file_atomic(dir / "survival.csv", analysis::survival_csv(scene, h.events().exits));
  info.health = health_facts(h);
  // The shortcut's work, only where it was on (metadata of ordinary runs stays as it was).
  if (scene.drain) {
    info.facts.push_back({"drain_outcome", m.drain_outcome});
    info.facts.push_back({"drain_end_s", m.drain_end_s});
    info.facts.push_back({"drain_remaining", static_cast<long>(m.drain_remaining)});
  }
  // Where the grains leave (Thomas and Durian's projection of a tilted outlet), in every run.
  const sim::Silo::ExitDirection& exit = h.exit_direction();
  info.facts.push_back({"exit_direction_exits", exit.exits});
  if (exit.exits > 0) info.facts.push_back({"exit_direction_deg", exit.mean_velocity_deg()});
  if (exit.exits > 1) info.facts.push_back({"exit_angle_sd_deg", exit.angle_sd_deg()});
  if (scene.arrest_skip > 0) {
    info.facts.push_back({"arrest_skips", h.arrest_skips()});
    info.facts.push_back({"arrest_skipped_s", h.skipped_seconds()});
  }
  io::write_file_atomic(dir / io::run_file::kMetadata, io::metadata_toml(h.model(), info));
  return m;
}

std::string arch_formation_csv(const core::Events& ev, double clog_min_gap) {
  std::string out = "clog,start_s,formed_s,confirmed_s,end_s,ended_by,formed_before_confirmed_s,arrival\n";
  for (size_t k = 0; k < ev.clogs.size(); ++k) {
    const core::ClogEvent& c = ev.clogs[k];
    if (std::isnan(c.formed)) continue;
    const double confirmed = c.start + clog_min_gap;
    std::string ids;
    for (int id : c.arrival) ids += (ids.empty() ? "" : ";") + std::to_string(id);
    out += std::to_string(k + 1) + "," + core::format_g(c.start, 9) + "," + core::format_g(c.formed, 9) +
           "," + core::format_g(confirmed, 9) + "," + core::format_g(c.end, 9) + "," +
           core::clog_end_name(c.ended_by) + "," + core::format_g(std::max(0.0, confirmed - c.formed), 6) +
           "," + ids + "\n";
  }
  return out;
}

io::Facts health_facts(const sim::Silo& h) {
  const bool ballistic = h.ballistic();
  const char* status = h.health_warnings() > 0 ? "unsafe" : ballistic ? "ballistic" : "ok";
  return {{"status", status},
          {"warnings", h.health_warnings()},
          {"ballistic", ballistic},
          {"airborne_fraction_mean", h.airborne().mean()},
          {"airborne_fraction_max", h.airborne().max},
          {"ballistic_threshold", sim::Silo::kBallisticFraction}};
}

io::TrajectoryInfo trajectory_info(const sim::Silo& h, double frame_interval, const std::string& metadata) {
  io::TrajectoryInfo t;
  t.n_particles = static_cast<std::uint32_t>(h.particle_count());
  t.n_species = static_cast<std::uint32_t>(h.setup().species.size());
  t.frame_interval = frame_interval;
  t.clog_timeout = h.scene().clog_timeout;
  t.clog_min_gap = h.scene().clog_min_gap;
  t.radius_original = h.setup().reference_radius;
  for (double r : h.radii()) t.radius.push_back(static_cast<float>(r));
  t.species = h.species();
  t.metadata = metadata;
  return t;
}

}  // namespace app
