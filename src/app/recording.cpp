#include "app/recording.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/error.h"
#include "core/format.h"
#include "sim/hopper.h"

namespace app {

namespace {
std::string num6(double v) {
  return core::format_g(v, 6);
}
}  // namespace

FrameClock make_frame_clock(double dt, int fps, double speed, double slowmo) {
  FrameClock c;
  const double wanted = speed / fps;  // simulated seconds per video frame asked for
  const double exact = wanted / dt;
  if (exact < 0.5)
    throw core::InputError("--speed " + num6(speed) + " at --fps " + std::to_string(fps) +
                           " asks for a frame every " + num6(wanted) +
                           " s of simulation, less than one time step (dt = " + num6(dt) +
                           " s); use --speed >= " + num6(fps * dt) + " or a lower --fps");
  c.steps = std::max(1L, std::lround(exact));
  // A whole number of steps per frame; the rate written into the movie follows it (33 steps of 1 ms at 30
  // fps: 1000/33 = 30.30 frames per video second), so video time stays equal to simulated time / speed.
  if (std::abs(c.steps - exact) / exact > 0.05)
    throw core::InputError(
        "--speed " + num6(speed) + " at --fps " + std::to_string(fps) + " needs " + num6(exact) +
        " time steps per frame; the nearest whole number (" + std::to_string(c.steps) +
        ") would change the frame rate by more than 5%; use --speed " + num6(c.steps * dt * fps) + " or " +
        num6(std::max(1L, c.steps + (exact > c.steps ? 1 : -1)) * dt * fps));
  c.slow_steps = std::max(1L, std::lround(c.steps / slowmo));
  if (slowmo > 1 && c.steps / slowmo < 0.5)
    throw core::InputError("--slowmo " + num6(slowmo) + " would need less than one time step per frame (" +
                           std::to_string(c.steps) + " steps per frame at this --speed); the most is " +
                           std::to_string(2 * c.steps));
  c.frame_interval = c.steps * dt;
  c.video_fps = speed / c.frame_interval;
  c.effective_slowmo = static_cast<double>(c.steps) / static_cast<double>(c.slow_steps);
  return c;
}

void EventMarks::update(const sim::Hopper& h, core::Frame& f) {
  const auto& arches = h.events().arches;
  const auto& clogs = h.events().clogs;
  if (arches.size() > arches_seen_) {
    const core::ArchEvent& a = arches.back();
    rings_.clear();
    for (size_t k = 0; k < a.ids.size() && k < a.x.size(); ++k)
      rings_.push_back({a.x[k], a.y[k], static_cast<float>(h.radii()[static_cast<size_t>(a.ids[k])])});
    char text[96];
    std::snprintf(text, sizeof text, "arch removed (%g s rule): %zu %s", h.scene().clog_timeout, a.ids.size(),
                  h.setup().any_polygon() ? "grains" : "disks");
    start(text, a.t, true);
    arches_seen_ = arches.size();
  }
  if (clogs.size() > clogs_seen_) {
    const core::ClogEvent& c = clogs.back();
    if (c.ended_by == core::ClogEnd::Vibration) {
      char text[96];
      std::snprintf(text, sizeof text, "clog broken by vibration after %.1f s", c.end - c.start);
      start(text, c.end, false);
    }
    clogs_seen_ = clogs.size();
  }
  if (frames_left_ > 0 || f.t - since_ < kMinSeconds) {
    f.marks.caption = caption_;
    f.marks.removed = rings_;
    if (frames_left_ > 0) --frames_left_;
  } else {
    rings_.clear();
  }
}

void EventMarks::start(const std::string& caption, double t, bool keep_rings) {
  caption_ = caption;
  since_ = t;
  frames_left_ = kMinFrames;
  if (!keep_rings) rings_.clear();
}

double color_scale_from_data(const core::Scene& scene, bool forces, double seconds) {
  sim::Hopper h(scene);
  std::vector<double> values;
  const double end = std::min(seconds, scene.duration);
  for (double t = 0.1; t <= end + 1e-9; t += 0.1) {
    h.advance_to(t);
    const core::Frame f = h.frame(false, forces);
    for (const auto& p : f.particles) values.push_back(forces ? p.force : std::hypot(p.vx, p.vy));
  }
  if (values.empty()) return 0;
  const size_t k = static_cast<size_t>(0.99 * static_cast<double>(values.size() - 1));
  std::nth_element(values.begin(), values.begin() + static_cast<long>(k), values.end());
  return values[k];
}

}  // namespace app
