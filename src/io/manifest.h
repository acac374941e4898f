// The manifest of an output directory: what siloscope wrote there (each file's name, size and hash) and which
// kind of output it is. It proves ownership (--force replaces a directory only when it is the same kind of
// output and holds exactly what its manifest lists: no file a user added or changed goes with it) and lets
// readers check what they read (a truncated or edited file is named, not believed).
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "core/scene.h"

namespace io {

// The kinds of output directory, by the command that writes them.
enum class DirKind { Run, Analysis, Figures, Export };
const char* dir_kind_name(DirKind k);  // "run", "analysis", "figures", "export"

struct ManifestEntry {
  std::string name;  // path relative to the directory, '/'-separated
  std::uint64_t size = 0;
  std::string hash;  // FNV-1a 64 of the contents, 16 hex digits
};

struct Manifest {
  std::string kind;  // dir_kind_name of the writer
  std::vector<ManifestEntry> files;
};

constexpr const char* kManifestName = "manifest.toml";
// Every output directory's record of what made it (a run's, an analysis', an export's).
constexpr const char* kMetadataFile = core::kMetadataFile;
// A manifest larger than this is not one siloscope wrote.
constexpr std::uintmax_t kMaxManifestBytes = 16u << 20;

// FNV-1a 64 of a file's contents as 16 hex digits (reads in blocks; a file of any size).
std::string file_hash(const std::filesystem::path& path);

// Lists every regular file under `dir` (recursively, the manifest itself left out) with its size and hash,
// and writes DIR/manifest.toml. Throws core::RuntimeFault if it cannot be written; a symbolic link or another
// non-regular entry inside `dir` is a fault too (siloscope writes none).
void write_manifest(const std::filesystem::path& dir, DirKind kind);

// Every output directory siloscope writes now has a manifest, and its metadata.toml says so in its
// [siloscope] table (`manifest = "manifest.toml"`), so a reader can tell an output whose manifest was removed
// from one written before manifests. Adds that line to DIR/metadata.toml (when it has a [siloscope] table),
// before the manifest is written; throws core::RuntimeFault if it cannot.
constexpr const char* kManifestDeclaration = "manifest = \"manifest.toml\"";
void declare_manifest(const std::filesystem::path& dir);
// Whether DIR/metadata.toml declares a manifest (see declare_manifest).
bool declares_manifest(const std::filesystem::path& dir);

// Reads DIR/manifest.toml. Returns false when there is none; throws core::InputError naming the file when it
// is malformed.
bool read_manifest(const std::filesystem::path& dir, Manifest& out);

// Why `dir` does not hold exactly what its manifest lists: empty when it does. `hashes`: compare contents too
// (sizes and names always). Names the first difference: "exits.csv is 120 bytes where its manifest says 4312
// (truncated?)", "notes.txt is not in its manifest (a file added after siloscope wrote it)".
// `siloscope_made`: a file not in the manifest that siloscope made later with another command (a figure of
// the run saved into it, with its record) is no user's addition when this says so.
std::string manifest_mismatch(const std::filesystem::path& dir, const Manifest& m, bool hashes = true,
                              const std::function<bool(const std::string&)>& siloscope_made = {});

// Why the file of entry `e` under `dir` is not as listed (missing, another size, another hash when `hashes`):
// empty when it is.
std::string entry_mismatch(const std::filesystem::path& dir, const ManifestEntry& e, bool hashes);
// Why a directory's manifest is missing, for messages: its metadata declares one. `dir` is named when not
// empty.
std::string missing_manifest_why(const std::filesystem::path& dir);

// For readers: if `dir` has a manifest, every file it lists (or only those of `only` that it lists) must be
// there with its size and hash; throws core::InputError naming `what`, the file and the difference. Files
// added beside them are allowed (a reader reads only what it knows). A directory without a manifest passes
// when it was written before manifests; when its metadata.toml declares one, the missing manifest is the
// error.
void verify_manifest(const std::filesystem::path& dir, const std::string& what,
                     const std::vector<std::string>& only = {});

// For readers of one file: the manifest of the output that holds `file` (in its directory or the one above,
// where a recording's panels keep theirs) is checked for that file's entry, if it has one; throws
// core::InputError naming `what`, the file and the difference, or the missing manifest that one of those
// directories' metadata.toml declares.
void verify_listed(const std::filesystem::path& file, const std::string& what);

}  // namespace io
