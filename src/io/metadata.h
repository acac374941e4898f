// The metadata file every output directory carries: the version of siloscope, how it was invoked, every scene
// parameter (its [scene] table loads back as a scene file), and derived and measured facts of the run.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "core/scene.h"

namespace io {

struct RunInfo {
  std::string command;  // the command line
  std::vector<std::pair<std::string, std::string>> facts;  // key, TOML value text; written under [run]
};

std::string version_string();  // "0.1.0 (git abc1234, Release)"
std::string metadata_toml(const core::Scene& scene, const RunInfo& info);

// Facts derived from the scene (counts, angles, the dipole's safe time step, ...), as [derived].
std::vector<std::pair<std::string, std::string>> derived_facts(const core::Scene& scene);

}  // namespace io
