// A run directory as one object: what `run`, `record`, `import` and a sweep's realizations write, opened once
// and checked once. The C++ twin of the Python package's siloscope.Run. Every command that reads a run takes
// one of these; none opens a run's files by itself, so every reader gets the same checks:
//   - the manifest, when the run has one: every file it lists present with its size, each file's contents
//     checked against its hash when it is read; a manifest that the metadata declares but that is gone is an
//     error (io/manifest.h);
//   - metadata.toml at most 1 MiB, its scene compiled once (core::Model);
//   - the events from the run's own tables (exits.csv, clogs.csv, arches.csv), or from the trajectory when
//     the run is a trajectory file alone;
//   - trajectory.sstraj and contacts.sscon read only when asked for, with their sizes bounded by what their
//     headers and the trajectory allow before anything is read, and the contacts tied to the trajectory they
//     came with (the grains they name must touch in the trajectory's frames).
// Names of a run's files are here and nowhere else.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <toml++/toml.h>

#include "core/events.h"
#include "core/frame.h"
#include "core/model.h"
#include "io/contacts.h"
#include "io/manifest.h"
#include "io/metadata.h"
#include "io/trajectory.h"

namespace io {

// The files of a run directory.
namespace run_file {
constexpr const char* kMetadata = kMetadataFile;
constexpr const char* kTrajectory = "trajectory.sstraj";
constexpr const char* kContacts = "contacts.sscon";
constexpr const char* kExits = "exits.csv";
constexpr const char* kClogs = "clogs.csv";
constexpr const char* kArches = "arches.csv";
constexpr const char* kArchShapes = "arch_shapes.csv";
constexpr const char* kArchFormation = "arch_formation.csv";  // each clog's arch: formed, confirmed, arrival
constexpr const char* kClogArches = "clog_arches.csv";        // an imported run's clogs' arches
constexpr const char* kSummary = "summary.csv";
constexpr const char* kSurvival = "survival.csv";
constexpr const char* kSpecies = "species.csv";
}  // namespace run_file

// Whether `dir` looks like a run directory (metadata.toml and exits.csv): for finding runs under a
// directory. Says nothing of whether the run is sound; Run::open does.
bool is_run_directory(const std::filesystem::path& dir);

class Run {
 public:
  // What a reader needs of the run, checked at open: a run without them is refused naming what is missing
  // and how to make it.
  enum Needs : unsigned {
    kScene = 0,            // metadata.toml with a valid scene (every reader)
    kEvents = 1u << 0,     // exits.csv and clogs.csv (arches.csv when present)
    kTrajectory = 1u << 1  // trajectory.sstraj
  };
  // Opens `path`: a run or recording directory, a file inside one (its trajectory.sstraj or metadata.toml),
  // or a trajectory file on its own. `who` names the reader in every message ("gallery", "frame", ...).
  // Throws core::InputError naming the file and what is wrong.
  static Run open(const std::filesystem::path& path, const std::string& who, unsigned needs = kScene);

  Run(Run&&) noexcept;
  Run& operator=(Run&&) noexcept;
  ~Run();

  const std::filesystem::path& dir() const;  // the run's directory
  std::string name() const;                  // the directory's name (the trajectory's stem for a lone file)
  std::filesystem::path file(const char* name) const { return dir() / name; }
  bool has(const char* name) const;  // the run holds this file

  // The run's scene, compiled once from its metadata (for a trajectory alone: the metadata it carries).
  const core::Model& model() const;
  const std::string& metadata_text() const;
  const toml::table& metadata() const;  // parsed once
  const RunRecord& record() const;
  bool imported() const;  // made by `siloscope import` from a lab's tracks

  // The run's events: its tables when it has them, else its trajectory's (complete when the trajectory was
  // closed normally). Read at the first call.
  const core::Events& events() const;
  // An imported run's clogs' arches (clog_arches.csv): the clog (1-based), the time and the members. Empty
  // for a simulated run.
  struct ClogArch {
    int clog = 0;
    double t = 0;
    std::vector<int> ids;
  };
  const std::vector<ClogArch>& clog_arches() const;

  bool has_trajectory() const;
  // The trajectory, read at the first call; throws core::InputError saying how to make one when the run has
  // none.
  const Trajectory& trajectory() const;
  // The contacts recorded with the trajectory (force chains), read at the first call; null when the run
  // kept none.
  const Contacts* contacts() const;

 private:
  Run();
  struct State;
  std::unique_ptr<State> s_;
};

}  // namespace io
