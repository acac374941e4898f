#include "app/services/recording.h"
#include "app/services/terminal.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>

#include "app/services/session.h"
#include "core/error.h"
#include "core/format.h"
#include "sim/silo.h"

namespace app {

render::Annotations EventMarks::update(const sim::Silo& h, const core::StepEvents& events,
                                       const core::Frame& f) {
  const double t = f.t;
  render::Annotations notes;
  if (!events.rule_removed.empty()) {
    const core::ArchEvent& a = events.rule_removed.back();
    rings_.clear();
    // Where they stood, in the container's frame; drawn where the container is in this frame (frames may
    // reach the movie later than the world moved on: hindsight).
    const core::Vec2 off{f.container_x, f.container_y};
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

void resolve_camera_subjects(const core::Model& model, render::CameraPath& path, const std::string& what,
                             bool show) {
  const core::Scene& scene = model.scene;
  auto& keys = path.keys;
  auto key_text = [&](size_t i) {  // the option and what it says of this key
    return what == "--camera"
               ? what + " " + keys[i].camera.text
               : what + " key '" + core::format_g(keys[i].t, 6) + ":" + keys[i].camera.text + "'";
  };
  constexpr double kEvery = 0.01;  // s between a followed grain's samples
  int last_clog = 0;
  double end = 0;  // the simulated time the samples must reach
  struct Follow {
    size_t key;
    double t0, t1;
    std::shared_ptr<render::SubjectTrack> track;
  };
  std::vector<Follow> follows;
  for (size_t i = 0; i < keys.size(); ++i) {
    const render::CameraSpec& c = keys[i].camera;
    if (c.kind == render::CameraSpec::Kind::Arch) last_clog = std::max(last_clog, c.subject);
    if (c.kind != render::CameraSpec::Kind::Grain) continue;
    if (c.subject >= model.setup.n_total)
      throw core::InputError(key_text(i) + ": the scene has " + std::to_string(model.setup.n_total) +
                             " grains (ids 0 to " + std::to_string(model.setup.n_total - 1) + ")");
    // Shown from the key before (a glide in) to the key after (a glide out), or from the opening / to the
    // end.
    const double t0 = i == 0 ? 0 : keys[i - 1].t;
    const double t1 = i + 1 == keys.size() ? scene.duration : std::min(scene.duration, keys[i + 1].t);
    follows.push_back({i, t0, t1, std::make_shared<render::SubjectTrack>()});
    end = std::max(end, t1);
  }
  if (last_clog == 0 && follows.empty()) return;
  std::map<int, std::vector<core::Vec2>> arches;  // by clog number: the members' centres as it forms
  std::map<int, double> radius;                   // by clog number: the largest member's radius
  int opened = 0;
  Session session({model});
  FunctionSink probe;
  probe.on_step = [&](const sim::Silo& h, const core::StepEvents& e, size_t) {
    for (int number : e.clogs_opened) {
      opened = std::max(opened, number);
      if (number > last_clog || !h.clog().open || h.clog().number != number) continue;
      const core::Frame f = h.frame(false);
      const std::vector<double> radii = h.radii();
      auto& centres = arches[number];
      for (int id : h.clog().arch) {
        const auto& p = f.particles[static_cast<size_t>(id)];
        centres.push_back({p.x, p.y});
        radius[number] = std::max(radius[number], radii[static_cast<size_t>(id)]);
      }
    }
    return opened < last_clog || h.time() < end + kEvery;
  };
  probe.on_frame = [&](const FrameTick& tick) {
    const core::Frame& f = tick.frames[0];
    for (auto& fo : follows) {
      if (f.t < fo.t0 - kEvery || f.t > fo.t1 + kEvery) continue;
      const auto& p = f.particles[static_cast<size_t>(keys[fo.key].camera.subject)];
      fo.track->t.push_back(f.t);
      fo.track->x.push_back(p.x);
      fo.track->y.push_back(p.y);
    }
  };
  const double until = last_clog > 0 ? scene.duration : std::min(scene.duration, end + 2 * kEvery);
  Progress progress(what + ": simulating ahead to find its subjects", until, show);
  session.run(until, FrameClock::every(scene.dt, kEvery, what), {&probe}, {},
              [&](double now) { progress.update(now); });
  progress.finish();
  for (size_t i = 0; i < keys.size(); ++i) {
    render::CameraSpec& c = keys[i].camera;
    if (c.kind != render::CameraSpec::Kind::Arch) continue;
    if (opened < c.subject)
      throw core::InputError(key_text(i) + ": the run has " + std::to_string(opened) +
                             (opened == 1 ? " clog" : " clogs") + " in its " +
                             core::format_g(scene.duration, 6) + " s");
    if (arches[c.subject].empty())
      throw core::InputError(key_text(i) +
                             ": no arch blocks the outlet as that clog forms (grains resting on the floor or "
                             "an obstacle block it without one); use outlet or a window");
    render::frame_arch(c, arches[c.subject], radius[c.subject], model.setup.geo.grain_diameter);
  }
  for (auto& fo : follows) {
    if (fo.track->t.empty())  // shown only past the end of the run: where it was last seen
      throw core::InputError(key_text(fo.key) + ": shown only after the run's end (" +
                             core::format_g(scene.duration, 6) + " s)");
    // Through a removal or an exit the camera holds, then glides: the event is seen (five diameters in one
    // 0.01 s sample is no grain's motion).
    render::hold_through_jumps(*fo.track, 5 * model.setup.geo.grain_diameter);
    keys[fo.key].camera.track = fo.track;
  }
}

}  // namespace app
