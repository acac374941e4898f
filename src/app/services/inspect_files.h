// The windows' sources and sinks (ui/sources.h) made from io and record: a trajectory file's frames, PNG and
// MP4 files.
#pragma once

#include "io/trajectory.h"
#include "ui/sources.h"

namespace app {

class TrajectoryFrames : public ui::FrameSource {
 public:
  explicit TrajectoryFrames(const io::Trajectory& t) : t_(t) {}
  long size() const override { return t_.size(); }
  core::Frame frame(long k) const override { return t_.frame(k); }
  double time(long k) const override { return t_.time(k); }
  double since_last_exit(long k) const override { return t_.since_last_exit(k); }
  int long_arches(long k) const override { return t_.long_arches(k); }
  double frame_interval() const override { return t_.info().frame_interval; }
  double clog_min_gap() const override { return t_.info().clog_min_gap; }

 private:
  const io::Trajectory& t_;
};

class RecordFiles : public ui::ImageFiles {
 public:
  void write_png(const std::string& path, const core::Image& img) const override;
  void check_movie(int width, int height, int fps) const override;
  std::unique_ptr<ui::MovieSink> open_movie(const std::string& path, int width, int height,
                                            int fps) const override;
};

}  // namespace app
