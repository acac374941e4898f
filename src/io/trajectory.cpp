#include "io/trajectory.h"
#include "core/format.h"

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

size_t TrajectoryWriter::frame_bytes(std::uint32_t n) {
  return 8 * 4 + 4 * 2 + 4 * kTrajectoryMaxArch + 24 * size_t(n);
}

TrajectoryWriter::TrajectoryWriter(const std::filesystem::path& path, const TrajectoryInfo& info)
    : path_(path.string()), n_(info.n_particles) {
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
  put<std::uint32_t>(h, 24, static_cast<std::uint32_t>(frame_bytes(n_)));
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
  buf_.resize(frame_bytes(n_));
}

TrajectoryWriter::~TrajectoryWriter() {
  if (f_) std::fclose(f_);
}

void TrajectoryWriter::add(const core::Frame& f, int long_arches) {
  if (f.particles.size() != n_) throw core::RuntimeFault("trajectory: frame with a different particle count");
  std::fill(buf_.begin(), buf_.end(), 0);
  put<double>(buf_, 0, f.t);
  put<double>(buf_, 8, f.since_last_exit);
  put<std::int64_t>(buf_, 16, f.exits_original);
  put<std::int64_t>(buf_, 24, f.exits_added);
  put<std::int32_t>(buf_, 32, long_arches);
  const int count = static_cast<int>(std::min<size_t>(f.arch.size(), kTrajectoryMaxArch));
  put<std::int32_t>(buf_, 36, count);
  for (int k = 0; k < kTrajectoryMaxArch; ++k)
    put<std::int32_t>(buf_, 40 + 4 * k, k < count ? f.arch[k] : -1);
  const size_t base = 40 + 4 * kTrajectoryMaxArch, n = n_;
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
  // Whole frames reach the file as the run goes, so a cut-off run keeps what it recorded.
  if (++frames_ % 30 == 0) std::fflush(f_);
}

void TrajectoryWriter::close() {
  if (!f_) return;
  const bool ok = std::fflush(f_) == 0;
  const bool closed = std::fclose(f_) == 0;
  f_ = nullptr;
  if (!ok || !closed)
    throw core::RuntimeFault("cannot finish trajectory " + path_ + ": " + std::strerror(errno));
}

Trajectory::Trajectory(const std::filesystem::path& path) {
  const std::string p = path.string();
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw core::InputError(p + " is a directory; did you mean " + (path / "trajectory.sstraj").string() +
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
  if (version != kTrajectoryVersion)
    throw core::InputError(p + ": trajectory version " + std::to_string(version) +
                           "; this siloscope reads version " + std::to_string(kTrajectoryVersion));
  const auto header = get<std::uint32_t>(data.data(), 12);
  info_.n_particles = get<std::uint32_t>(data.data(), 16);
  const auto max_arch = get<std::uint32_t>(data.data(), 20);
  const auto fbytes = get<std::uint32_t>(data.data(), 24);
  const size_t after_arrays = pad8(kFixedHeader + 5 * size_t(info_.n_particles));
  if (max_arch != kTrajectoryMaxArch || fbytes != TrajectoryWriter::frame_bytes(info_.n_particles) ||
      header > data.size() || header < after_arrays + 4)
    throw core::InputError(p + ": corrupted trajectory header");
  info_.frame_interval = get<double>(data.data(), 32);
  info_.clog_timeout = get<double>(data.data(), 40);
  info_.clog_min_gap = get<double>(data.data(), 48);
  info_.radius_original = get<double>(data.data(), 56);
  // The inspector divides by these: they must be positive and finite.
  for (double v : {info_.frame_interval, info_.clog_timeout, info_.radius_original})
    if (!(v > 0 && v < 1e6))
      throw core::InputError(p + ": corrupted trajectory header (a time or length out of range)");
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
    core::validate(scene);
    setup_ = std::make_unique<core::Setup>(core::resolve(scene));
  } catch (const core::InputError&) {
    setup_.reset();
  }
  sides_.assign(n, 0);
  for (size_t i = 0; i < n; ++i) {
    const int sp = core::species_index(info_.species[i]);
    if (setup_ && static_cast<size_t>(sp) >= setup_->species.size())
      throw core::InputError(p + ": corrupted trajectory header (particle " + std::to_string(i) +
                             " has species " + std::to_string(sp) + "; the scene has " +
                             std::to_string(setup_->species.size()) + ")");
    if (setup_ && setup_->n_total == static_cast<int>(n))
      sides_[i] = static_cast<std::uint8_t>(setup_->species[static_cast<size_t>(sp)].sides);
  }
  const size_t body = data.size() - header;
  truncated_ = body % fbytes != 0;
  data_ = std::move(data);
  header_ = header;
  frame_bytes_ = fbytes;
  count_ = static_cast<long>(body / fbytes);
  for (long k = 0; k < count_; ++k) long_arches_.push_back(get<std::int32_t>(record(k), 32));
  for (size_t i = 0; i < n; ++i)
    if (!(info_.radius[i] > 0 && info_.radius[i] < 1e6))
      throw core::InputError(p + ": corrupted trajectory header (radius of particle " + std::to_string(i) +
                             ")");
  // Every number a frame holds must be finite: a corrupted frame is named, never drawn as an empty silo.
  static const char* kFields[] = {"x", "y", "angle", "vx", "vy", "force"};
  const size_t base = 40 + 4 * kTrajectoryMaxArch;
  // Finite but impossible values are refused as well: time must run forwards, exit counts never fall below
  // zero or go down, and a grain cannot be farther from the container than the container's own size (1 km
  // when the metadata holds no scene).
  double reach = 1e3;
  if (setup_)
    reach = 10.0 * std::max(setup_->geo.total_height, setup_->geo.x_right - setup_->geo.x_left) + 1.0;
  double last_t = -INFINITY;
  std::int64_t last_orig = 0, last_added = 0;
  for (long k = 0; k < count_; ++k) {
    const unsigned char* b = record(k);
    const std::string frame = p + ": frame " + std::to_string(k) + " is corrupted: ";
    const double t = get<double>(b, 0);
    if (std::isfinite(t) && !(t > last_t))
      throw core::InputError(frame + "its time " + core::format_shortest(t) +
                             " s does not come after the previous frame's " + core::format_shortest(last_t) +
                             " s");
    last_t = t;
    const auto orig = get<std::int64_t>(b, 16), added = get<std::int64_t>(b, 24);
    if (orig < last_orig || added < last_added)
      throw core::InputError(frame + "its exit counts (" + std::to_string(orig) + ", " +
                             std::to_string(added) + ") are negative or lower than the previous frame's (" +
                             std::to_string(last_orig) + ", " + std::to_string(last_added) + ")");
    last_orig = orig, last_added = added;
    if (get<double>(b, 8) < 0) throw core::InputError(frame + "its time since the last exit is negative");
    for (size_t a = 0; a < 2; ++a)
      for (size_t i = 0; i < n; ++i) {
        const float v = get<float>(b, base + 4 * (a * n + i));
        if (std::isfinite(v) && std::abs(v) > reach)
          throw core::InputError(frame + kFields[a] + " of particle " + std::to_string(i) + " is " +
                                 core::format_g(v, 7) + " m, far outside the container (allowed: within " +
                                 core::format_shortest(reach) + " m)");
      }
    for (size_t off : {size_t(0), size_t(8)})
      if (!std::isfinite(get<double>(b, off)))
        throw core::InputError(p + ": frame " + std::to_string(k) + " is corrupted: its " +
                               (off == 0 ? "time" : "time since the last exit") + " is not a finite number");
    for (size_t a = 0; a < 6; ++a)
      for (size_t i = 0; i < n; ++i)
        if (!std::isfinite(get<float>(b, base + 4 * (a * n + i))))
          throw core::InputError(p + ": frame " + std::to_string(k) + " is corrupted: " + kFields[a] +
                                 " of particle " + std::to_string(i) + " is not a finite number");
  }
}

double Trajectory::time(long k) const {
  return get<double>(record(k), 0);
}
double Trajectory::since_last_exit(long k) const {
  return get<double>(record(k), 8);
}

core::Frame Trajectory::frame(long k) const {
  if (k < 0 || k >= size())
    throw core::InputError("frame " + std::to_string(k) +
                           " is out of range; the trajectory has frames 0 to " + std::to_string(size() - 1));
  const unsigned char* b = record(k);
  core::Frame f;
  f.t = get<double>(b, 0);
  f.since_last_exit = get<double>(b, 8);
  f.exits_original = get<std::int64_t>(b, 16);
  f.exits_added = get<std::int64_t>(b, 24);
  const int count = get<std::int32_t>(b, 36);
  const size_t n = info_.n_particles;
  for (int j = 0; j < std::min(count, kTrajectoryMaxArch); ++j) {
    const int id = get<std::int32_t>(b, 40 + 4 * j);
    if (id >= 0 && static_cast<size_t>(id) < n) f.arch.push_back(id);
  }
  // Trajectories written before arches were checked (core::blocks_outlet) may hold one-grain "arches".
  if (f.arch.size() < 2) f.arch.clear();
  const size_t base = 40 + 4 * kTrajectoryMaxArch;
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
  if (setup_) {
    const core::Vec2 off = core::container_offset(*setup_, f.t);
    f.container_x = off.x;
    f.container_y = off.y;
  }
  return f;
}

}  // namespace io
