// The metadata file every output directory carries: the version of siloscope, how it was invoked, every scene
// parameter (its [scene] table loads back as a scene file), and derived and measured facts of the run.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "core/scene.h"

namespace io {

struct RunInfo {
  std::string command;                                      // the command line
  std::vector<std::pair<std::string, std::string>> facts;   // key, TOML value text; written under [run]
  std::vector<std::pair<std::string, std::string>> health;  // key, TOML value text; written under [health]
};

// What a run's metadata says about its health and coverage (defaults when the tables or keys are absent).
struct RunRecord {
  long health_warnings = 0;      // --unsafe warnings (the run went on past a failed health check)
  bool ballistic = false;        // disks in flight above the column on average (kicks too strong)
  double airborne_fraction = 0;  // mean fraction of disks in flight
  bool interrupted = false;      // stopped before its planned duration
  double covered_s = -1;         // s of discharge the run covered (-1: the planned duration)
};
// Throws core::InputError naming the file when it is not valid TOML.
RunRecord read_run_record(const std::string& metadata_path);

std::string version_string();  // "0.1.0 (git abc1234, Release)"
std::string metadata_toml(const core::Scene& scene, const RunInfo& info);

// Facts derived from the scene (counts, angles, the dipole's safe time step, ...), as [derived].
std::vector<std::pair<std::string, std::string>> derived_facts(const core::Scene& scene);

}  // namespace io
