// A run's outputs, written the same way by run and record: events, measurements, arch descriptors, metadata,
// and the header of its trajectory.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "analysis/measure.h"
#include "core/frame.h"
#include "io/metadata.h"

namespace sim {
class Silo;
}
namespace io {
struct TrajectoryInfo;
}

namespace app {

// The header of a trajectory of `h`: radii, species, the scene's clog settings, `metadata` (TOML text).
io::TrajectoryInfo trajectory_info(const sim::Silo& h, double frame_interval, const std::string& metadata);
// The [health] table of a run's metadata: warnings under --unsafe, disks in flight, the "ballistic" warning.
io::Facts health_facts(const sim::Silo& h);
// A finished run's measurements over `duration` s of discharge, with its health (for summary.csv).
analysis::Measurements measure_run(const sim::Silo& h, double duration);
// arch_formation.csv: per clog with an arch, when it formed (before the clog's confirmation at start +
// clog_min_gap), and its members in the order they arrived.
std::string arch_formation_csv(const core::Events& ev, double clog_min_gap);
// arch_shapes.csv: per arch the clog rule removed, the descriptors of core::arch_descriptors.
std::string arch_shapes_csv(const core::Events& ev, const std::vector<double>& radii);
// A run's outputs into `dir`: exits/clogs/arches.csv, arch_shapes.csv, species.csv, summary.csv,
// survival.csv and metadata.toml (info, with the run's health added). Returns the measurements of `duration`
// s.
analysis::Measurements write_run_outputs(const std::filesystem::path& dir, const sim::Silo& h,
                                         double duration, io::RunInfo info);

}  // namespace app
