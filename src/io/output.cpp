#include "io/output.h"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>

#include "core/error.h"

namespace io {

void check_destination(const fs::path& path, bool force, const std::string& what) {
  std::error_code ec;
  if (fs::exists(path, ec) && !force)
    throw core::InputError(what + " " + path.string() + " already exists; pass --force to replace it");
  fs::path parent = path.has_parent_path() ? path.parent_path() : fs::path(".");
  if (!fs::is_directory(parent, ec)) {
    // Missing parents are created, as `mkdir -p` would; a file in the way or no permission is an error.
    fs::create_directories(parent, ec);
    if (ec || !fs::is_directory(parent))
      throw core::InputError(what + " " + path.string() + ": cannot create directory " + parent.string() + ": " +
                             (ec ? ec.message() : std::string("a file is in the way")));
  }
  if (::access(parent.c_str(), W_OK) != 0)
    throw core::InputError(what + " " + path.string() + ": directory " + parent.string() + " is not writable");
}

OutputDir::OutputDir(fs::path final_path, bool force) : final_(std::move(final_path)), force_(force) {
  if (final_.has_filename() == false) final_ = final_.parent_path();  // tolerate a trailing slash
  check_destination(final_, force, "output directory");
  tmp_ = final_;
  tmp_ += ".partial-" + std::to_string(::getpid());
  std::error_code ec;
  fs::remove_all(tmp_, ec);
  if (!fs::create_directory(tmp_, ec))
    throw core::InputError("output directory " + final_.string() + ": cannot create " + tmp_.string() + ": " +
                           ec.message());
}

OutputDir::~OutputDir() {
  if (committed_) return;
  std::error_code ec;
  fs::remove_all(tmp_, ec);
}

void OutputDir::commit() {
  std::error_code ec;
  fs::path old;
  if (fs::exists(final_, ec)) {
    if (!force_) throw core::RuntimeFault(final_.string() + " appeared while the run was going; not replacing it");
    old = final_;
    old += ".old-" + std::to_string(::getpid());
    fs::rename(final_, old, ec);
    if (ec) throw core::RuntimeFault("cannot move " + final_.string() + " aside: " + ec.message());
  }
  fs::rename(tmp_, final_, ec);
  if (ec) throw core::RuntimeFault("cannot rename " + tmp_.string() + " to " + final_.string() + ": " + ec.message());
  committed_ = true;
  if (!old.empty()) fs::remove_all(old, ec);
}

void rename_into_place(const fs::path& from, const fs::path& to) {
  if (std::rename(from.c_str(), to.c_str()) != 0)
    throw core::RuntimeFault("cannot rename " + from.string() + " to " + to.string() + ": " + std::strerror(errno));
}

void write_file_atomic(const fs::path& path, const std::string& text, bool sync) {
  fs::path tmp = path;
  tmp += ".tmp-" + std::to_string(::getpid());
  FILE* f = std::fopen(tmp.c_str(), "wb");
  if (!f) throw core::RuntimeFault("cannot write " + tmp.string() + ": " + std::strerror(errno));
  bool ok = std::fwrite(text.data(), 1, text.size(), f) == text.size();
  ok = (std::fflush(f) == 0) && ok;
  if (sync) ok = (::fsync(fileno(f)) == 0) && ok;
  int err = errno;
  ok = (std::fclose(f) == 0) && ok;
  if (!ok) {
    std::remove(tmp.c_str());
    throw core::RuntimeFault("cannot write " + path.string() + ": " + std::strerror(err ? err : EIO));
  }
  try {
    rename_into_place(tmp, path);
  } catch (...) {
    std::remove(tmp.c_str());
    throw;
  }
}

}  // namespace io
