// Outputs that appear whole or not at all. Files are written under a temporary name in the destination's
// directory and renamed into place when complete; a directory is built as DIR.partial-PID and renamed.
// An object destroyed before commit() removes what it wrote.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "io/manifest.h"

namespace io {

namespace fs = std::filesystem;

// What an output is, for deciding whether --force may replace an existing one.
enum class OutputKind {
  Directory,  // a run, recording, analysis or figures directory: holds siloscope's metadata.toml
  Movie,      // an MP4 whose comment tag holds siloscope's metadata
  Csv,        // a benchmark table or CSV export: its first line is the expected header
  Xyz,        // an extended XYZ export: its first comment line carries siloscope="VERSION"
  Sheet,      // a figure (PDF, SVG, PNG) whose metadata names "siloscope gallery" or "siloscope timeline"
  Gsd,        // a GSD export: a GSD file (its magic number) with siloscope's record beside it
  Page,  // a shared run (siloscope share): an HTML page or fragment that names "siloscope share" at its top
};

// Why --force may not replace `path`: empty when siloscope wrote it (as `kind`), otherwise what the path is
// ("a directory without siloscope's metadata.toml", "a regular file that is not a siloscope MP4", ...).
std::string foreign_output(const fs::path& path, OutputKind kind, const std::string& csv_header = "");

// Throws core::InputError if `path` exists and !force, or exists and is not siloscope's own output of `kind`
// (nothing a user made is ever replaced), or its parent directory cannot be created or written. A single
// file (every kind but Directory) is replaced only while it is what siloscope wrote: its record
// (record_output) must be there and match its size and hash, unless `unchanged_only` is false (a benchmark's
// table, which every run of the benchmark rewrites).
void check_destination(const fs::path& path, bool force, const std::string& what,
                       OutputKind kind = OutputKind::Directory, const std::string& csv_header = "",
                       bool unchanged_only = true);
// Single-file outputs (a movie, a figure, an export, claims.md) carry a record beside them,
// DIR/.NAME.siloscope: the size and hash of what siloscope wrote, so that --force can tell them from a file a
// user edited, re-encoded or appended notes to. Call once the file is complete under its final name. Throws
// core::RuntimeFault when the record cannot be written.
void record_output(const fs::path& path);
fs::path output_record_path(const fs::path& path);
// Why `path` is not (any longer) what siloscope wrote: empty when its record matches; otherwise "a file with
// no record that siloscope wrote it (...)" or "changed since siloscope wrote it (...)".
std::string changed_since_written(const fs::path& path);

// Why --force may not replace the directory `dir` with a new output of `kind`: empty when it is siloscope's
// own output of that kind holding exactly what its manifest lists. Otherwise what it is: a campaign's results
// (never replaced), another kind of output, a directory with files a user added or changed, one without a
// manifest, a symbolic link, a file.
std::string foreign_directory(const fs::path& dir, DirKind kind);

// An output path made absolute and normal (".." and trailing slashes resolved, the parent's symbolic links
// followed), after refusing what names no new entry: an empty path, ".", "..", "/". `option` names the flag
// in the error (e.g. "--out").
fs::path output_path(const std::string& path, const std::string& option = "--out");

// Refuses an output that is, or holds, one of the command's inputs (analyze RESULTS/runs --out RESULTS would
// replace the runs it reads): throws core::InputError naming both.
void check_not_input(const fs::path& out, const std::vector<fs::path>& inputs, const std::string& what);

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

// Clear what a dead siloscope process left next to `final_path` (NAME.partial-PID, NAME.old-PID whose PID is
// gone, and the `extra` names, e.g. NAME.mp4.partial), saying so on stderr. An old output moved aside whose
// replacement never arrived (NAME.old-PID with no NAME) is put back, not removed. Call while holding its
// OutputLock.
void remove_dead_leftovers(const fs::path& final_path, const std::vector<std::string>& extra = {});

class OutputDir {
 public:
  // `kind`: what the directory will be, written into its manifest at commit(); --force replaces only a
  // directory of the same kind that holds exactly what its manifest lists.
  OutputDir(const std::string& final_path, bool force, DirKind kind);
  ~OutputDir();
  OutputDir(const OutputDir&) = delete;
  OutputDir& operator=(const OutputDir&) = delete;
  // Path of `name` inside the directory being built.
  fs::path file(const std::string& name) const { return tmp_ / name; }
  const fs::path& final_path() const { return final_; }
  // Write the manifest and move the finished directory into place (replacing an old one if force; if the
  // last rename fails, the old one is put back under its own name).
  void commit();

 private:
  fs::path final_, tmp_;
  DirKind kind_;
  std::unique_ptr<OutputLock> lock_;
  bool force_, committed_ = false;
};

// Write `text` to `path` atomically (temporary file, fsync if `sync`, rename). Throws core::RuntimeFault on
// failure (a full disk, no permission), leaving no temporary file behind.
void write_file_atomic(const fs::path& path, const std::string& text, bool sync = true);

// A single-file output finished under a temporary name put in place: its record (record_output) written first
// from the finished contents, then the rename. Throws core::RuntimeFault (the caller removes `partial`).
void place_output(const fs::path& partial, const fs::path& final_path);
// `text` written as a single-file output at `path`, with its record, whole or not at all.
void write_output(const fs::path& path, const std::string& text);
// An output directory replaced by --force: the movie the old one named beside it (NAME.mp4, as siloscope
// wrote it) goes too when the new one does not name it, so no stale movie outlives its run.
void remove_orphan_movie(const fs::path& old_dir, const fs::path& new_dir);

// Rename `from` onto `to` (same filesystem), replacing `to`; throws core::RuntimeFault naming both.
void rename_into_place(const fs::path& from, const fs::path& to);

}  // namespace io
