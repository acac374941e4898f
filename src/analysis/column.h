// Where each species sits in the column (the paper's C4.2: "magnetic disks float on top of the column"),
// measured on a run's frames: in each frame of the discharge, the grains above the outlet are ranked by their
// height along gravity (0 the lowest, 1 the highest: rank (i + 1/2) / n), and each species' mean rank is
// taken; a run's value is the mean over its frames. A species spread evenly through the column has rank 1/2;
// one that floats on top lies above, one that sinks below. Grains below the outlet (falling out, or a drain's
// parked ones) are not in the column.
#pragma once

#include <vector>

#include "core/frame.h"

namespace analysis {

class ColumnMeter {
 public:
  // `tilt`: the container's tilt, rad (heights along gravity: a tilted column's free surface is level in the
  // laboratory); `n_species`: the scene's species.
  ColumnMeter(double tilt, int n_species);
  // Frames before the aperture opened (t < 0) are skipped.
  void add(const core::Frame& f);
  long frames() const { return frames_; }
  // Each species' mean rank over the frames measured (NaN for a species never in the column, or no frame).
  std::vector<double> ranks() const;

 private:
  double up_x_, up_y_;
  std::vector<double> sum_;  // per species, the sum over frames of its mean rank in the frame
  std::vector<long> seen_;   // frames the species was in the column
  long frames_ = 0;
  std::vector<std::pair<double, int>> order_;  // scratch: (height, species)
};

}  // namespace analysis
