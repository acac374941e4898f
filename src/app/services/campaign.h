// A campaign: a grid of scene points, each run for a number of realizations. Loaded from TOML:
//
//   name = "quick"
//   scene = "../scenes/paper.toml"     # relative to the campaign file
//   seed = 2022                        # realization seeds derive from (seed, point, index)
//   realizations = 4
//   duration = 40.0                    # s of discharge per realization
//   [grid]                             # Cartesian product of the lists
//   size_ratio = [0.4, 0.65, 1.0]
//   dipole_force_ratio = [0.0, 3.0]    # pseudo-key: sets mu so that the dipole force between two added disks
//                                      # in contact is this many times an added disk's weight
//   [[points]]                         # extra points, each one table of keys
//   chi = 0.0
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "core/scene.h"

namespace app {

using Assignment = std::pair<std::string, std::string>;  // scene key, value text

struct CampaignPoint {
  std::vector<Assignment> set;  // applied to the base scene, as --set key=value
  core::Scene scene;            // the resulting scene (seed not yet set)
  std::string label;            // e.g. "size_ratio=0.4,mu=1.2"
};

struct Campaign {
  std::string path, name, scene_path;  // scene_path absolute
  std::string text;                    // the file's bytes, to recognise the campaign of a results directory
  std::uint64_t seed = 1;
  int realizations = 1;
  double duration = 0;
  // > 0: every realization keeps a trajectory at this many frames per second (run --trajectory-fps), for
  // measurements the events cannot give (where each species sits in the column: analyze's column.csv).
  double trajectory_fps = 0;
  std::vector<CampaignPoint> points;

  // Seed of realization k of point p: a hash of (campaign seed, point label, k), so it does not depend on the
  // order of points or on how the work is split between machines.
  std::uint64_t realization_seed(size_t p, int k) const;
  // Where realization k of point p lives under a results directory.
  std::string run_dir(size_t p, int k) const;
  // The keys the points set beyond the paper's (size_ratio, chi, mu, kick_impulse_max; dipole_force_ratio
  // sets mu): what `analyze --by` must tell the points apart by.
  std::vector<std::string> extra_point_keys() const;
};

// Throws core::InputError naming the file, the key and the problem (empty grid, unknown key, duplicate
// point...).
Campaign load_campaign(const std::string& path);
// The same from text; `path` names it in errors and anchors the relative scene path.
Campaign parse_campaign(const std::string& text, const std::string& path);

}  // namespace app
