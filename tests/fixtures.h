// Fixtures written once, shared by the tests of several layers.
#pragma once

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <memory>

#include "core/geometry.h"
#include "core/model.h"
#include "core/scene.h"
#include "io/metadata.h"
#include "io/trajectory.h"
#include "sim/silo.h"

namespace test {

// Five original disks in the paper's hopper: three in an arch over the aperture, loaded by two more resting
// on it (an unloaded 3-disk arch rolls off the walls; with a load it holds, as in a real column). Kicks off.
struct StagedArch {
  core::Scene scene;
  std::unique_ptr<sim::Silo> hopper;
  double y_top = 0;  // the keystone's height, m
  explicit StagedArch(std::uint64_t seed = 1) {
    core::apply_overrides(scene, {"n_total=5", "chi=0", "settle_time=0", "kick_impulse_max=0"});
    scene.seed = seed;
    hopper = std::make_unique<sim::Silo>(core::compile(scene));
    const auto& g = hopper->geometry();
    const double r = scene.radius_original, ya = 0.12;
    const double x0 = g.right_at(ya) - r / std::cos(g.wall_angle_from_vertical());
    core::Vec2 a{-x0, ya}, b{0, ya + std::sqrt(4 * r * r - x0 * x0) + 1e-4}, c{x0, ya};
    y_top = b.y;
    auto above = [r](core::Vec2 p, core::Vec2 q) {
      core::Vec2 m = 0.5 * (p + q), d = q - p;
      double len = core::length(d), h = std::sqrt(4 * r * r - 0.25 * len * len) + 1e-4;
      return m + h * core::Vec2{-d.y / len, d.x / len};
    };
    hopper->place(0, a);
    hopper->place(1, b);
    hopper->place(2, c);
    hopper->place(3, above(a, b));
    hopper->place(4, above(b, c));
  }
};

// A five-frame trajectory of two disks: an original disk moving right along y = 0.5 (x = -0.2 + 0.1 k), an
// added disk resting at (0.2, 0.8). Frames 2 and 3 are clogged (clog 1 open, timer >= 0.5 s) and hold the
// arch [0, 1]; the rule removes it at frame 4 (its events block says so).
inline std::filesystem::path synthetic_trajectory(const std::filesystem::path& dir) {
  core::Scene s;
  core::apply_overrides(s, {"n_total=2", "chi=0.5"});
  io::TrajectoryInfo info;
  info.n_particles = 2;
  info.frame_interval = 1.0 / 30;
  info.radius = {0.065f, 0.026f};
  info.species = {core::Species::Original, core::Species::Added};
  info.metadata = io::metadata_toml(core::compile(s), {"test", {}, {}, {}});
  const std::filesystem::path p = dir / "trajectory.sstraj";
  io::TrajectoryWriter w(p, info);
  for (int k = 0; k < 5; ++k) {
    core::Frame f;
    f.t = k / 30.0;
    f.particles = {{static_cast<float>(-0.2 + 0.1 * k), 0.5f, 0, 0, 0, 0.065f, 0, core::Species::Original},
                   {0.2f, 0.8f, 0, 0, 0, 0.026f, 0, core::Species::Added}};
    f.since_last_exit = (k == 2 || k == 3) ? 1.0 + k : 0.0;
    core::StepEvents e;
    if (k >= 2 && k <= 3) {
      f.arch = {0, 1};
      f.clog_open = f.clog_arrested = true;
      f.clog_number = 1;
    }
    if (k == 4) {
      core::ArchEvent a;
      a.t = f.t;
      a.ids = {0, 1};
      a.species = {core::Species::Original, core::Species::Added};
      a.x = {0.0f, 0.2f};
      a.y = {0.5f, 0.8f};
      e.rule_removed.push_back(a);
      e.clogs_closed.push_back({0.0, f.t, core::ClogEnd::Rule, true, NAN, {}});
    }
    w.add(f, k == 4 ? 1 : 0, e);
  }
  w.close();
  return p;
}

}  // namespace test
