#include "app/services/session.h"

#include "core/interrupt.h"

#include <algorithm>
#include <cmath>
#include <future>

#include "core/error.h"
#include "core/format.h"
#include "sim/silo.h"

namespace app {

namespace {
std::string num6(double v) {
  return core::format_g(v, 6);
}
}  // namespace

FrameClock FrameClock::every(double dt, double interval, const std::string& option) {
  FrameClock c;
  const double exact = interval / dt;
  if (!(exact >= 0.5) || !std::isfinite(exact))
    throw core::InputError(option + ": a frame every " + num6(interval) +
                           " s is shorter than one time step (dt = " + num6(dt) + " s)");
  c.steps = c.slow_steps = std::max(1L, std::lround(exact));
  if (std::abs(c.steps - exact) / exact > 0.05)
    throw core::InputError(option + ": a frame every " + num6(interval) + " s needs " + num6(exact) +
                           " time steps per frame; the nearest whole number (" + std::to_string(c.steps) +
                           ") is more than 5% off: frames every " + num6(c.steps * dt) + " s");
  c.frame_interval = c.steps * dt;
  return c;
}

FrameClock FrameClock::video(double dt, int fps, double speed, double slowmo) {
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

FrameClock FrameClock::at_steps(std::vector<long> steps) {
  FrameClock c;
  std::sort(steps.begin(), steps.end());
  steps.erase(std::unique(steps.begin(), steps.end()), steps.end());
  c.at = std::move(steps);
  return c;
}

Session::Session(const std::vector<core::Model>& models) {
  if (models.empty()) throw core::InputError("a session needs a scene");
  worlds_.resize(models.size());
  last_removal_.assign(models.size(), -INFINITY);
  // Each world deposits and settles on its own thread (a comparison's panels cost one settling's time).
  std::vector<std::future<void>> others;
  for (size_t k = 1; k < models.size(); ++k)
    others.push_back(
        std::async(std::launch::async, [&, k] { worlds_[k] = std::make_unique<sim::Silo>(models[k]); }));
  std::exception_ptr first;
  try {
    worlds_[0] = std::make_unique<sim::Silo>(models[0]);
  } catch (...) {
    first = std::current_exception();
  }
  for (auto& f : others) {
    try {
      f.get();
    } catch (...) {
      if (!first) first = std::current_exception();
    }
  }
  if (first) std::rethrow_exception(first);
}

Session::~Session() = default;

long Session::step() const {
  return std::lround(worlds_[0]->time() / worlds_[0]->scene().dt);
}

long Session::end_step(double end) const {
  // The first step at which t >= end - dt/2: every command's run ends there.
  const double dt = worlds_[0]->scene().dt;
  return std::max(0L, static_cast<long>(std::ceil(end / dt - 0.5 - 1e-9)));
}

void Session::step_all(long n) {
  if (n <= 0) return;
  if (worlds_.size() == 1) {
    for (long s = 0; s < n; ++s) worlds_[0]->step();
    return;
  }
  std::vector<std::future<void>> others;
  for (size_t k = 1; k < worlds_.size(); ++k)
    others.push_back(std::async(std::launch::async, [&, k] {
      for (long s = 0; s < n; ++s) worlds_[k]->step();
    }));
  std::exception_ptr first;
  try {
    for (long s = 0; s < n; ++s) worlds_[0]->step();
  } catch (...) {
    first = std::current_exception();
  }
  for (auto& f : others) {
    try {
      f.get();  // rethrows a world's error
    } catch (...) {
      if (!first) first = std::current_exception();
    }
  }
  if (first) std::rethrow_exception(first);
}

bool Session::run(double end, const FrameClock& clock, const std::vector<Sink*>& sinks,
                  const std::function<bool()>& stop, const std::function<void(double)>& progress) {
  const double dt = worlds_[0]->scene().dt;
  const long last = end_step(end);
  bool forces = false, per_step = false, want_frames = false;
  for (const Sink* s : sinks) {
    want_frames = want_frames || s->wants_frames();
    forces = forces || s->wants_forces();
    per_step = per_step || s->wants_steps();
  }
  const bool frames = clock.steps > 0 || !clock.at.empty();
  // Frames that carry forces carry each contact's mean over the frame interval, not one step's.
  if (forces && frames)
    for (const auto& w : worlds_)
      if (!w->averaging_forces()) w->average_forces(true);
  size_t listed = 0;  // the next of clock.at
  while (listed < clock.at.size() && clock.at[listed] < step()) ++listed;
  // A frame is taken while its time is at most the end less half a frame interval (the first always).
  auto frame_ok = [&](long s) {
    if (!clock.at.empty()) return s <= last;
    return frames_taken_ == 0 || s * dt <= end - 0.5 * clock.frame_interval + 1e-9;
  };
  auto next_due = [&]() -> long {
    if (!clock.at.empty()) return listed < clock.at.size() ? clock.at[listed] : -1;
    return clock.steps > 0 ? next_frame_step_ : -1;
  };
  const long poll_every = std::max(1L, std::lround(0.5 / dt));
  long s = step(), polled = s;
  for (;;) {
    const long due = frames ? next_due() : -1;
    if (due == s && frame_ok(s)) {
      FrameTick tick;
      tick.index = frames_taken_;
      tick.step = s;
      for (const auto& w : worlds_) {
        if (want_frames) tick.frames.push_back(w->frame(forces));
        if (w->averaging_forces()) w->restart_force_average();
        tick.events.push_back(w->take_events());
        tick.worlds.push_back(w.get());
      }
      // Slow motion (record --slowmo): from 0.5 s before a clog rule is due to 1 s after a removal, any world
      // (both as the steps reported them).
      if (clock.steps > 0 && clock.slow_steps != clock.steps)
        for (size_t k = 0; k < worlds_.size(); ++k) {
          const core::StepEvents& e = tick.events[k];
          if (!e.rule_removed.empty()) last_removal_[k] = e.rule_removed.back().t;
          tick.slow = tick.slow || e.rule_due_in <= 0.5 || worlds_[k]->time() - last_removal_[k] < 1.0;
        }
      for (Sink* sink : sinks) sink->frame(tick);
      ++frames_taken_;
      if (!clock.at.empty())
        ++listed;
      else
        next_frame_step_ = s + (tick.slow ? clock.slow_steps : clock.steps);
      for (const Sink* sink : sinks)
        if (sink->done()) return false;
      if (stop && stop()) return false;
    }
    if (s >= last) break;
    long target = last;
    const long upcoming = frames ? next_due() : -1;
    if (upcoming > s) target = std::min(target, upcoming);
    target = std::min(target, polled + poll_every);
    if (per_step) {
      for (; s < target; ++s)
        for (size_t k = 0; k < worlds_.size(); ++k) {
          const core::StepEvents& e = worlds_[k]->step();
          for (Sink* sink : sinks)
            if (sink->wants_steps()) sink->step(*worlds_[k], e, k);
        }
      for (const Sink* sink : sinks)
        if (sink->done()) return false;
    } else {
      step_all(target - s);
      s = target;
    }
    if (s - polled >= poll_every) {
      polled = s;
      // Without frames no sink collects the worlds' reports (per-step sinks had them): drop them here so a
      // long run does not keep a second copy of its events.
      if (!frames)
        for (auto& w : worlds_) w->take_events();
      if (progress) progress(worlds_[0]->time());
      if (stop && stop()) return false;
      // A caller without its own way of ending an interrupted run (run and record keep what they have) stops
      // here on Ctrl-C: core::Interrupted unwinds to the command frame, removing what was being built.
      if (!stop) core::throw_if_interrupted();
    }
  }
  return true;
}

void Session::finish(const std::vector<Sink*>& sinks) {
  std::vector<core::StepEvents> closed;
  for (auto& w : worlds_) {
    w->finish();
    closed.push_back(w->take_events());
  }
  for (Sink* sink : sinks) sink->finished(closed);
}

}  // namespace app
