// Outputs that appear whole or not at all, and never over what a user made (io/output.h): ownership checks of
// every kind of output, the single-file records, locks, leftovers of dead writers, output directories.
// Over 400 lines because every command's outputs pass through these same few rules, kept together so that no
// writer decides them alone.
#include "io/output.h"
#include "core/format.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <csignal>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>

#include <toml++/toml.h>

#include "core/error.h"
#include "io/manifest.h"

namespace io {

namespace {
bool file_starts_with(const fs::path& p, const std::string& prefix) {
  std::ifstream in(p, std::ios::binary);
  std::string head(prefix.size(), '\0');
  return in.read(head.data(), static_cast<std::streamsize>(head.size())) && head == prefix;
}

bool file_contains(const fs::path& p, const std::string& needle, size_t within) {
  std::error_code ec;
  const auto size = fs::file_size(p, ec);
  if (ec) return false;
  within = std::min(within, static_cast<size_t>(size));
  std::ifstream in(p, std::ios::binary);
  std::string buf(within, '\0');
  in.read(buf.data(), static_cast<std::streamsize>(within));
  buf.resize(static_cast<size_t>(in.gcount()));
  return buf.find(needle) != std::string::npos;
}

// A directory siloscope wrote carries metadata.toml with a [siloscope] table (runs, recordings, analyses,
// figures) or a sweep's campaign.toml beside its scenes/.
bool siloscope_directory(const fs::path& d) {
  std::error_code ec;
  const fs::path meta = d / kMetadataFile;
  if (fs::is_regular_file(meta, ec) && file_contains(meta, "\n[siloscope]\n", 4096)) return true;
  return fs::is_regular_file(d / "campaign.toml", ec) && fs::is_directory(d / "scenes", ec);
}

bool pid_alive(long pid) {
  return pid > 0 && (::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM);
}
}  // namespace

std::string foreign_output(const fs::path& path, OutputKind kind, const std::string& csv_header) {
  std::error_code ec;
  const fs::file_status st = fs::symlink_status(path, ec);
  if (fs::is_symlink(st)) return "a symbolic link";
  switch (kind) {
    case OutputKind::Directory:
      if (fs::is_regular_file(st)) return "a regular file, not a siloscope output directory";
      if (!fs::is_directory(st)) return "not a regular file or directory";
      if (!siloscope_directory(path))
        return "a directory siloscope did not write (it holds no siloscope metadata.toml)";
      return "";
    case OutputKind::Movie:
      if (fs::is_directory(st)) return "a directory, not a siloscope MP4";
      if (!fs::is_regular_file(st)) return "not a regular file";
      // The MP4's comment tag holds the run's metadata; +faststart puts it near the start of the file.
      if (!file_contains(path, "siloscope run metadata", 8u << 20))
        return "a file that is not a siloscope MP4";
      return "";
    case OutputKind::Csv:
      if (fs::is_directory(st)) return "a directory, not a CSV file";
      if (!fs::is_regular_file(st)) return "not a regular file";
      if (!csv_header.empty() && !file_starts_with(path, csv_header + "\n"))
        return "a file that is not siloscope's CSV of this kind (its first line differs)";
      return "";
    case OutputKind::Sheet:
      if (fs::is_directory(st)) return "a directory, not a figure sheet";
      if (!fs::is_regular_file(st)) return "not a regular file";
      if (!file_contains(path, "siloscope gallery", 32u << 20) &&
          !file_contains(path, "siloscope timeline", 32u << 20))
        return "a file that is not a siloscope gallery sheet or timeline figure";
      return "";
    case OutputKind::Gsd:
      if (fs::is_directory(st)) return "a directory, not a GSD file";
      if (!fs::is_regular_file(st)) return "not a regular file";
      if (!file_starts_with(path, std::string("\xDF\x65\xDF\x65\xDF\x65\xDF\x65", 8)))
        return "a file that is not a GSD file (no GSD magic number)";
      return "";
    case OutputKind::Page:
      if (fs::is_directory(st)) return "a directory, not a shared run's page";
      if (!fs::is_regular_file(st)) return "not a regular file";
      if (!file_contains(path, "<!-- siloscope share ", 512))
        return "a file that is not a page siloscope share wrote";
      return "";
    case OutputKind::Xyz:
      if (fs::is_directory(st)) return "a directory, not an XYZ file";
      if (!fs::is_regular_file(st)) return "not a regular file";
      if (!file_contains(path, " siloscope=\"", 4096)) return "a file that is not a siloscope XYZ export";
      return "";
  }
  return "";
}

namespace {
// Missing parents are created, as `mkdir -p` would; a file in the way or no permission is an error.
void ensure_parent(const fs::path& path, const std::string& what) {
  std::error_code ec;
  fs::path parent = path.has_parent_path() ? path.parent_path() : fs::path(".");
  if (!fs::is_directory(parent, ec)) {
    fs::create_directories(parent, ec);
    if (ec || !fs::is_directory(parent))
      throw core::InputError(what + " " + path.string() + ": cannot create directory " + parent.string() +
                             ": " + (ec ? ec.message() : std::string("a file is in the way")));
  }
  if (::access(parent.c_str(), W_OK) != 0)
    throw core::InputError(what + " " + path.string() + ": directory " + parent.string() +
                           " is not writable");
}
}  // namespace

std::string foreign_directory(const fs::path& d, DirKind kind) {
  std::error_code ec;
  const fs::file_status st = fs::symlink_status(d, ec);
  if (fs::is_symlink(st)) return "a symbolic link";
  if (fs::is_regular_file(st)) return "a regular file, not a siloscope output directory";
  if (!fs::is_directory(st)) return "not a regular file or directory";
  if (fs::is_regular_file(d / "campaign.toml", ec))
    return "a campaign's results (it holds campaign.toml): no command replaces those";
  Manifest m;
  if (!read_manifest(d, m)) {
    if (siloscope_directory(d))
      return "a siloscope output without a manifest (written before manifests, or by hand), so what it holds "
             "cannot be proven to be only siloscope's: remove it yourself if you mean to";
    return "a directory siloscope did not write (it holds no manifest.toml)";
  }
  if (m.kind != dir_kind_name(kind))
    return std::string("siloscope's ") + m.kind + " output, not " + core::with_article(dir_kind_name(kind)) +
           " one (--force replaces only an output of the same kind)";
  // Files siloscope made there later (a frame or timeline of the run saved into it) are its own, with their
  // records: no user's addition, so --force replaces them with the rest.
  const std::string why = manifest_mismatch(d, m, true, [&](const std::string& name) {
    const fs::path p = d / name;
    const std::string file = p.filename().string();
    if (file.size() > 11 && file[0] == '.' && file.compare(file.size() - 10, 10, ".siloscope") == 0) {
      const fs::path of = p.parent_path() / file.substr(1, file.size() - 11);
      return fs::exists(of) && changed_since_written(of).empty();
    }
    return changed_since_written(p).empty();
  });
  if (!why.empty()) return "siloscope's " + m.kind + " output, but " + why;
  return "";
}

fs::path output_path(const std::string& path, const std::string& option) {
  if (path.empty()) throw core::InputError(option + " is empty: name the output to write");
  fs::path p(path);
  std::string last = p.filename().string();
  if (last.empty()) last = p.parent_path().filename().string();  // "runs/x/" names x
  if (last.empty() || last == "." || last == "..")
    throw core::InputError(option + " " + path +
                           " names a directory that already holds other things (., .., /); name a new one "
                           "inside it, e.g. " +
                           option + " " + (fs::path(path) / "out").string());
  std::error_code ec;
  // As the kernel resolves it: symbolic links in the existing part first, then "..", so "d/lnk/../x" with
  // d/lnk -> sub/deep is d/sub/x (a lexical "d/x" first would replace the wrong file).
  fs::path abs = fs::absolute(p, ec);
  if (!abs.has_filename()) abs = abs.parent_path();
  const fs::path parent = fs::weakly_canonical(abs.parent_path(), ec);
  return (ec ? abs.parent_path().lexically_normal() : parent) / abs.filename();
}

void check_not_input(const fs::path& out, const std::vector<fs::path>& inputs, const std::string& what) {
  std::error_code ec;
  const fs::path o = fs::weakly_canonical(out, ec);
  for (const auto& in : inputs) {
    const fs::path i = fs::weakly_canonical(in, ec);
    const auto rel = i.lexically_relative(o);
    if (!rel.empty() && *rel.begin() != "..")
      throw core::InputError(what + " " + out.string() + " is " + (rel == "." ? "" : "above ") +
                             "an input of this command (" + in.string() +
                             "); writing there would replace "
                             "what it reads, so choose another path");
  }
}

fs::path output_record_path(const fs::path& path) {
  return path.parent_path() / ("." + path.filename().string() + ".siloscope");
}

void record_output(const fs::path& path) {
  std::error_code ec;
  const auto size = fs::file_size(path, ec);
  if (ec) throw core::RuntimeFault("cannot read back " + path.string() + ": " + ec.message());
  write_file_atomic(output_record_path(path),
                    "# siloscope wrote " + path.filename().string() +
                        "; --force replaces it only while it still has this size and hash\nfile = \"" +
                        path.filename().string() + "\"\nsize = " + std::to_string(size) + "\nhash = \"" +
                        file_hash(path) + "\"\n",
                    false);
}

std::string changed_since_written(const fs::path& path) {
  const fs::path rec = output_record_path(path);
  std::error_code ec;
  const std::string none = "a file with no record that siloscope wrote it (" + rec.filename().string() +
                           ", kept beside every single-file output: missing, or the file predates it)";
  if (!fs::is_regular_file(fs::symlink_status(rec, ec)) || fs::file_size(rec, ec) > 4096) return none;
  toml::table t;
  try {
    t = toml::parse_file(rec.string());
  } catch (const toml::parse_error&) {
    return none;
  }
  const auto size = t["size"].value<std::int64_t>();
  const auto hash = t["hash"].value<std::string>();
  if (!size || !hash || t["file"].value_or(std::string()) != path.filename().string()) return none;
  const auto now = fs::file_size(path, ec);
  if (ec) return "unreadable (" + ec.message() + ")";
  if (static_cast<std::int64_t>(now) != *size)
    return "changed since siloscope wrote it (" + std::to_string(now) + " bytes where siloscope wrote " +
           std::to_string(*size) + ")";
  if (file_hash(path) != *hash) return "changed since siloscope wrote it (same size, other contents)";
  return "";
}

void check_destination(const fs::path& path, bool force, const std::string& what, OutputKind kind,
                       const std::string& csv_header, bool unchanged_only) {
  std::error_code ec;
  if (fs::exists(fs::symlink_status(path, ec))) {
    std::string why = foreign_output(path, kind, csv_header);
    if (why.empty() && kind != OutputKind::Directory && unchanged_only) why = changed_since_written(path);
    if (!force && !why.empty())
      throw core::InputError(what + " " + path.string() + " already exists: it is " + why +
                             "; choose another path");
    if (!force)
      throw core::InputError(what + " " + path.string() + " already exists; pass --force to replace it");
    if (!why.empty())
      throw core::InputError(
          what + " " + path.string() + " is " + why +
          "; --force replaces only what siloscope wrote and nobody changed since, so choose another path "
          "(or move it away yourself)");
  }
  ensure_parent(path, what);
}

OutputLock::OutputLock(const fs::path& final_path) {
  const fs::path parent = final_path.has_parent_path() ? final_path.parent_path() : fs::path(".");
  lock_path_ = parent / ("." + final_path.filename().string() + ".lock");
  // The lock file is removed when the lock is released, so no litter stays beside the outputs. A process that
  // opened the file just before its owner removed it would lock a file nobody else sees: after locking, check
  // that the path still names the file that was locked, and start again if not.
  for (int attempt = 0; attempt < 100; ++attempt) {
    fd_ = ::open(lock_path_.c_str(), O_CREAT | O_RDWR | O_CLOEXEC, 0644);
    if (fd_ < 0)
      throw core::InputError("output " + final_path.string() + ": cannot create the lock file " +
                             lock_path_.string() + ": " + std::strerror(errno));
    if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
      ::close(fd_);
      fd_ = -1;
      throw core::OutputBusy("another siloscope process is writing " + final_path.string() +
                             " right now; wait for it to finish or choose another --out");
    }
    struct stat held {
    }, named{};
    if (::fstat(fd_, &held) == 0 && ::stat(lock_path_.c_str(), &named) == 0 && held.st_ino == named.st_ino &&
        held.st_dev == named.st_dev)
      return;
    ::close(fd_);
    fd_ = -1;
  }
  throw core::OutputBusy("could not take the lock " + lock_path_.string() + " (it keeps being replaced)");
}

OutputLock::~OutputLock() {
  if (fd_ < 0) return;
  ::unlink(lock_path_.c_str());  // still holding the lock: nobody else can be between open and check
  ::close(fd_);
}

void remove_dead_leftovers(const fs::path& final_path, const std::vector<std::string>& extra) {
  const fs::path parent = final_path.has_parent_path() ? final_path.parent_path() : fs::path(".");
  const std::string name = final_path.filename().string();
  std::error_code ec;
  std::vector<fs::path> dead;
  for (const auto& e : fs::directory_iterator(parent, ec)) {
    const std::string f = e.path().filename().string();
    for (const std::string tag : {".partial-", ".old-"}) {
      const std::string prefix = name + tag;
      if (f.size() <= prefix.size() || f.compare(0, prefix.size(), prefix) != 0) continue;
      const std::string digits = f.substr(prefix.size());
      if (digits.find_first_not_of("0123456789") != std::string::npos || digits.size() > 9) continue;
      if (!pid_alive(std::stol(digits))) dead.push_back(e.path());
    }
    for (const auto& x : extra)
      if (f == x) dead.push_back(e.path());
  }
  for (const auto& p : dead) {
    const std::string f = p.filename().string();
    const bool moved_aside = f.compare(0, name.size() + 5, name + ".old-") == 0;
    if (moved_aside && !fs::exists(fs::symlink_status(final_path, ec))) {
      fs::rename(p, final_path, ec);  // its replacement never arrived: put it back
      std::fprintf(stderr, "siloscope: put %s back as %s: a siloscope process that died had moved it aside\n",
                   p.c_str(), final_path.c_str());
      continue;
    }
    fs::remove_all(p, ec);
    std::fprintf(stderr, "siloscope: removed %s, left by a siloscope process that died\n", p.c_str());
  }
}

namespace {
// The movie an output's metadata names ([run] movie = "NAME.mp4", beside the directory).
std::string movie_of(const fs::path& dir) {
  try {
    const toml::table t = toml::parse_file((dir / kMetadataFile).string());
    return t["run"]["movie"].value_or(std::string());
  } catch (const toml::parse_error&) {
    return "";
  }
}
}  // namespace

void remove_orphan_movie(const fs::path& old_dir, const fs::path& new_dir) {
  const std::string movie = movie_of(old_dir);
  if (movie.empty() || movie.find('/') != std::string::npos || movie == movie_of(new_dir)) return;
  const fs::path p = new_dir.parent_path() / movie;
  std::error_code ec;
  // Only a movie as siloscope wrote it (its record matches) goes: a user's re-encoding or edit stays.
  if (!fs::is_regular_file(fs::symlink_status(p, ec)) || !changed_since_written(p).empty()) return;
  fs::remove(p, ec);
  fs::remove(output_record_path(p), ec);
}

OutputDir::OutputDir(const std::string& final_path, bool force, DirKind kind)
    : final_(output_path(final_path)), kind_(kind), force_(force) {
  std::error_code ec;
  ensure_parent(final_, "output directory");
  lock_ = std::make_unique<OutputLock>(final_);
  remove_dead_leftovers(
      final_);  // first: an old output a dead process moved aside goes back before the checks
  if (fs::exists(fs::symlink_status(final_, ec))) {
    const std::string why = foreign_directory(final_, kind);
    // --force is suggested only where it would work.
    if (!force && !why.empty())
      throw core::InputError("output directory " + final_path + " already exists: it is " + why +
                             "; choose another path");
    if (!force)
      throw core::InputError("output directory " + final_path +
                             " already exists; pass --force to replace it");
    if (!why.empty())
      throw core::InputError("output directory " + final_path + " is " + why +
                             "; --force replaces only a siloscope output of the same kind that holds what "
                             "siloscope wrote, so choose another path");
  }
  tmp_ = final_;
  tmp_ += ".partial-" + std::to_string(::getpid());
  if (!fs::create_directory(tmp_, ec))
    throw core::InputError("output directory " + final_path + ": cannot create " + tmp_.string() + ": " +
                           ec.message());
}

OutputDir::~OutputDir() {
  if (committed_) return;
  std::error_code ec;
  fs::remove_all(tmp_, ec);
}

void OutputDir::commit() {
  declare_manifest(tmp_);
  write_manifest(tmp_, kind_);
  std::error_code ec;
  fs::path old;
  if (fs::exists(fs::symlink_status(final_, ec))) {
    if (!force_)
      throw core::RuntimeFault(final_.string() + " appeared while the run was going; not replacing it");
    const std::string why = foreign_directory(final_, kind_);
    if (!why.empty())
      throw core::RuntimeFault(final_.string() + " appeared or changed while the run was going and is " +
                               why + "; not replacing it");
    old = final_;
    old += ".old-" + std::to_string(::getpid());
    fs::rename(final_, old, ec);
    if (ec) throw core::RuntimeFault("cannot move " + final_.string() + " aside: " + ec.message());
  }
  fs::rename(tmp_, final_, ec);
  if (ec) {
    std::error_code back;
    if (!old.empty()) fs::rename(old, final_, back);  // the old output goes back under its own name
    throw core::RuntimeFault("cannot rename " + tmp_.string() + " to " + final_.string() + ": " +
                             ec.message() +
                             (old.empty() ? ""
                              : back      ? "; the old output is in " + old.string()
                                          : "; the old output is back in place"));
  }
  committed_ = true;
  if (!old.empty()) {
    remove_orphan_movie(old, final_);
    fs::remove_all(old, ec);
  }
}

void place_output(const fs::path& partial, const fs::path& final_path) {
  // The record first, of the finished contents under the final name: a record that cannot be written (a full
  // disk) leaves no output that --force could never replace.
  std::error_code ec;
  const auto size = fs::file_size(partial, ec);
  if (ec) throw core::RuntimeFault("cannot read back " + partial.string() + ": " + ec.message());
  write_file_atomic(output_record_path(final_path),
                    "# siloscope wrote " + final_path.filename().string() +
                        "; --force replaces it only while it still has this size and hash\nfile = \"" +
                        final_path.filename().string() + "\"\nsize = " + std::to_string(size) +
                        "\nhash = \"" + file_hash(partial) + "\"\n",
                    false);
  rename_into_place(partial, final_path);
}

void write_output(const fs::path& path, const std::string& text) {
  fs::path tmp = path;
  tmp += ".partial-" + std::to_string(::getpid());
  write_file_atomic(tmp, text, false);
  try {
    place_output(tmp, path);
  } catch (...) {
    std::error_code ec;
    fs::remove(tmp, ec);
    throw;
  }
}

void rename_into_place(const fs::path& from, const fs::path& to) {
  if (std::rename(from.c_str(), to.c_str()) != 0)
    throw core::RuntimeFault("cannot rename " + from.string() + " to " + to.string() + ": " +
                             std::strerror(errno));
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
