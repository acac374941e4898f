// A run played back beside a live simulation (app/services/replay.h).
#include "app/services/replay.h"

#include <cmath>

#include "app/services/hindsight.h"
#include "app/services/terminal.h"
#include "core/error.h"
#include "core/format.h"
#include "sim/silo.h"

namespace app {

namespace fs = std::filesystem;

Replay::Replay(const std::string& run)
    : run_(io::Run::open(run, "--compare-run " + run, io::Run::kTrajectory)) {}

core::Frame Replay::at(double t) {
  const io::Trajectory& traj = run_.trajectory();
  const long n = traj.size();
  while (k_ + 1 < n && traj.time(k_ + 1) <= t + 1e-9) ++k_;
  while (k_ > 0 && traj.time(k_) > t + 1e-9) --k_;
  return traj.frame(k_);
}

void resimulate(const io::Run& run, double until, const FrameClock& clock, const std::vector<Sink*>& sinks,
                const std::string& label) {
  resimulate(
      run, until, clock, [&](const sim::Silo&) { return sinks; }, label);
}

void resimulate(const io::Run& run, double until, const FrameClock& clock, const SinksFor& sinks_for,
                const std::string& label) {
  const core::Model& model = run.model();
  Session session({model});
  // As the run itself was written: arches seen from their formation (hindsight's latency).
  HindsightSink hindsight(sinks_for(session.world(0)), model.scene.clog_min_gap + clock.frame_interval);
  Progress progress(label, until, true);
  session.run(until, clock, {&hindsight}, {}, [&](double t) { progress.update(t); });
  session.finish({&hindsight});
  progress.finish();
  check_replayed_events(run, session.world(0).events(), session.world(0).time());
}

void check_replayed_events(const io::Run& run, const core::Events& again, double t_end) {
  const core::Events& recorded = run.events();
  const double dt = run.model().scene.dt;
  auto differs = [&](const std::string& what) {
    return core::RuntimeFault("re-simulating " + run.dir().string() + " from its metadata did not give its " +
                              what + " (a different build or physics?)");
  };
  for (size_t k = 0; k < recorded.exits.size() && recorded.exits[k].t <= t_end + 0.5 * dt; ++k)
    if (k >= again.exits.size() || again.exits[k].id != recorded.exits[k].id ||
        std::fabs(again.exits[k].t - recorded.exits[k].t) > 1e-6)
      throw differs("exit " + std::to_string(k + 1) + " at t = " + core::format_g(recorded.exits[k].t, 6) +
                    " s");
  for (size_t k = 0; k < recorded.arches.size() && recorded.arches[k].t <= t_end + 0.5 * dt; ++k)
    if (k >= again.arches.size() || again.arches[k].ids != recorded.arches[k].ids)
      throw differs("long-lasting arch " + std::to_string(k + 1) +
                    " at t = " + core::format_g(recorded.arches[k].t, 6) + " s");
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
