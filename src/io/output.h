// Outputs that appear whole or not at all. Files are written under a temporary name in the destination's
// directory and renamed into place when complete; a directory is built as DIR.partial-PID and renamed.
// An object destroyed before commit() removes what it wrote.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace io {

namespace fs = std::filesystem;

// What an output is, for deciding whether --force may replace an existing one.
enum class OutputKind {
  Directory,  // a run, recording, analysis or figures directory: holds siloscope's metadata.toml
  Movie,      // an MP4 whose comment tag holds siloscope's metadata
  Csv,        // a benchmark table or CSV export: its first line is the expected header
  Xyz,        // an extended XYZ export: its first comment line carries siloscope="VERSION"
  Sheet,      // a figure sheet (PDF, SVG, PNG) whose metadata names "siloscope gallery"
};

// Why --force may not replace `path`: empty when siloscope wrote it (as `kind`), otherwise what the path is
// ("a directory without siloscope's metadata.toml", "a regular file that is not a siloscope MP4", ...).
std::string foreign_output(const fs::path& path, OutputKind kind, const std::string& csv_header = "");

// Throws core::InputError if `path` exists and !force, or exists and is not siloscope's own output of `kind`
// (nothing a user made is ever replaced), or its parent directory cannot be created or written.
void check_destination(const fs::path& path, bool force, const std::string& what,
                       OutputKind kind = OutputKind::Directory, const std::string& csv_header = "");

// One writer per output: an exclusive lock on PARENT/.NAME.lock, held for the object's life. A second process
// aiming at the same output gets core::OutputBusy at once, before any work. The lock goes with the process,
// so a killed writer never leaves it held.
class OutputLock {
 public:
  explicit OutputLock(const fs::path& final_path);
  ~OutputLock();
  OutputLock(const OutputLock&) = delete;
  OutputLock& operator=(const OutputLock&) = delete;

 private:
  fs::path lock_path_;
  int fd_ = -1;
};

// Remove what a dead siloscope process left next to `final_path` (NAME.partial-PID, NAME.old-PID whose PID is
// gone, and the `extra` names, e.g. NAME.mp4.partial), saying so on stderr. Call while holding its
// OutputLock.
void remove_dead_leftovers(const fs::path& final_path, const std::vector<std::string>& extra = {});

class OutputDir {
 public:
  OutputDir(fs::path final_path, bool force);
  ~OutputDir();
  OutputDir(const OutputDir&) = delete;
  OutputDir& operator=(const OutputDir&) = delete;
  // Path of `name` inside the directory being built.
  fs::path file(const std::string& name) const { return tmp_ / name; }
  const fs::path& final_path() const { return final_; }
  // Move the finished directory into place (replacing an old one if force).
  void commit();

 private:
  fs::path final_, tmp_;
  std::unique_ptr<OutputLock> lock_;
  bool force_, committed_ = false;
};

// Write `text` to `path` atomically (temporary file, fsync if `sync`, rename). Throws core::RuntimeFault on
// failure (a full disk, no permission), leaving no temporary file behind.
void write_file_atomic(const fs::path& path, const std::string& text, bool sync = true);

// Rename `from` onto `to` (same filesystem), replacing `to`; throws core::RuntimeFault naming both.
void rename_into_place(const fs::path& from, const fs::path& to);

}  // namespace io
