#include "io/manifest.h"

#include <toml++/toml.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <functional>
#include <iterator>
#include <map>

#include "core/error.h"
#include "io/output.h"

namespace io {

namespace fs = std::filesystem;

const char* dir_kind_name(DirKind k) {
  switch (k) {
    case DirKind::Run:
      return "run";
    case DirKind::Analysis:
      return "analysis";
    case DirKind::Figures:
      return "figures";
    case DirKind::Export:
      return "export";
  }
  return "?";
}

namespace {
std::uint64_t fnv1a(std::uint64_t h, const char* data, size_t n) {
  for (size_t i = 0; i < n; ++i) {
    h ^= static_cast<unsigned char>(data[i]);
    h *= 0x100000001b3ULL;
  }
  return h;
}
std::string hex16(std::uint64_t h) {
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h));
  return hex;
}
constexpr std::uint64_t kFnvBasis = 0xcbf29ce484222325ULL;
// The manifest's own hash: its last line, `self = "HASH"`, the FNV-1a 64 of every byte before that line, so
// that an edited manifest is told apart from an edited file it lists.
constexpr const char* kSelfKey = "self = \"";
}  // namespace

std::string file_hash(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw core::InputError(path.string() + ": cannot be read");
  std::uint64_t h = kFnvBasis;
  std::vector<char> buf(1 << 16);
  while (in) {
    in.read(buf.data(), static_cast<std::streamsize>(buf.size()));
    h = fnv1a(h, buf.data(), static_cast<size_t>(in.gcount()));
  }
  return hex16(h);
}

namespace {
// Every entry under `dir` but the manifest: regular files by relative name; anything else is reported.
std::map<std::string, fs::path> listing(const fs::path& dir, std::string& odd) {
  std::map<std::string, fs::path> out;
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(dir, ec); !ec && it != fs::recursive_directory_iterator();
       it.increment(ec)) {
    const fs::path rel = it->path().lexically_relative(dir);
    const fs::file_status st = it->symlink_status(ec);
    if (fs::is_directory(st)) continue;
    if (rel == kManifestName) continue;
    if (!fs::is_regular_file(st)) {
      if (odd.empty())
        odd = rel.generic_string() + (fs::is_symlink(st) ? " is a symbolic link" : " is not a regular file");
      continue;
    }
    out[rel.generic_string()] = it->path();
  }
  return out;
}
}  // namespace

void write_manifest(const fs::path& dir, DirKind kind) {
  std::string odd;
  const auto files = listing(dir, odd);
  if (!odd.empty())
    throw core::RuntimeFault(dir.string() + ": " + odd + "; siloscope writes only regular files");
  std::string s =
      "# siloscope manifest: the files siloscope wrote here (name, bytes, FNV-1a 64). --force replaces\n"
      "# this directory only while it holds exactly these; readers check what they read against it.\n";
  s += std::string("kind = \"") + dir_kind_name(kind) + "\"\nfiles = [\n";
  for (const auto& [name, path] : files) {
    std::error_code ec;
    const auto size = fs::file_size(path, ec);
    if (ec) throw core::RuntimeFault(path.string() + ": " + ec.message());
    std::string quoted;
    for (char c : name) quoted += (c == '"' || c == '\\') ? std::string("\\") + c : std::string(1, c);
    s += "  [\"" + quoted + "\", " + std::to_string(size) + ", \"" + file_hash(path) + "\"],\n";
  }
  s += "]\n";
  s += std::string(kSelfKey) + hex16(fnv1a(kFnvBasis, s.data(), s.size())) + "\"\n";
  write_file_atomic(dir / kManifestName, s);
}

namespace {
constexpr const char* kSiloscopeTable = "\n[siloscope]\n";
// The head of DIR/metadata.toml, where its [siloscope] table is ("" when there is none).
std::string metadata_head(const fs::path& dir, size_t bytes) {
  std::error_code ec;
  if (!fs::is_regular_file(fs::symlink_status(dir / kMetadataFile, ec))) return "";
  std::ifstream in(dir / kMetadataFile, std::ios::binary);
  std::string buf(bytes, '\0');
  in.read(buf.data(), static_cast<std::streamsize>(bytes));
  buf.resize(static_cast<size_t>(in.gcount()));
  return buf;
}
}  // namespace

void declare_manifest(const fs::path& dir) {
  const fs::path meta = dir / kMetadataFile;
  std::error_code ec;
  if (!fs::is_regular_file(fs::symlink_status(meta, ec))) return;
  std::ifstream in(meta, std::ios::binary);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (!in.eof() && in.fail()) throw core::RuntimeFault(meta.string() + ": cannot be read back");
  const size_t at = text.find(kSiloscopeTable);
  const std::string declared = std::string(kSiloscopeTable) + kManifestDeclaration + "\n";
  if (at == std::string::npos || text.compare(at, declared.size(), declared) == 0) return;
  text.insert(at + std::char_traits<char>::length(kSiloscopeTable), std::string(kManifestDeclaration) + "\n");
  write_file_atomic(meta, text);
}

bool declares_manifest(const fs::path& dir) {
  return metadata_head(dir, 4096).find(std::string(kSiloscopeTable) + kManifestDeclaration + "\n") !=
         std::string::npos;
}

bool read_manifest(const fs::path& dir, Manifest& out) {
  const fs::path p = dir / kManifestName;
  std::error_code ec;
  const fs::file_status st = fs::symlink_status(p, ec);
  if (!fs::exists(st)) return false;
  if (!fs::is_regular_file(st))
    throw core::InputError(p.string() + ": not a regular file (a manifest is one)");
  if (fs::file_size(p, ec) > kMaxManifestBytes)
    throw core::InputError(p.string() + ": larger than any manifest siloscope writes");
  std::string text;
  {
    std::ifstream in(p, std::ios::binary);
    text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  toml::table t;
  try {
    t = toml::parse(text, p.string());
  } catch (const toml::parse_error& e) {
    throw core::InputError(p.string() + ": malformed TOML: " + std::string(e.description()));
  }
  // Manifests since the self line check themselves; older ones are taken as they are.
  if (const auto self = t["self"].value<std::string>()) {
    const size_t at = text.rfind(std::string("\n") + kSelfKey);
    if (at == std::string::npos || hex16(fnv1a(kFnvBasis, text.data(), at + 1)) != *self)
      throw core::InputError(p.string() +
                             ": the manifest itself was changed after siloscope wrote it (its own "
                             "hash differs), so the files it lists cannot be checked against it");
  }
  out = {};
  const auto kind = t["kind"].value<std::string>();
  const toml::array* files = t["files"].as_array();
  if (!kind || !files) throw core::InputError(p.string() + ": no kind or files (truncated?)");
  out.kind = *kind;
  for (const auto& node : *files) {
    const toml::array* row = node.as_array();
    const auto name = row && row->size() == 3 ? (*row)[0].value<std::string>() : std::nullopt;
    std::int64_t size = -1;
    if (row && row->size() == 3) size = (*row)[1].value<std::int64_t>().value_or(-1);
    const auto hash = row && row->size() == 3 ? (*row)[2].value<std::string>() : std::nullopt;
    if (!name || !hash || size < 0)
      throw core::InputError(p.string() + ": an entry of files is not [name, bytes, hash]");
    out.files.push_back({*name, static_cast<std::uint64_t>(size), *hash});
  }
  return true;
}

std::string entry_mismatch(const fs::path& dir, const ManifestEntry& e, bool hashes) {
  const fs::path p = dir / e.name;
  std::error_code ec;
  const fs::file_status st = fs::symlink_status(p, ec);
  if (!fs::exists(st)) return e.name + " is missing (its manifest lists it)";
  if (!fs::is_regular_file(st)) return e.name + " is no longer a regular file";
  const auto size = fs::file_size(p, ec);
  if (size != e.size)
    return e.name + " is " + std::to_string(size) + " bytes where its manifest says " +
           std::to_string(e.size) + (size < e.size ? " (truncated?)" : " (changed after siloscope wrote it)");
  if (hashes && file_hash(p) != e.hash)
    return e.name + " differs from what siloscope wrote (changed by hand?)";
  return "";
}

std::string manifest_mismatch(const fs::path& dir, const Manifest& m, bool hashes,
                              const std::function<bool(const std::string&)>& siloscope_made) {
  std::string odd;
  auto files = listing(dir, odd);
  if (!odd.empty()) return odd;
  for (const auto& e : m.files) {
    const std::string why = entry_mismatch(dir, e, hashes);
    if (!why.empty()) return why;
    files.erase(e.name);
  }
  for (const auto& [name, size] : files)
    if (!siloscope_made || !siloscope_made(name))
      return name + " is not in its manifest (a file added after siloscope wrote it)";
  return "";
}

// `dir`: named when the caller named a file inside it; empty when the caller named the directory itself.
std::string missing_manifest_why(const fs::path& dir) {
  return (dir.empty() ? std::string("no manifest.toml") : (dir / "").string() + " has no manifest.toml") +
         ", though its metadata.toml says siloscope wrote one (removed after?), so what the output holds "
         "cannot be checked";
}

void verify_manifest(const fs::path& dir, const std::string& what, const std::vector<std::string>& only) {
  Manifest m;
  if (!read_manifest(dir, m)) {
    if (declares_manifest(dir))
      throw core::InputError(what + " " + dir.string() + ": " + missing_manifest_why({}));
    return;
  }
  for (const auto& e : m.files) {
    if (!only.empty() && std::find(only.begin(), only.end(), e.name) == only.end()) continue;
    const std::string why = entry_mismatch(dir, e, true);
    if (!why.empty()) throw core::InputError(what + " " + dir.string() + ": " + why);
  }
}

void verify_listed(const fs::path& file, const std::string& what) {
  fs::path dir = file.parent_path();
  for (int up = 0; up < 2 && !dir.empty(); ++up, dir = dir.parent_path()) {
    Manifest m;
    if (!read_manifest(dir, m)) {
      if (declares_manifest(dir))
        throw core::InputError(what + " " + file.string() + ": " + missing_manifest_why(dir) +
                               ": make it again");
      continue;
    }
    const std::string rel = file.lexically_relative(dir).generic_string();
    for (const auto& e : m.files)
      if (e.name == rel) {
        const std::string why = entry_mismatch(dir, e, true);
        if (!why.empty()) throw core::InputError(what + " " + file.string() + ": " + why);
      }
    return;
  }
}

}  // namespace io
