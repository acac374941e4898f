// Sinks every command shares (app/session.h): a run's trajectory file and its contacts.
#pragma once

#include <filesystem>

#include "app/services/session.h"
#include "io/contacts.h"
#include "io/run.h"
#include "io/trajectory.h"
#include "sim/silo.h"

namespace app {

// Writes world `world`'s frames to a trajectory file (arches and forces included: the inspector shows both).
class TrajectorySink : public Sink {
 public:
  // Beside the trajectory, contacts.sscon keeps each frame's contacts with their forces (io/contacts.h).
  TrajectorySink(const std::filesystem::path& path, const io::TrajectoryInfo& info, size_t world = 0)
      : writer_(path, info),
        contacts_(path.parent_path() / io::run_file::kContacts, info.n_particles),
        world_(world) {}
  void frame(const FrameTick& t) override {
    const core::StepEvents& e = t.events[world_];
    removals_ += static_cast<int>(e.rule_removed.size());
    writer_.add(t.frames[world_], removals_, e);
    contacts_.add(t.frames[world_].contacts, t.frames[world_].wall_contacts);
  }
  // The clogs the run's end closed (censored) go into the trajectory's events too.
  void finished(const std::vector<core::StepEvents>& closed) override { writer_.add_events(closed[world_]); }
  bool wants_forces() const override { return true; }
  void close() {
    writer_.close();
    contacts_.close();
  }
  long frames() const { return writer_.frames(); }

 private:
  io::TrajectoryWriter writer_;
  io::ContactsWriter contacts_;
  size_t world_;
  int removals_ = 0;  // rule removals so far
};

}  // namespace app
