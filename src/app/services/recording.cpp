#include "app/services/recording.h"
#include "app/services/terminal.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "app/services/session.h"
#include "core/error.h"
#include "core/format.h"
#include "sim/silo.h"

namespace app {

render::Annotations EventMarks::update(const sim::Silo& h, const core::StepEvents& events, double t) {
  render::Annotations notes;
  if (!events.rule_removed.empty()) {
    const core::ArchEvent& a = events.rule_removed.back();
    rings_.clear();
    // Where they stood, in the container's frame; drawn where the container is now.
    const core::Vec2 off = h.container_offset();
    for (size_t k = 0; k < a.ids.size() && k < a.x.size(); ++k)
      rings_.push_back({static_cast<float>(a.x[k] + off.x), static_cast<float>(a.y[k] + off.y),
                        static_cast<float>(h.radii()[static_cast<size_t>(a.ids[k])])});
    char text[96];
    std::snprintf(text, sizeof text, "arch removed (%g s rule): %zu %s", h.scene().clog_timeout, a.ids.size(),
                  h.setup().any_polygon() ? "grains" : "disks");
    start(text, a.t, true);
  }
  for (const core::ClogEvent& c : events.clogs_closed) {
    if (c.ended_by != core::ClogEnd::Vibration) continue;
    char text[96];
    std::snprintf(text, sizeof text, "clog broken by vibration after %.1f s", c.end - c.start);
    start(text, c.end, false);
  }
  if (frames_left_ > 0 || t - since_ < kMinSeconds) {
    notes.caption = caption_;
    notes.removed = rings_;
    if (frames_left_ > 0) --frames_left_;
  } else {
    rings_.clear();
  }
  return notes;
}

void EventMarks::start(const std::string& caption, double t, bool keep_rings) {
  caption_ = caption;
  since_ = t;
  frames_left_ = kMinFrames;
  if (!keep_rings) rings_.clear();
}

double color_scale_from_data(const core::Model& model, bool forces, double seconds, bool show) {
  // Frames every 0.1 s from 0.1 s to `seconds` (the end half a frame later so the last one is taken).
  const core::Scene& scene = model.scene;
  const double end = std::min(seconds, scene.duration);
  Session session({model});
  std::vector<double> values;
  FunctionSink probe;
  probe.forces = forces;
  probe.on_frame = [&](const FrameTick& tick) {
    if (tick.index == 0) return;  // the opening: everything at rest
    for (const auto& p : tick.frames[0].particles)
      values.push_back(forces ? p.force : std::hypot(p.vx, p.vy));
  };
  Progress progress("--color-max auto: simulating ahead", end, show);
  session.run(end + 0.05, FrameClock::every(scene.dt, 0.1, "--color-max auto"), {&probe}, {},
              [&](double now) { progress.update(now); });
  progress.finish();
  if (values.empty()) return 0;
  const size_t k = static_cast<size_t>(0.99 * static_cast<double>(values.size() - 1));
  std::nth_element(values.begin(), values.begin() + static_cast<long>(k), values.end());
  return values[k];
}

std::vector<int> grains_in_box(const core::Model& model, double x0, double y0, double x1, double y1, double t,
                               bool show) {
  const core::Scene& scene = model.scene;
  Session session({model});
  std::vector<int> ids;
  auto take = [&](const sim::Silo& h) {
    const core::Frame f = h.frame(false);
    for (size_t i = 0; i < f.particles.size(); ++i) {
      const auto& p = f.particles[i];
      if (p.x >= x0 && p.x <= x1 && p.y >= y0 && p.y <= y1) ids.push_back(static_cast<int>(i));
    }
  };
  if (t < 0.5 * scene.dt) {  // at the opening: no step is taken
    take(session.world(0));
    return ids;
  }
  FunctionSink probe;
  probe.on_step = [&](const sim::Silo& h, const core::StepEvents&, size_t) {
    if (h.time() < t - 0.5 * scene.dt) return true;
    take(h);
    return false;
  };
  Progress progress("--track-region: simulating ahead", t, show);
  session.run(t + scene.dt, FrameClock::none(), {&probe}, {}, [&](double now) { progress.update(now); });
  progress.finish();
  return ids;
}

std::vector<int> long_arch_members(const core::Model& model, int k, bool show) {
  const core::Scene& scene = model.scene;
  Session session({model});
  FunctionSink probe;
  std::vector<int> ids;
  int removed = 0;
  probe.on_step = [&](const sim::Silo&, const core::StepEvents& e, size_t) {
    for (const core::ArchEvent& a : e.rule_removed)
      if (++removed == k) ids = a.ids;
    return removed < k;
  };
  Progress progress("--track-arch: simulating ahead", scene.duration, show);
  session.run(scene.duration, FrameClock::none(), {&probe}, {}, [&](double now) { progress.update(now); });
  progress.finish();
  if (removed < k)
    throw core::InputError("--track-arch " + std::to_string(k) + ": the run has " + std::to_string(removed) +
                           " long-lasting arches in its " + core::format_g(scene.duration, 6) + " s");
  return ids;
}

std::vector<int> clog_arch_members(const core::Model& model, int k, bool show) {
  const core::Scene& scene = model.scene;
  Session session({model});
  FunctionSink probe;
  std::vector<int> ids;
  int opened = 0;
  probe.on_step = [&](const sim::Silo& h, const core::StepEvents& e, size_t) {
    // The k-th clog (row k of clogs.csv) as the step reports its opening; its arch is the one the step
    // found then.
    opened += static_cast<int>(e.clogs_opened.size());
    if (opened < k) return true;
    if (h.clog().open && h.clog().number == k) ids = h.clog().arch;
    return false;
  };
  Progress progress("--track-clog: simulating ahead", scene.duration, show);
  session.run(scene.duration, FrameClock::none(), {&probe}, {}, [&](double now) { progress.update(now); });
  progress.finish();
  if (opened < k)
    throw core::InputError("--track-clog " + std::to_string(k) + ": the run has " + std::to_string(opened) +
                           " clogs in its " + core::format_g(scene.duration, 6) + " s");
  if (ids.empty())
    throw core::InputError(
        "--track-clog " + std::to_string(k) +
        ": no arch blocks the outlet as that clog forms (grains resting on the floor or an "
        "obstacle block it without one)");
  return ids;
}

}  // namespace app
