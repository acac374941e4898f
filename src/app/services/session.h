// One simulation loop for every command. A Session holds one world per scene (a comparison movie has 2 to 4,
// stepped side by side on one clock), steps them to the end of the run, and at every frame the FrameClock
// says is due hands the frames to its sinks (a trajectory file, the movie pipeline, a look-ahead, a gallery's
// capture, a benchmark's probe). `run`, `record`, `--compare`, the colour-scale look-ahead, `gallery`, `live`
// and the benches are configurations of it, so two things are decided here once, identically for all:
//   - when a frame is taken: every `steps` time steps from the opening (fewer around a clog rule's firing in
//     slow motion, or at listed steps), while its time is at most the end less half a frame interval;
//   - when the run ends: at the step where t >= end - dt/2 (a whole number of steps; never past it).
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/events.h"
#include "core/frame.h"
#include "core/model.h"
#include "core/scene.h"

namespace sim {
class Silo;
}

namespace app {

// When frames are taken: a whole number of time steps between them (one rule for every command).
struct FrameClock {
  long steps = 0;               // time steps per frame; 0: no frames
  long slow_steps = 0;          // per frame in slow motion (around a long-lasting arch's removal)
  double frame_interval = 0;    // s of simulation per frame (steps * dt)
  double video_fps = 0;         // frames per video second (record: speed / frame_interval)
  double effective_slowmo = 1;  // steps / slow_steps
  std::vector<long> at;         // instead: frames at exactly these steps after the opening (gallery)

  // No frames.
  static FrameClock none() { return {}; }
  // A frame every `interval` s of simulation at time step dt: refused (naming `option`) when interval is not
  // within 5% of a whole number of steps, or shorter than one step; the interval becomes steps * dt exactly.
  static FrameClock every(double dt, double interval, const std::string& option);
  // record: --fps video frames per video second showing --speed simulated s per video s, --slowmo times
  // slower around each rule removal. Refused with the nearest good --speed when it needs a fraction of a
  // step.
  static FrameClock video(double dt, int fps, double speed, double slowmo);
  // Frames at these steps (each >= 0) after the opening.
  static FrameClock at_steps(std::vector<long> steps);
};

// What a frame tick hands to the sinks: each world's frame (if any sink asked for frames), what each world's
// steps reported since the previous tick (core/events.h: the only account of exits, clogs, arches and the
// rule), and the worlds.
struct FrameTick {
  long index = 0;                        // 0, 1, 2, ...
  long step = 0;                         // time steps since the opening
  bool slow = false;                     // taken at slow-motion spacing
  std::vector<core::Frame> frames;       // one per world, in world order
  std::vector<core::StepEvents> events;  // one per world: since the previous tick (the first: since opening)
  std::vector<const sim::Silo*> worlds;  // the same order
};

// Something that watches a session. Every hook is optional.
class Sink {
 public:
  virtual ~Sink() = default;
  // A frame is due (only when the clock takes frames).
  virtual void frame(const FrameTick&) {}
  // What the sink needs in FrameTick::frames: the frames at all, contact forces (each costs time).
  virtual bool wants_frames() const { return true; }
  virtual bool wants_forces() const { return false; }
  // Called after every time step of world k, with what that step reported, when wants_steps() (probes that
  // watch every step).
  virtual bool wants_steps() const { return false; }
  virtual void step(const sim::Silo&, const core::StepEvents&, size_t /*world*/) {}
  // The run's end closed the worlds' open clogs (Session::finish): their censored rows, per world.
  virtual void finished(const std::vector<core::StepEvents>&) {}
  // True to stop the run early (a closed pipeline, a probe that has seen enough).
  virtual bool done() const { return false; }
};

class Session {
 public:
  // One world per scene, built in parallel (deposit, settle, open). `slow_near_rule`: frames at slow spacing
  // from 0.5 s before any world's clog rule fires to 1 s after a removal (record --slowmo).
  explicit Session(const std::vector<core::Model>& models);
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;

  size_t size() const { return worlds_.size(); }
  sim::Silo& world(size_t k) { return *worlds_[k]; }
  const sim::Silo& world(size_t k) const { return *worlds_[k]; }

  // Step every world from where it stands to `end` s, with frames by `clock` to `sinks`. `stop` is polled
  // every half simulated second (Ctrl-C); `progress(t)` too. Returns false if a sink or `stop` ended it
  // early. Without `stop`, Ctrl-C throws core::Interrupted at those polls.
  bool run(double end, const FrameClock& clock, const std::vector<Sink*>& sinks,
           const std::function<bool()>& stop = {}, const std::function<void(double)>& progress = {});
  // The step index of time `end`: where t >= end - dt/2.
  long end_step(double end) const;
  // Close the worlds' open clogs (censored at the run's end); once, after the last run(). Sinks hear of it.
  void finish(const std::vector<Sink*>& sinks = {});
  // The steps since the opening of world 0.
  long step() const;

 private:
  void step_all(long n);
  std::vector<std::unique_ptr<sim::Silo>> worlds_;
  std::vector<double> last_removal_;  // s, each world's last rule removal (slow motion)
  long next_frame_step_ = 0, frames_taken_ = 0;
};

// A sink from functions: the frame and step hooks a command needs without a class of its own.
class FunctionSink : public Sink {
 public:
  std::function<void(const FrameTick&)> on_frame;
  // Returns false to stop the run.
  std::function<bool(const sim::Silo&, const core::StepEvents&, size_t)> on_step;
  bool frames = true, forces = false;
  void frame(const FrameTick& t) override {
    if (on_frame) on_frame(t);
  }
  bool wants_frames() const override { return frames && static_cast<bool>(on_frame); }
  bool wants_forces() const override { return forces; }
  bool wants_steps() const override { return static_cast<bool>(on_step); }
  void step(const sim::Silo& h, const core::StepEvents& e, size_t k) override {
    stopped_ = stopped_ || (on_step && !on_step(h, e, k));
  }
  bool done() const override { return stopped_; }

 private:
  bool stopped_ = false;
};

}  // namespace app
