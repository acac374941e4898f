// A run played back beside a live simulation (app/services/replay.h).
#include "app/services/replay.h"

#include <cmath>

#include "app/services/inspect_files.h"
#include "core/error.h"
#include "core/format.h"

namespace app {

namespace fs = std::filesystem;

Replay::Replay(const std::string& run) {
  fs::path p = run;
  if (fs::is_directory(p)) p /= "trajectory.sstraj";
  if (!fs::exists(p))
    throw core::InputError("--compare-run " + run +
                           ": no trajectory.sstraj (a recording, an imported run, or a run "
                           "written with --trajectory-fps)");
  traj_ = std::make_unique<io::Trajectory>(p);
  model_ = &run_model(*traj_, p.string());
  name_ = fs::absolute(fs::path(run)).lexically_normal().filename().string();
  if (name_.empty() || name_ == "trajectory.sstraj")
    name_ = fs::absolute(p).parent_path().filename().string();
  imported_ = traj_->info().metadata.find("\nimported = true") != std::string::npos;
}

core::Frame Replay::at(double t) {
  const long n = traj_->size();
  while (k_ + 1 < n && traj_->time(k_ + 1) <= t + 1e-9) ++k_;
  while (k_ > 0 && traj_->time(k_) > t + 1e-9) --k_;
  return traj_->frame(k_);
}

std::string container_difference(const core::Geometry& a, const core::Geometry& b) {
  const double tol = 1e-3;
  auto differs = [&](double x, double y) { return std::fabs(x - y) > tol; };
  if (a.kind != b.kind) return "one is a hopper, the other a flat silo";
  if (differs(a.half_aperture, b.half_aperture))
    return "outlet " + core::format_g(2 * a.half_aperture, 4) + " m against " +
           core::format_g(2 * b.half_aperture, 4) + " m";
  if (differs(a.x_left, b.x_left) || differs(a.x_right, b.x_right))
    return "width " + core::format_g(a.x_right - a.x_left, 4) + " m against " +
           core::format_g(b.x_right - b.x_left, 4) + " m";
  if (differs(a.hopper_height, b.hopper_height))
    return "hopper height " + core::format_g(a.hopper_height, 4) + " m against " +
           core::format_g(b.hopper_height, 4) + " m";
  if (a.obstacle.kind != b.obstacle.kind || differs(a.obstacle.centre.y, b.obstacle.centre.y) ||
      differs(a.obstacle.width, b.obstacle.width))
    return "the obstacles differ";
  return "";
}

}  // namespace app
