// A recorded or imported run played back beside a live simulation (record --compare-run): its frames by time,
// on the simulation's clock, from its trajectory. The clock of both starts when the outlet opens (an imported
// run: its first frame).
#pragma once

#include <filesystem>
#include <memory>
#include <string>

#include "core/frame.h"
#include "core/model.h"
#include "io/trajectory.h"

namespace app {

class Replay {
 public:
  // RUN: a run or recording directory (with trajectory.sstraj) or the file. Throws core::InputError naming
  // it.
  explicit Replay(const std::string& run);
  // The last frame at or before t (the first before the run's first frame, the last after its end).
  core::Frame at(double t);
  const core::Model& model() const { return *model_; }
  const io::Trajectory& trajectory() const { return *traj_; }
  std::string name() const { return name_; }
  bool imported() const { return imported_; }

 private:
  std::unique_ptr<io::Trajectory> traj_;
  const core::Model* model_ = nullptr;
  std::string name_;
  bool imported_ = false;
  long k_ = 0;
};

// Why two containers differ (an empty string: the same within a millimetre): the comparison shows one
// geometry filmed the same way.
std::string container_difference(const core::Geometry& a, const core::Geometry& b);

}  // namespace app
