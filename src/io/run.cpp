// A run directory opened once (io/run.h).
#include "io/run.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <sstream>

#include "core/error.h"
#include "core/scene.h"
#include "core/setup.h"
#include "io/csv_table.h"
#include "io/events_csv.h"
#include "io/manifest.h"

namespace io {

namespace fs = std::filesystem;

struct Run::State {
  std::string who;
  fs::path dir, trajectory_path;
  bool lone_trajectory = false;  // a trajectory file without its run directory
  bool has_manifest = false;
  Manifest manifest;
  std::string metadata;
  toml::table table;
  core::Model model;
  RunRecord record;
  bool imported = false;
  mutable std::unique_ptr<core::Events> events;
  mutable std::unique_ptr<std::vector<ClogArch>> clog_arches;
  mutable std::unique_ptr<Trajectory> trajectory;
  mutable std::unique_ptr<Contacts> contacts;
  mutable bool contacts_read = false;

  std::string where(const fs::path& p) const { return who + ": " + p.string(); }
};

bool is_run_directory(const fs::path& dir) {
  std::error_code ec;
  // Present (whatever they are: a reader names a file that is not a regular one).
  return fs::is_directory(dir, ec) && fs::exists(dir / run_file::kMetadata, ec) &&
         fs::exists(dir / run_file::kExits, ec);
}

namespace {
std::string read_text(const fs::path& p, const std::string& what) {
  core::check_text_file(p.string(), what, run_file::kMetadata);
  std::ifstream in(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// Where the run is: its directory, and its trajectory file when `path` names one outside a run directory.
void locate(const fs::path& path, Run& run, fs::path& dir, fs::path& trajectory, bool& lone) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) {
    dir = path;
    trajectory = dir / run_file::kTrajectory;
    return;
  }
  if (!fs::exists(path, ec)) throw core::InputError(path.string() + ": no such run, directory or file");
  dir = path.has_parent_path() ? path.parent_path() : fs::path(".");
  const std::string name = path.filename().string();
  if (name == run_file::kMetadata) {
    trajectory = dir / run_file::kTrajectory;
  } else if (path.extension() == ".sstraj") {
    trajectory = path;
    lone = name != run_file::kTrajectory || !fs::exists(dir / run_file::kMetadata, ec);
  } else {
    throw core::InputError(path.string() +
                           ": not a run (a run directory, its metadata.toml or a trajectory .sstraj file)");
  }
}

// A comparison's panel (NAME/panelK/) has no manifest of its own: the recording's lists its files as
// panelK/NAME. Those entries, relative to the panel.
void panel_manifest(const fs::path& dir, Manifest& out, bool& found) {
  const fs::path abs = fs::absolute(dir).lexically_normal();
  const fs::path parent = (abs.filename().empty() ? abs.parent_path() : abs).parent_path();
  const std::string prefix = (abs.filename().empty() ? abs.parent_path() : abs).filename().string() + "/";
  Manifest up;
  if (!read_manifest(parent, up)) return;
  for (const auto& e : up.files)
    if (e.name.rfind(prefix, 0) == 0) {
      ManifestEntry mine = e;
      mine.name = e.name.substr(prefix.size());
      out.files.push_back(mine);
    }
  found = !out.files.empty();
  out.kind = up.kind;
}

std::vector<std::string> split_ids(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string id; in >> id;) out.push_back(id);
  return out;
}
}  // namespace

Run::Run() : s_(std::make_unique<State>()) {}
Run::Run(Run&&) noexcept = default;
Run& Run::operator=(Run&&) noexcept = default;
Run::~Run() = default;

Run Run::open(const fs::path& path, const std::string& who, unsigned needs) {
  Run run;
  State& s = *run.s_;
  s.who = who;
  locate(path, run, s.dir, s.trajectory_path, s.lone_trajectory);
  std::error_code ec;
  if (s.lone_trajectory) {
    // A trajectory on its own carries its run's metadata; its own reader checks it (and the manifest of the
    // directory it sits in, if any).
    s.trajectory = std::make_unique<Trajectory>(s.trajectory_path);
    s.metadata = s.trajectory->info().metadata;
    if (!s.trajectory->model()) {
      (void)core::compile(core::parse_scene(s.metadata, s.trajectory_path.string() + " (its metadata)"));
      throw core::InputError(s.where(s.trajectory_path) + ": its metadata holds no valid scene");
    }
    s.model = *s.trajectory->model();
  } else {
    const fs::path meta = s.dir / run_file::kMetadata;
    if (!fs::exists(meta, ec))
      throw core::InputError(s.where(s.dir) +
                             " is not a run directory (no metadata.toml: run, record and import write one)");
    s.has_manifest = read_manifest(s.dir, s.manifest);
    if (!s.has_manifest) panel_manifest(s.dir, s.manifest, s.has_manifest);
    if (!s.has_manifest && declares_manifest(s.dir))
      throw core::InputError(who + ": " + (s.dir / "").string() + " has " + missing_manifest_why({}) +
                             ": make it again");
    // Every file the manifest lists as siloscope wrote it: present, its size (first, for all: a cut or padded
    // file is named before any is read), then its contents by hash. A reader needs only some of them, but a
    // run with any file damaged is not the run its metadata describes.
    if (s.has_manifest) {
      for (bool hashes : {false, true})
        for (const auto& e : s.manifest.files) {
          const std::string why = entry_mismatch(s.dir, e, hashes);
          if (!why.empty()) throw core::InputError(who + ": run " + s.dir.string() + ": " + why);
        }
    }
    s.metadata = read_text(meta, "run metadata");
    s.model = core::compile(core::parse_scene(s.metadata, meta.string()));
    s.record = run_record_of(s.metadata, meta.string());
  }
  try {
    s.table = toml::parse(s.metadata, s.dir.string());
    s.imported = s.table["run"]["imported"].value_or(false);
  } catch (const toml::parse_error&) {
  }
  if ((needs & kEvents) && !s.lone_trajectory)
    for (const char* f : {run_file::kExits, run_file::kClogs})
      if (!fs::exists(s.dir / f, ec))
        throw core::InputError(s.where(s.dir) + " has no " + f +
                               " (a run directory holds metadata.toml, exits.csv and clogs.csv)");
  if ((needs & kTrajectory) && !run.has_trajectory())
    throw core::InputError(
        s.where(s.dir) +
        ": no trajectory.sstraj (record writes one; run writes one with --trajectory-fps 30)");
  // A run of an earlier siloscope opens; what was translated or dropped from its scene is said once.
  for (const std::string& h : s.model.scene.history)
    std::fprintf(stderr, "siloscope %s: %s was made by an earlier siloscope: its scene key %s\n", who.c_str(),
                 path.string().c_str(), h.c_str());
  return run;
}

const fs::path& Run::dir() const {
  return s_->dir;
}

std::string Run::name() const {
  if (s_->lone_trajectory) return s_->trajectory_path.stem().string();
  const fs::path abs = fs::absolute(s_->dir).lexically_normal();
  const std::string n = abs.filename().string();
  return n.empty() ? abs.parent_path().filename().string() : n;
}

bool Run::has(const char* name) const {
  std::error_code ec;
  return fs::is_regular_file(s_->dir / name, ec);
}

const core::Model& Run::model() const {
  return s_->model;
}
const std::string& Run::metadata_text() const {
  return s_->metadata;
}
const toml::table& Run::metadata() const {
  return s_->table;
}
const RunRecord& Run::record() const {
  return s_->record;
}
bool Run::imported() const {
  return s_->imported;
}

bool Run::has_trajectory() const {
  std::error_code ec;
  return s_->trajectory || fs::is_regular_file(s_->trajectory_path, ec);
}

const Trajectory& Run::trajectory() const {
  State& s = *s_;
  if (!s.trajectory) {
    if (!has_trajectory())
      throw core::InputError(
          s.where(s.dir) +
          ": no trajectory.sstraj (record writes one; run writes one with --trajectory-fps 30)");
    // Checked against the manifest at open: read here in one piece, bounded as the trajectory reader bounds
    // a file it opens itself.
    const std::string p = s.trajectory_path.string();
    core::check_input_file(p, "trajectory", std::uintmax_t{4} << 30);
    std::ifstream in(s.trajectory_path, std::ios::binary);
    std::vector<unsigned char> bytes(std::filesystem::file_size(s.trajectory_path));
    if (!in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(bytes.size())))
      throw core::InputError(p + ": cannot read the trajectory");
    s.trajectory = std::make_unique<Trajectory>(bytes, p);
    // An imported run's grains are its tracks, not its geometry scene's count.
    if (!s.imported && s.trajectory->info().n_particles != static_cast<std::uint32_t>(s.model.setup.n_total))
      throw core::InputError(s.where(s.trajectory_path) + ": " +
                             std::to_string(s.trajectory->info().n_particles) +
                             " grains where the run's scene has " + std::to_string(s.model.setup.n_total) +
                             " (a trajectory of another run?)");
  }
  return *s.trajectory;
}

namespace {
// Contacts that belong to the trajectory name grains that touch in its frames: a file of another recording
// (the same scene, another seed) names pairs metres apart. Checked on a few frames spread over the file.
// Files written before frames dropped the contacts of grains re-injected after the step hold a few pairs
// apart (a grain at the top with one below the outlet): up to a tenth of the pairs checked may be apart.
void check_contacts_touch(const Contacts& c, const Trajectory& t, const std::string& name) {
  const long n = std::min(c.size(), t.size());
  if (n == 0) return;
  long pairs = 0, apart = 0;
  std::string first;
  for (long k : {0L, n / 2, n - 1}) {
    const core::Frame f = t.frame(k);
    for (const core::Contact& ct : c.frame(k)) {
      const auto& a = f.particles[static_cast<size_t>(ct.a)];
      const auto& b = f.particles[static_cast<size_t>(ct.b)];
      ++pairs;
      if (core::within_reach(a, b)) continue;
      if (apart++ == 0)
        first = "frame " + std::to_string(k) + " lists grains " + std::to_string(ct.a) + " and " +
                std::to_string(ct.b) + " in contact, but they are " +
                std::to_string(std::hypot(a.x - b.x, a.y - b.y)) + " m apart in the trajectory";
    }
  }
  if (apart > 0 && 10 * apart > pairs)
    throw core::InputError(name + ": " + first + " (" + std::to_string(apart) + " of " +
                           std::to_string(pairs) +
                           " pairs checked are apart): the contacts of another recording");
}
}  // namespace

const Contacts* Run::contacts() const {
  State& s = *s_;
  if (s.contacts_read) return s.contacts.get();
  s.contacts_read = true;
  // Beside the trajectory (a lone trajectory's too, as frame's re-simulation writes it).
  const fs::path p = s.trajectory_path.parent_path() / run_file::kContacts;
  std::error_code ec;
  if (!fs::exists(p, ec)) return nullptr;
  const Trajectory& t = trajectory();
  s.contacts = std::make_unique<Contacts>(p, t.info().n_particles, t.size() + 1);
  check_contacts_touch(*s.contacts, t, s.where(p));
  return s.contacts.get();
}

const core::Events& Run::events() const {
  State& s = *s_;
  if (s.events) return *s.events;
  std::error_code ec;
  if (s.lone_trajectory || !fs::exists(s.dir / run_file::kExits, ec)) {
    s.events = std::make_unique<core::Events>(trajectory().events());
    return *s.events;
  }
  s.events = std::make_unique<core::Events>(read_events(s.dir, s.model.setup.species_names()));
  return *s.events;
}

const std::vector<Run::ClogArch>& Run::clog_arches() const {
  State& s = *s_;
  if (s.clog_arches) return *s.clog_arches;
  s.clog_arches = std::make_unique<std::vector<ClogArch>>();
  const fs::path p = s.dir / run_file::kClogArches;
  std::error_code ec;
  if (s.lone_trajectory || !fs::exists(p, ec)) return *s.clog_arches;
  const size_t n_clogs = events().clogs.size();
  const CsvTable rows = CsvTable::read(p.string(), "an imported run's clog arches");
  for (size_t r = 0; r < rows.rows(); ++r) {
    ClogArch a;
    a.t = rows.num(r, "t_s");
    const double clog = rows.num(r, "clog");
    const std::string line = p.string() + ":" + std::to_string(r + 2);
    if (!(clog >= 1) || clog > static_cast<double>(n_clogs) || clog != std::floor(clog))
      throw core::InputError(line + ": clog " + rows.text(r, "clog") + " is not a row of clogs.csv");
    a.clog = static_cast<int>(clog);
    for (const std::string& id : split_ids(rows.text(r, "ids"))) {
      char* end = nullptr;
      const long v = std::strtol(id.c_str(), &end, 10);
      if (*end || v < 0 || v >= s.model.setup.n_total)
        throw core::InputError(line + ": grain " + id + " is not one of the run's " +
                               std::to_string(s.model.setup.n_total) + " grains");
      a.ids.push_back(static_cast<int>(v));
    }
    s.clog_arches->push_back(std::move(a));
  }
  return *s.clog_arches;
}

}  // namespace io
