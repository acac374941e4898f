// The recording's clock and its on-screen events: when `record` takes a frame, and what it marks on it.
#pragma once

#include <string>
#include <vector>

#include "core/frame.h"
#include "core/scene.h"

namespace sim {
class Hopper;
}

namespace app {

// When record takes a frame: a whole number of time steps per frame (refused with the nearest good --speed if
// that would change the frame rate by more than 5%), and fewer around a clog's removal for --slowmo.
struct FrameClock {
  long steps = 1, slow_steps = 1;  // time steps per frame, normally and in slow motion
  double frame_interval = 0;       // s of simulation per frame (steps * dt)
  double video_fps = 0;            // frames per video second written into the movie (speed / frame_interval)
  double effective_slowmo = 1;     // steps / slow_steps
};
FrameClock make_frame_clock(double dt, int fps, double speed, double slowmo);

// --color-max auto: the top of the speed (forces = false) or contact-force scale taken from the data, the
// 99th percentile of every disk's value over frames every 0.1 s of the first `seconds` of discharge,
// simulated ahead from the same scene and seed (one extra settling). 0 if everything stayed at rest.
double color_scale_from_data(const core::Scene& scene, bool forces, double seconds);

// The marks record puts on its frames (core::Marks): the members of the last rule removal, ringed where they
// stood, and a caption, after each rule firing or clog broken by vibration, for at least kMinFrames frames
// and kMinSeconds of simulated time.
class EventMarks {
 public:
  static constexpr int kMinFrames = 10;
  static constexpr double kMinSeconds = 0.7;
  void update(const sim::Hopper& h, core::Frame& f);

 private:
  void start(const std::string& caption, double t, bool keep_rings);
  size_t arches_seen_ = 0, clogs_seen_ = 0;
  std::vector<core::Marks::Ring> rings_;
  std::string caption_;
  double since_ = -1e9;
  int frames_left_ = 0;
};

}  // namespace app
