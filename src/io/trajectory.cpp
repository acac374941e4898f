// The trajectory file (io/trajectory.h): its writer and its reader, both versions. Over 400 lines because
// one binary format is written and read in one place, so that the two never disagree on a byte; the checks a
// reader makes of a file it did not write (bounds, order, finite values) are most of it.
#include "io/trajectory.h"
#include "core/format.h"
#include "io/run.h"

#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>

#include "core/error.h"
#include "core/scene.h"
#include "io/manifest.h"

namespace io {

namespace {
constexpr char kMagic[8] = {'S', 'I', 'L', 'O', 'T', 'R', 'A', 'J'};
constexpr char kEventsMagic[8] = {'S', 'I', 'L', 'O', 'E', 'V', 'T', 'S'};
constexpr char kEndMagic[8] = {'S', 'I', 'L', 'O', 'E', 'N', 'D', 0};
constexpr std::uint32_t kOpen = 1, kArrested = 2, kForming = 4;  // frame flags (kForming: version 3)
constexpr size_t kFixedHeader = 64;

size_t pad8(size_t n) {
  return (n + 7) & ~size_t(7);
}

template <class T>
void put(std::vector<unsigned char>& b, size_t at, const T& v) {
  std::memcpy(&b[at], &v, sizeof v);
}
template <class T>
T get(const unsigned char* b, size_t at) {
  T v;
  std::memcpy(&v, b + at, sizeof v);
  return v;
}
}  // namespace

FrameLayout frame_layout(std::uint32_t version, std::uint32_t n_species) {
  FrameLayout l;  // version 1's
  l.n_species = version >= 2 ? n_species : 2;
  if (version >= 2) {  // version 3's frames are version 2's (one more flag)
    l.clog_start = 16, l.rule_due_in = 24, l.long_arches = 32, l.clog_number = 36, l.clog_flags = 40;
    l.arch_count = 44, l.arch = 48, l.exits = l.arch + 4 * kTrajectoryMaxArch;
    l.particles = l.exits + 8 * size_t(l.n_species);
  }
  return l;
}

size_t TrajectoryWriter::frame_bytes(std::uint32_t n, std::uint32_t n_species, std::uint32_t version) {
  return frame_layout(version, n_species).bytes(n);
}

TrajectoryWriter::TrajectoryWriter(const std::filesystem::path& path, const TrajectoryInfo& info)
    : path_(path.string()), n_(info.n_particles), layout_(frame_layout(kTrajectoryVersion, info.n_species)) {
  f_ = std::fopen(path_.c_str(), "wb");
  if (!f_) throw core::RuntimeFault("cannot write trajectory " + path_ + ": " + std::strerror(errno));
  const size_t after_arrays = pad8(kFixedHeader + 4 * size_t(n_) + n_);
  const size_t header = pad8(after_arrays + 4 + info.metadata.size());
  std::vector<unsigned char> h(header, 0);
  std::memcpy(h.data(), kMagic, 8);
  put<std::uint32_t>(h, 8, kTrajectoryVersion);
  put<std::uint32_t>(h, 12, static_cast<std::uint32_t>(header));
  put<std::uint32_t>(h, 16, n_);
  put<std::uint32_t>(h, 20, kTrajectoryMaxArch);
  put<std::uint32_t>(h, 24, static_cast<std::uint32_t>(layout_.bytes(n_)));
  put<std::uint32_t>(h, 28, info.n_species);
  put<double>(h, 32, info.frame_interval);
  put<double>(h, 40, info.clog_timeout);
  put<double>(h, 48, info.clog_min_gap);
  put<double>(h, 56, info.radius_original);
  for (std::uint32_t i = 0; i < n_; ++i) {
    put<float>(h, kFixedHeader + 4 * i, info.radius[i]);
    h[kFixedHeader + 4 * size_t(n_) + i] = static_cast<unsigned char>(info.species[i]);
  }
  put<std::uint32_t>(h, after_arrays, static_cast<std::uint32_t>(info.metadata.size()));
  std::memcpy(&h[after_arrays + 4], info.metadata.data(), info.metadata.size());
  if (std::fwrite(h.data(), 1, h.size(), f_) != h.size())
    throw core::RuntimeFault("cannot write trajectory " + path_);
  bytes_ = h.size();
  buf_.resize(layout_.bytes(n_));
}

TrajectoryWriter::~TrajectoryWriter() {
  if (f_) std::fclose(f_);
}

void TrajectoryWriter::add_events(const core::StepEvents& e) {
  events_.exits.insert(events_.exits.end(), e.exits.begin(), e.exits.end());
  events_.clogs.insert(events_.clogs.end(), e.clogs_closed.begin(), e.clogs_closed.end());
  events_.arches.insert(events_.arches.end(), e.rule_removed.begin(), e.rule_removed.end());
}

void TrajectoryWriter::add(const core::Frame& f, int long_arches, const core::StepEvents& since_last) {
  if (f.particles.size() != n_) throw core::RuntimeFault("trajectory: frame with a different particle count");
  add_events(since_last);
  std::fill(buf_.begin(), buf_.end(), 0);
  const FrameLayout& l = layout_;
  put<double>(buf_, l.t, f.t);
  put<double>(buf_, l.since_last_exit, f.since_last_exit);
  put<double>(buf_, l.clog_start, f.clog_start);
  put<double>(buf_, l.rule_due_in, f.rule_due_in);
  put<std::int32_t>(buf_, l.long_arches, long_arches);
  put<std::int32_t>(buf_, l.clog_number, f.clog_number);
  put<std::uint32_t>(
      buf_, l.clog_flags,
      (f.clog_open ? kOpen : 0) | (f.clog_arrested ? kArrested : 0) | (f.arch_forming ? kForming : 0));
  const int count = static_cast<int>(std::min<size_t>(f.arch.size(), kTrajectoryMaxArch));
  put<std::int32_t>(buf_, l.arch_count, count);
  for (int k = 0; k < kTrajectoryMaxArch; ++k)
    put<std::int32_t>(buf_, l.arch + 4 * k, k < count ? f.arch[k] : -1);
  for (std::uint32_t sp = 0; sp < l.n_species; ++sp)
    put<std::int64_t>(buf_, l.exits + 8 * sp, f.exits_of(static_cast<int>(sp)));
  const size_t base = l.particles, n = n_;
  for (size_t i = 0; i < n; ++i) {
    const auto& p = f.particles[i];
    put<float>(buf_, base + 4 * i, p.x);
    put<float>(buf_, base + 4 * (n + i), p.y);
    put<float>(buf_, base + 4 * (2 * n + i), p.angle);
    put<float>(buf_, base + 4 * (3 * n + i), p.vx);
    put<float>(buf_, base + 4 * (4 * n + i), p.vy);
    put<float>(buf_, base + 4 * (5 * n + i), p.force);
  }
  if (std::fwrite(buf_.data(), 1, buf_.size(), f_) != buf_.size())
    throw core::RuntimeFault("cannot write trajectory " + path_ + ": " + std::strerror(errno));
  bytes_ += buf_.size();
  // Whole frames reach the file as the run goes, so a cut-off run keeps what it recorded.
  if (++frames_ % 30 == 0) std::fflush(f_);
}

namespace {
// A clog's record in the events block: 24 bytes up to version 2, 32 from version 3 (its arch's formation).
size_t clog_bytes(std::uint32_t version) {
  return version >= 3 ? 32 : 24;
}

std::vector<unsigned char> events_block(const core::Events& ev, std::uint64_t offset) {
  const size_t cb = clog_bytes(kTrajectoryVersion);
  std::vector<unsigned char> b(24 + 16 * ev.exits.size() + cb * ev.clogs.size());
  std::memcpy(b.data(), kEventsMagic, 8);
  put<std::uint32_t>(b, 8, static_cast<std::uint32_t>(ev.exits.size()));
  put<std::uint32_t>(b, 12, static_cast<std::uint32_t>(ev.clogs.size()));
  put<std::uint32_t>(b, 16, static_cast<std::uint32_t>(ev.arches.size()));
  size_t at = 24;
  for (const auto& e : ev.exits) {
    put<double>(b, at, e.t);
    put<std::int32_t>(b, at + 8, e.id);
    put<std::uint32_t>(b, at + 12, static_cast<std::uint32_t>(core::species_index(e.species)));
    at += 16;
  }
  for (const auto& c : ev.clogs) {
    put<double>(b, at, c.start);
    put<double>(b, at + 8, c.end);
    put<std::uint32_t>(b, at + 16, static_cast<std::uint32_t>(c.ended_by));
    put<std::uint32_t>(b, at + 20, c.arrested ? 1 : 0);
    put<double>(b, at + 24, c.formed);  // NaN: no arch blocked it
    at += cb;
  }
  for (const auto& a : ev.arches) {
    b.resize(at + 48 + 16 * a.ids.size());
    put<double>(b, at, a.t);
    put<double>(b, at + 8, a.clog_duration);
    put<double>(b, at + 16, a.geometry.span);
    put<double>(b, at + 24, a.geometry.height);
    put<double>(b, at + 32, a.geometry.max_angle_deg);
    put<std::uint32_t>(b, at + 40, static_cast<std::uint32_t>(a.ids.size()));
    put<std::uint32_t>(b, at + 44, static_cast<std::uint32_t>(a.method));
    at += 48;
    for (size_t k = 0; k < a.ids.size(); ++k) {
      put<std::int32_t>(b, at, a.ids[k]);
      put<std::uint32_t>(b, at + 4, static_cast<std::uint32_t>(core::species_index(a.species[k])));
      put<float>(b, at + 8, k < a.x.size() ? a.x[k] : 0.0f);
      put<float>(b, at + 12, k < a.y.size() ? a.y[k] : 0.0f);
      at += 16;
    }
  }
  b.resize(at + 16);
  put<std::uint64_t>(b, at, offset);
  std::memcpy(&b[at + 8], kEndMagic, 8);
  return b;
}
}  // namespace

void TrajectoryWriter::close() {
  if (!f_) return;
  const std::vector<unsigned char> block = events_block(events_, bytes_);
  const bool wrote = std::fwrite(block.data(), 1, block.size(), f_) == block.size();
  const bool ok = wrote && std::fflush(f_) == 0;
  const bool closed = std::fclose(f_) == 0;
  f_ = nullptr;
  if (!ok || !closed)
    throw core::RuntimeFault("cannot finish trajectory " + path_ + ": " + std::strerror(errno));
}

Trajectory::Trajectory(const std::filesystem::path& path) {
  const std::string p = path.string();
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw core::InputError(p + " is a directory; did you mean " + (path / run_file::kTrajectory).string() +
                           "?");
  if (std::filesystem::exists(path, ec) && !std::filesystem::is_regular_file(path, ec))
    throw core::InputError(p + ": a trajectory must be a regular file (this is a device, pipe or socket)");
  if (std::filesystem::exists(path, ec))
    core::check_input_file(p, "trajectory", std::uintmax_t{4} << 30);  // read whole: bounded
  verify_listed(path, "trajectory");
  std::ifstream in(p, std::ios::binary);
  if (!in) throw core::InputError(p + ": cannot open trajectory file");
  parse(std::vector<unsigned char>((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>()),
        p);
}

Trajectory::Trajectory(const std::vector<unsigned char>& data, const std::string& name) {
  parse(data, name);
}

void Trajectory::parse(std::vector<unsigned char> data, const std::string& p) {
  if (data.size() < kFixedHeader || std::memcmp(data.data(), kMagic, 8) != 0)
    throw core::InputError(p + ": not a siloscope trajectory (no SILOTRAJ header)");
  const auto version = get<std::uint32_t>(data.data(), 8);
  if (version < 1 || version > kTrajectoryVersion)
    throw core::InputError(p + ": trajectory version " + std::to_string(version) +
                           "; this siloscope reads versions 1 to " + std::to_string(kTrajectoryVersion));
  version_ = version;
  const auto header = get<std::uint32_t>(data.data(), 12);
  info_.n_particles = get<std::uint32_t>(data.data(), 16);
  const auto max_arch = get<std::uint32_t>(data.data(), 20);
  const auto fbytes = get<std::uint32_t>(data.data(), 24);
  const auto n_species = get<std::uint32_t>(data.data(), 28);
  const size_t after_arrays = pad8(kFixedHeader + 5 * size_t(info_.n_particles));
  if (version >= 2 && (n_species < 1 || n_species > 16))
    throw core::InputError(p + ": corrupted trajectory header (" + std::to_string(n_species) +
                           " species; allowed: 1 to 16)");
  layout_ = frame_layout(version, n_species);
  info_.n_species = layout_.n_species;
  if (max_arch != kTrajectoryMaxArch || fbytes != layout_.bytes(info_.n_particles) || header > data.size() ||
      header < after_arrays + 4)
    throw core::InputError(p + ": corrupted trajectory header");
  info_.frame_interval = get<double>(data.data(), 32);
  info_.clog_timeout = get<double>(data.data(), 40);
  info_.clog_min_gap = get<double>(data.data(), 48);
  info_.radius_original = get<double>(data.data(), 56);
  // The inspector divides by these: they must be positive and finite. clog_timeout 0 is the rule switched
  // off.
  for (double v : {info_.frame_interval, info_.radius_original})
    if (!(v > 0 && v < 1e6))
      throw core::InputError(p + ": corrupted trajectory header (a time or length out of range)");
  if (!(info_.clog_timeout >= 0 && info_.clog_timeout < 1e6))
    throw core::InputError(p + ": corrupted trajectory header (clog_timeout " +
                           core::format_shortest(info_.clog_timeout) + " s; allowed: 0 (rule off) to 1e6 s)");
  if (!(info_.clog_min_gap >= 0 && info_.clog_min_gap < 1e6))
    throw core::InputError(p + ": corrupted trajectory header (clog_min_gap)");
  const size_t n = info_.n_particles;
  for (size_t i = 0; i < n; ++i) {
    info_.radius.push_back(get<float>(data.data(), kFixedHeader + 4 * i));
    info_.species.push_back(static_cast<core::Species>(data[kFixedHeader + 4 * n + i]));
  }
  const auto meta = get<std::uint32_t>(data.data(), after_arrays);
  if (after_arrays + 4 + size_t(meta) > header)
    throw core::InputError(p + ": corrupted trajectory header (metadata)");
  info_.metadata.assign(reinterpret_cast<const char*>(&data[after_arrays + 4]), meta);
  // The scene in the metadata gives each grain's shape and a vibrating container's motion; a trajectory whose
  // metadata holds no valid scene (written by hand, or foreign) shows disks in a still container.
  try {
    core::Scene scene = core::parse_scene(info_.metadata, p + " (its metadata)");
    model_ = std::make_unique<core::Model>(core::compile(scene));
  } catch (const core::InputError&) {
    model_.reset();
  }
  const core::Setup* setup = model_ ? &model_->setup : nullptr;
  sides_.assign(n, 0);
  for (size_t i = 0; i < n; ++i) {
    const int sp = core::species_index(info_.species[i]);
    if (setup && static_cast<size_t>(sp) >= setup->species.size())
      throw core::InputError(p + ": corrupted trajectory header (particle " + std::to_string(i) +
                             " has species " + std::to_string(sp) + "; the scene has " +
                             std::to_string(setup->species.size()) + ")");
    if (setup && setup->n_total == static_cast<int>(n))
      sides_[i] = static_cast<std::uint8_t>(setup->species[static_cast<size_t>(sp)].sides);
  }
  for (size_t i = 0; i < n; ++i)
    if (!(info_.radius[i] > 0 && info_.radius[i] < 1e6))
      throw core::InputError(p + ": corrupted trajectory header (radius of particle " + std::to_string(i) +
                             ")");
  data_ = std::move(data);
  header_ = header;
  frame_bytes_ = fbytes;
  const size_t frames_end = read_events(p);
  const size_t body = frames_end - header;
  truncated_ = body % fbytes != 0;
  count_ = static_cast<long>(body / fbytes);
  for (long k = 0; k < count_; ++k) long_arches_.push_back(get<std::int32_t>(record(k), layout_.long_arches));
  check_frames(p);
  if (!events_complete_) rebuild_clogs();
}

size_t Trajectory::read_events(const std::string& p) {
  // Version 2 ends with the events block and a 16-byte footer pointing at it; a file without the footer was
  // cut off (its frames run to the end) or is version 1.
  const size_t size = data_.size();
  if (version_ < 2 || size < header_ + 16 || std::memcmp(&data_[size - 8], kEndMagic, 8) != 0) return size;
  const std::uint64_t offset = get<std::uint64_t>(data_.data(), size - 16);
  const std::string bad = p + ": corrupted events block (";
  if (offset < header_ || offset + 24 > size - 16 || (offset - header_) % frame_bytes_ != 0 ||
      std::memcmp(&data_[offset], kEventsMagic, 8) != 0)
    throw core::InputError(bad + "its offset " + std::to_string(offset) + " points at no events)");
  const unsigned char* b = data_.data();
  const size_t end = size - 16;
  const std::uint64_t n_exits = get<std::uint32_t>(b, offset + 8),
                      n_clogs = get<std::uint32_t>(b, offset + 12),
                      n_arches = get<std::uint32_t>(b, offset + 16);
  size_t at = offset + 24;
  // Sizes are checked before anything is read or allocated.
  const size_t cb = clog_bytes(version_);
  if (n_exits * 16 + n_clogs * cb + n_arches * 48 > end - at)
    throw core::InputError(bad + std::to_string(n_exits) + " exits, " + std::to_string(n_clogs) +
                           " clogs and " + std::to_string(n_arches) + " arches do not fit in its " +
                           std::to_string(end - at) + " bytes)");
  const size_t n = info_.n_particles;
  auto time_ok = [](double t) { return std::isfinite(t) && t >= 0 && t < 1e9; };
  auto species_ok = [&](std::uint32_t s) { return s < 16 && (!model_ || s < model_->setup.species.size()); };
  for (std::uint64_t k = 0; k < n_exits; ++k, at += 16) {
    core::ExitEvent e{get<double>(b, at), get<std::int32_t>(b, at + 8),
                      static_cast<core::Species>(get<std::uint32_t>(b, at + 12))};
    if (!time_ok(e.t) || e.id < 0 || static_cast<size_t>(e.id) >= n ||
        !species_ok(get<std::uint32_t>(b, at + 12)))
      throw core::InputError(bad + "exit " + std::to_string(k + 1) +
                             " has a time, id or species out of range)");
    events_.exits.push_back(e);
  }
  for (std::uint64_t k = 0; k < n_clogs; ++k, at += cb) {
    const auto how = get<std::uint32_t>(b, at + 16), arrested = get<std::uint32_t>(b, at + 20);
    core::ClogEvent c{
        get<double>(b, at), get<double>(b, at + 8), static_cast<core::ClogEnd>(how), arrested == 1, NAN, {}};
    if (version_ >= 3) c.formed = get<double>(b, at + 24);
    const bool formed_ok = std::isnan(c.formed) || (c.formed >= c.start - 1e-9 && c.formed <= c.end + 1e-9);
    if (!time_ok(c.start) || !time_ok(c.end) || c.end < c.start || how > 3 || arrested > 1 || !formed_ok)
      throw core::InputError(bad + "clog " + std::to_string(k + 1) + " has times or an ending out of range)");
    events_.clogs.push_back(c);
  }
  for (std::uint64_t k = 0; k < n_arches; ++k) {
    if (at + 48 > end) throw core::InputError(bad + "arch " + std::to_string(k + 1) + " is cut off)");
    core::ArchEvent a;
    a.t = get<double>(b, at);
    a.clog_duration = get<double>(b, at + 8);
    a.geometry = {get<double>(b, at + 16), get<double>(b, at + 24), get<double>(b, at + 32)};
    const std::uint64_t count = get<std::uint32_t>(b, at + 40);
    const auto method = get<std::uint32_t>(b, at + 44);
    at += 48;
    if (!time_ok(a.t) || !time_ok(a.clog_duration) || method > 1 || count > n || count * 16 > end - at)
      throw core::InputError(bad + "arch " + std::to_string(k + 1) + " has values out of range)");
    a.method = static_cast<core::ArchMethod>(method);
    for (std::uint64_t j = 0; j < count; ++j, at += 16) {
      const auto id = get<std::int32_t>(b, at);
      const auto sp = get<std::uint32_t>(b, at + 4);
      const float x = get<float>(b, at + 8), y = get<float>(b, at + 12);
      if (id < 0 || static_cast<size_t>(id) >= n || !species_ok(sp) || !std::isfinite(x) || !std::isfinite(y))
        throw core::InputError(bad + "member " + std::to_string(j + 1) + " of arch " + std::to_string(k + 1) +
                               " is out of range)");
      a.ids.push_back(id);
      a.species.push_back(static_cast<core::Species>(sp));
      a.x.push_back(x);
      a.y.push_back(y);
    }
    events_.arches.push_back(std::move(a));
  }
  if (at != end)
    throw core::InputError(bad + std::to_string(end - at) + " bytes left over after its events)");
  events_complete_ = true;
  return offset;
}

void Trajectory::check_frames(const std::string& p) const {
  const size_t n = info_.n_particles;
  // Every number a frame holds must be finite: a corrupted frame is named, never drawn as an empty silo.
  static const char* kFields[] = {"x", "y", "angle", "vx", "vy", "force"};
  const FrameLayout& l = layout_;
  const size_t base = l.particles;
  // Finite but impossible values are refused as well: time must run forwards, exit counts never fall below
  // zero or go down, and a grain cannot be farther from the container than the container's own size (1 km
  // when the metadata holds no scene).
  double reach = 1e3;
  if (model_) {
    const core::Geometry& g = model_->setup.geo;
    reach = 10.0 * std::max(g.total_height, g.x_right - g.x_left) + 1.0;
  }
  double last_t = -INFINITY;
  std::vector<std::int64_t> last_exits(l.n_species, 0);
  for (long k = 0; k < count_; ++k) {
    const unsigned char* b = record(k);
    const std::string frame = p + ": frame " + std::to_string(k) + " is corrupted: ";
    const double t = get<double>(b, l.t);
    if (std::isfinite(t) && !(t > last_t))
      throw core::InputError(frame + "its time " + core::format_shortest(t) +
                             " s does not come after the previous frame's " + core::format_shortest(last_t) +
                             " s");
    last_t = t;
    for (std::uint32_t sp = 0; sp < l.n_species; ++sp) {
      const auto e = get<std::int64_t>(b, l.exits + 8 * sp);
      if (e < last_exits[sp])
        throw core::InputError(frame + "its exit count of species " + std::to_string(sp) + " (" +
                               std::to_string(e) + ") is negative or lower than the previous frame's (" +
                               std::to_string(last_exits[sp]) + ")");
      last_exits[sp] = e;
    }
    if (get<double>(b, l.since_last_exit) < 0)
      throw core::InputError(frame + "its time since the last exit is negative");
    if (version_ >= 2) {
      const double start = get<double>(b, l.clog_start), due = get<double>(b, l.rule_due_in);
      if (!std::isfinite(start) || std::isnan(due) || get<std::int32_t>(b, l.clog_number) < 0 ||
          get<std::uint32_t>(b, l.clog_flags) > (version_ >= 3 ? 7u : 3u))
        throw core::InputError(frame + "its clog state (start, rule time, number or flags) is out of range");
    }
    for (size_t a = 0; a < 2; ++a)
      for (size_t i = 0; i < n; ++i) {
        const float v = get<float>(b, base + 4 * (a * n + i));
        if (std::isfinite(v) && std::abs(v) > reach)
          throw core::InputError(frame + kFields[a] + " of particle " + std::to_string(i) + " is " +
                                 core::format_g(v, 7) + " m, far outside the container (allowed: within " +
                                 core::format_shortest(reach) + " m)");
      }
    for (size_t off : {l.t, l.since_last_exit})
      if (!std::isfinite(get<double>(b, off)))
        throw core::InputError(p + ": frame " + std::to_string(k) + " is corrupted: its " +
                               (off == l.t ? "time" : "time since the last exit") +
                               " is not a finite number");
    for (size_t a = 0; a < 6; ++a)
      for (size_t i = 0; i < n; ++i)
        if (!std::isfinite(get<float>(b, base + 4 * (a * n + i))))
          throw core::InputError(p + ": frame " + std::to_string(k) + " is corrupted: " + kFields[a] +
                                 " of particle " + std::to_string(i) + " is not a finite number");
  }
}

void Trajectory::rebuild_clogs() {
  // Without the events block: a clog is a stretch of frames with a clog open (version 2: the frame's flag;
  // version 1: the timer at least clog_min_gap). Its start is the frame's clog start (or t - timer); its end
  // the last exit or rule firing before the next frame that shows none open (t - timer there).
  events_.clogs.clear();
  const bool driven = model_ && (model_->setup.drive.kick_impulse_max > 0 || model_->setup.drive.vibrating());
  bool open = false;
  core::ClogEvent c{};
  int number = 0;
  for (long k = 0; k < count_; ++k) {
    const core::Frame f = frame(k);
    if (open && (!f.clog_open || f.clog_number != number)) {
      c.end = f.t - f.since_last_exit;
      const bool removed = long_arches(k) > (k > 0 ? long_arches(k - 1) : 0);
      c.ended_by = removed                ? core::ClogEnd::Rule
                   : c.arrested && driven ? core::ClogEnd::Vibration
                                          : core::ClogEnd::Spontaneous;
      events_.clogs.push_back(c);
      open = false;
    }
    if (f.clog_open && !open) {
      open = true;
      number = f.clog_number;
      c = {f.clog_start, f.t, core::ClogEnd::RunEnd, f.clog_arrested, NAN, {}};
    }
    if (open) c.arrested = c.arrested || f.clog_arrested;
  }
  if (open) {
    c.end = time(count_ - 1);
    c.ended_by = core::ClogEnd::RunEnd;
    events_.clogs.push_back(c);
  }
}

double Trajectory::time(long k) const {
  return get<double>(record(k), layout_.t);
}
double Trajectory::since_last_exit(long k) const {
  return get<double>(record(k), layout_.since_last_exit);
}

core::Frame Trajectory::frame(long k) const {
  if (k < 0 || k >= size())
    throw core::InputError("frame " + std::to_string(k) +
                           " is out of range; the trajectory has frames 0 to " + std::to_string(size() - 1));
  const unsigned char* b = record(k);
  core::Frame f;
  const FrameLayout& l = layout_;
  f.t = get<double>(b, l.t);
  f.since_last_exit = get<double>(b, l.since_last_exit);
  for (std::uint32_t sp = 0; sp < l.n_species; ++sp)
    f.exits.push_back(get<std::int64_t>(b, l.exits + 8 * sp));
  if (version_ >= 2) {
    f.clog_start = get<double>(b, l.clog_start);
    f.rule_due_in = get<double>(b, l.rule_due_in);
    f.clog_number = get<std::int32_t>(b, l.clog_number);
    const auto flags = get<std::uint32_t>(b, l.clog_flags);
    f.clog_open = (flags & kOpen) != 0;
    f.clog_arrested = (flags & kArrested) != 0;
    f.arch_forming = (flags & kForming) != 0;
  } else {
    // Version 1 kept only the timer: a clog is open once it reaches clog_min_gap.
    f.clog_open = f.since_last_exit >= info_.clog_min_gap && f.t > 0;
    f.clog_start = f.t - f.since_last_exit;
    f.rule_due_in = info_.clog_timeout > 0 ? std::max(0.0, info_.clog_timeout - f.since_last_exit) : INFINITY;
  }
  const int count = get<std::int32_t>(b, l.arch_count);
  const size_t n = info_.n_particles;
  for (int j = 0; j < std::min(count, kTrajectoryMaxArch); ++j) {
    const int id = get<std::int32_t>(b, l.arch + 4 * j);
    if (id >= 0 && static_cast<size_t>(id) < n) f.arch.push_back(id);
  }
  // An arch is shown only while a clog is open (version 1 files stored one in flowing frames too), and never
  // a one-grain "arch" (written before arches were checked by core::blocks_outlet).
  if (f.arch.size() < 2 || !(f.clog_open || f.arch_forming)) f.arch.clear();
  const size_t base = l.particles;
  f.particles.resize(n);
  for (size_t i = 0; i < n; ++i) {
    core::Particle& q = f.particles[i];
    q.x = get<float>(b, base + 4 * i);
    q.y = get<float>(b, base + 4 * (n + i));
    q.angle = get<float>(b, base + 4 * (2 * n + i));
    q.vx = get<float>(b, base + 4 * (3 * n + i));
    q.vy = get<float>(b, base + 4 * (4 * n + i));
    q.force = get<float>(b, base + 4 * (5 * n + i));
    q.radius = info_.radius[i];
    q.species = info_.species[i];
    q.sides = sides_[i];
  }
  if (model_) {
    const core::Vec2 off = core::container_offset(model_->setup, f.t);
    f.container_x = off.x;
    f.container_y = off.y;
  }
  return f;
}

}  // namespace io
