// Outputs that appear whole or not at all. Files are written under a temporary name in the destination's
// directory and renamed into place when complete; a directory is built as DIR.partial-PID and renamed.
// An object destroyed before commit() removes what it wrote.
#pragma once

#include <filesystem>
#include <string>

namespace io {

namespace fs = std::filesystem;

// Throws core::InputError if `path` exists and !force, or its parent directory is missing or unwritable.
void check_destination(const fs::path& path, bool force, const std::string& what);

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
  bool force_, committed_ = false;
};

// Write `text` to `path` atomically (temporary file, fsync if `sync`, rename). Throws core::RuntimeFault on
// failure (a full disk, no permission), leaving no temporary file behind.
void write_file_atomic(const fs::path& path, const std::string& text, bool sync = true);

// Rename `from` onto `to` (same filesystem), replacing `to`; throws core::RuntimeFault naming both.
void rename_into_place(const fs::path& from, const fs::path& to);

}  // namespace io
