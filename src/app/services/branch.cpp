#include "app/services/branch.h"

#include <cmath>

#include "app/services/cli.h"
#include "app/services/hindsight.h"
#include "app/services/replay.h"
#include "app/services/run_outputs.h"
#include "app/services/session.h"
#include "app/services/sinks.h"
#include "core/error.h"
#include "core/format.h"
#include "io/metadata.h"
#include "io/output.h"
#include "sim/silo.h"

namespace app {

namespace {

// Keeps every frame tick (after hindsight marked each clog's arch from its formation) and the clogs the
// end closed: what the saved branch's trajectory holds.
class TickStore : public Sink {
 public:
  void frame(const FrameTick& t) override { ticks.push_back(t); }
  bool wants_forces() const override { return true; }
  void finished(const std::vector<core::StepEvents>& c) override { closed = c; }
  std::vector<FrameTick> ticks;
  std::vector<core::StepEvents> closed;
};

class SiloBranch : public ui::Branch {
 public:
  SiloBranch(const io::Run& run, long k)
      : run_(run),
        from_(k),
        clock_(FrameClock::every(run.model().scene.dt, run.trajectory().info().frame_interval,
                                 "the trajectory's frame interval")),
        session_(std::vector<core::Model>{run.model()}),
        hindsight_({&store_}, run.model().scene.clog_min_gap + clock_.frame_interval) {
    const double t = run.trajectory().time(k);
    session_.run(t, clock_, {&hindsight_});
    sim::Silo& w = session_.world(0);
    check_replayed_events(run, w.events(), w.time());
    // The recorded frame and the rebuilt state agree grain by grain (the trajectory keeps floats).
    const core::Frame rec = run.trajectory().frame(k), now = w.frame(false);
    for (size_t i = 0; i < rec.particles.size() && i < now.particles.size(); ++i) {
      const double d =
          std::hypot(rec.particles[i].x - now.particles[i].x, rec.particles[i].y - now.particles[i].y);
      if (d > 1e-4)
        throw core::InputError("branch at frame " + std::to_string(k) + ": re-simulating " +
                               run.dir().string() + " put grain " + std::to_string(i) + " " +
                               core::format_g(d, 3) +
                               " m from where the trajectory has it (a different build or physics?)");
    }
  }
  long from_frame() const override { return from_; }
  double time() const override { return session_.world(0).time(); }
  core::Frame frame() const override { return session_.world(0).frame(true); }
  void advance_to(double t) override {
    writable("continue");
    session_.run(t, clock_, {&hindsight_});
  }
  void remove_grain(int id) override {
    writable("remove grain");
    session_.world(0).remove_by_hand({id});
    note("grain " + std::to_string(id) + " removed");
  }
  void kick(double dv) override {
    writable("kick");
    if (!(dv > 0 && dv <= 10))
      throw core::InputError("kick " + core::format_g(dv) +
                             ": the velocity change must be > 0 and at most 10 m/s");
    session_.world(0).kick_all(dv);
    note("every grain kicked up by " + core::format_g(dv, 4) + " m/s");
  }
  void set_key(const std::string& key, double value) override {
    writable("set");
    sim::Silo& w = session_.world(0);
    const std::vector<std::string> names = w.setup().species_names();
    // The dipole keys: `mu` (the paper's shorthand: the added disks) or species.NAME.dipole.
    int species = -1;
    if (key == "mu" && w.setup().shorthand) species = 1;
    for (size_t k = 0; k < names.size(); ++k)
      if (key == "species." + names[k] + ".dipole") species = static_cast<int>(k);
    if (species >= 0) {
      if (!(value >= 0 && value <= 100))
        throw core::InputError("set " + key + " " + core::format_g(value) + ": allowed 0 to 100 A*m^2");
      w.set_dipole(species, value);
      return note(key + " = " + core::format_g(value, 6) + " A*m^2");
    }
    if (key != "kick_impulse_max")
      throw core::InputError("set " + key +
                             ": a branch changes kick_impulse_max (N s) and the dipole moments (" +
                             std::string(w.setup().shorthand ? "mu, " : "") + "species.NAME.dipole, A*m^2)");
    if (!(value >= 0 && value <= 1))
      throw core::InputError("set kick_impulse_max " + core::format_g(value) + ": allowed 0 to 1 N s");
    w.set_kick_impulse_max(value);
    note("kick_impulse_max = " + core::format_g(value, 6) + " N s");
  }
  std::vector<std::string> changes() const override { return changes_; }
  bool saved() const override { return saved_; }
  void save(const std::string& dir) override {
    writable("save branch");
    io::OutputDir out(dir, false, io::DirKind::Run);
    saved_ = true;  // the run's end closes its open clog: it cannot go on
    session_.finish({&hindsight_});
    const sim::Silo& w = session_.world(0);
    io::RunInfo info;
    info.command = command_line();
    std::string changed;
    for (const auto& c : changes_) changed += (changed.empty() ? "" : "; ") + c;
    info.facts = {{"branch_of", run_.dir().string()},
                  {"branch_frame", from_},
                  {"branch_time_s", run_.trajectory().time(from_)},
                  {"branch_changes", changed},
                  {"steps", static_cast<long>(w.steps())},
                  {"interrupted", true},
                  {"simulated_s", w.time()}};
    {
      io::RunInfo tinfo{info.command, {}, {}, {}};
      TrajectorySink traj(out.file(io::run_file::kTrajectory),
                          trajectory_info(w, clock_.frame_interval, io::metadata_toml(w.model(), tinfo)));
      for (const auto& t : store_.ticks) traj.frame(t);
      if (!store_.closed.empty()) traj.finished(store_.closed);
      traj.close();
    }
    write_run_outputs(out.file(""), w, w.time(), info);
    out.commit();
  }

 private:
  void writable(const char* what) const {
    if (saved_)
      throw core::InputError(std::string(what) +
                             ": this branch was saved and ended there; `branch at FRAME` starts another");
  }
  void note(const std::string& what) {
    changes_.push_back("t = " + core::format_g(time(), 6) + " s: " + what);
  }
  const io::Run& run_;
  long from_;
  FrameClock clock_;
  Session session_;
  TickStore store_;
  HindsightSink hindsight_;
  std::vector<std::string> changes_;
  bool saved_ = false;
};

}  // namespace

std::unique_ptr<ui::Branch> RunBrancher::branch(long k) const {
  if (!run_.has_trajectory() || k < 0 || k >= run_.trajectory().size())
    throw core::InputError("branch at frame " + std::to_string(k) + ": the run has frames 0 to " +
                           std::to_string(run_.trajectory().size() - 1));
  if (run_.imported())
    throw core::InputError("branch: " + run_.dir().string() +
                           " was imported from lab data; only a simulated run can be re-simulated");
  try {
    return std::make_unique<SiloBranch>(run_, k);
  } catch (const core::InputError&) {
    throw;
  } catch (const core::RuntimeFault& e) {
    // The run's own files disagree with its re-simulation: it cannot be branched (a different build).
    throw core::InputError("branch at frame " + std::to_string(k) + ": " + e.what());
  }
}

}  // namespace app
