// Sinks every command shares (app/session.h): a run's trajectory file and its contacts.
#pragma once

#include <filesystem>

#include "app/services/session.h"
#include "io/contacts.h"
#include "io/trajectory.h"
#include "sim/hopper.h"

namespace app {

// Writes world `world`'s frames to a trajectory file (arches and forces included: the inspector shows both).
class TrajectorySink : public Sink {
 public:
  // Beside the trajectory, contacts.sscon keeps each frame's contacts with their forces (io/contacts.h).
  TrajectorySink(const std::filesystem::path& path, const io::TrajectoryInfo& info, size_t world = 0)
      : writer_(path, info),
        contacts_(path.parent_path() / "contacts.sscon", info.n_particles),
        world_(world) {}
  void frame(const FrameTick& t) override {
    writer_.add(t.frames[world_], static_cast<int>(t.worlds[world_]->events().arches.size()));
    contacts_.add(t.frames[world_].contacts);
  }
  bool wants_arch() const override { return true; }
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
};

}  // namespace app
