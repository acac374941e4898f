#include "io/contacts.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>

#include "core/error.h"

namespace io {

namespace {
constexpr char kMagic[8] = {'S', 'I', 'L', 'O', 'C', 'O', 'N', 'T'};
constexpr std::uint32_t kVersion = 2;
size_t record_bytes(std::uint32_t version) {
  return version == 1 ? 12 : 32;
}
void put32(std::vector<unsigned char>& b, std::uint32_t v) {
  for (int k = 0; k < 4; ++k) b.push_back(static_cast<unsigned char>(v >> (8 * k)));
}
std::uint32_t get32(const unsigned char* p) {
  return p[0] | (p[1] << 8) | (p[2] << 16) | (static_cast<std::uint32_t>(p[3]) << 24);
}
float getf(const unsigned char* p) {
  const std::uint32_t bits = get32(p);
  float v;
  std::memcpy(&v, &bits, 4);
  return v;
}
}  // namespace

ContactsWriter::ContactsWriter(const std::filesystem::path& path, std::uint32_t n_particles)
    : path_(path.string()) {
  f_ = std::fopen(path_.c_str(), "wb");
  if (!f_) throw core::RuntimeFault("cannot write contacts " + path_ + ": " + std::strerror(errno));
  std::vector<unsigned char> head(kMagic, kMagic + 8);
  put32(head, kVersion);
  put32(head, n_particles);
  if (std::fwrite(head.data(), 1, head.size(), f_) != head.size())
    throw core::RuntimeFault("cannot write contacts " + path_ + ": " + std::strerror(errno));
}

ContactsWriter::~ContactsWriter() {
  if (f_) std::fclose(f_);
}

void ContactsWriter::add(const std::vector<core::Contact>& contacts,
                         const std::vector<core::Contact>& walls) {
  buf_.clear();
  put32(buf_, frames_++);
  put32(buf_, static_cast<std::uint32_t>(contacts.size() + walls.size()));
  auto putf = [this](float v) {
    std::uint32_t bits;
    std::memcpy(&bits, &v, 4);
    put32(buf_, bits);
  };
  for (const auto* list : {&contacts, &walls})
    for (const auto& c : *list) {
      put32(buf_, static_cast<std::uint32_t>(c.a));
      put32(buf_, static_cast<std::uint32_t>(c.b));
      for (float v : {c.force, c.ft, c.px, c.py, c.nx, c.ny}) putf(v);
    }
  if (std::fwrite(buf_.data(), 1, buf_.size(), f_) != buf_.size())
    throw core::RuntimeFault("cannot write contacts " + path_ + ": " + std::strerror(errno));
}

void ContactsWriter::close() {
  if (!f_) return;
  const bool ok = std::fflush(f_) == 0;
  const int err = errno;
  const bool closed = std::fclose(f_) == 0;
  f_ = nullptr;
  if (!ok || !closed)
    throw core::RuntimeFault("cannot finish contacts " + path_ + ": " + std::strerror(ok ? errno : err));
}

std::uint64_t Contacts::max_bytes(std::uint32_t n_particles, long max_frames) {
  const std::uint64_t per_frame =
      8 + record_bytes(kVersion) * static_cast<std::uint64_t>(max_per_frame(n_particles));
  return 16 + per_frame * static_cast<std::uint64_t>(std::max(0L, max_frames));
}

Contacts::Contacts(const std::filesystem::path& path, std::uint32_t n_particles, long max_frames) {
  const std::string name = path.string();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw core::InputError(name + ": not a contacts file (not a regular file)");
  // Bounded before anything is read: no file of a run of this size holds more.
  const std::uint64_t size = std::filesystem::file_size(path, ec);
  const std::uint64_t bound = max_bytes(n_particles, max_frames);
  if (ec || size > bound)
    throw core::InputError(name + ": " + std::to_string(size) + " bytes, more than the contacts of " +
                           std::to_string(max_frames) + " frames of " + std::to_string(n_particles) +
                           " grains can take (" + std::to_string(bound) +
                           " bytes): not the contacts of this run");
  std::ifstream in(path, std::ios::binary);
  data_.assign(std::istreambuf_iterator<char>(in), {});
  if (data_.size() < 16 || std::memcmp(data_.data(), kMagic, 8) != 0)
    throw core::InputError(name + ": not a siloscope contacts file (no SILOCONT header)");
  version_ = get32(&data_[8]);
  if (version_ != 1 && version_ != 2)
    throw core::InputError(name + ": contacts file version " + std::to_string(version_) +
                           "; this build reads versions 1 and 2");
  record_ = record_bytes(version_);
  if (get32(&data_[12]) != n_particles)
    throw core::InputError(name + ": holds " + std::to_string(get32(&data_[12])) +
                           " grains where the trajectory has " + std::to_string(n_particles));
  size_t at = 16;
  while (at + 8 <= data_.size()) {
    const std::uint32_t frame = get32(&data_[at]), count = get32(&data_[at + 4]);
    const std::string where = name + ": frame " + std::to_string(frame);
    if (frame != offsets_.size())
      throw core::InputError(where + " where frame " + std::to_string(offsets_.size()) + " was due");
    if (count > max_per_frame(n_particles))
      throw core::InputError(where + " lists " + std::to_string(count) + " contacts; " +
                             std::to_string(n_particles) + " grains in a plane have at most " +
                             std::to_string(max_per_frame(n_particles)));
    const size_t end = at + 8 + record_ * static_cast<size_t>(count);
    if (end > data_.size()) break;  // a partial last frame (a crash): dropped
    for (size_t k = at + 8; k < end; k += record_) {
      const auto a = static_cast<std::int32_t>(get32(&data_[k])),
                 b = static_cast<std::int32_t>(get32(&data_[k + 4]));
      const bool wall = version_ >= 2 && a < 0 && a >= -kMaxWalls;
      if ((a < 0 && !wall) || b < 0 || static_cast<std::uint32_t>(std::max(a, b)) >= n_particles)
        throw core::InputError(
            where + " names grain " + std::to_string(a < 0 && !wall ? a : std::max(a, b)) +
            "; ids run from 0 to " + std::to_string(n_particles - 1) +
            (version_ >= 2 ? " (a wall from -1 to -" + std::to_string(kMaxWalls) + " in a)" : ""));
      const float force = getf(&data_[k + 8]);
      if (!std::isfinite(force) || force < 0)
        throw core::InputError(where + " holds a non-finite or negative force");
      if (version_ >= 2) {
        for (size_t q = k + 12; q < k + 32; q += 4)
          if (!std::isfinite(getf(&data_[q]))) throw core::InputError(where + " holds a non-finite number");
        const double n2 = static_cast<double>(getf(&data_[k + 24])) * getf(&data_[k + 24]) +
                          static_cast<double>(getf(&data_[k + 28])) * getf(&data_[k + 28]);
        if (std::abs(n2 - 1) > 1e-3)
          throw core::InputError(where + " holds a contact normal of length " +
                                 std::to_string(std::sqrt(n2)) + "; a normal is a unit vector");
      }
    }
    offsets_.push_back(at + 4);
    at = end;
  }
}

std::vector<core::Contact> Contacts::frame(long k) const {
  return read(k, false);
}
std::vector<core::Contact> Contacts::walls(long k) const {
  return read(k, true);
}

std::vector<core::Contact> Contacts::read(long k, bool walls) const {
  std::vector<core::Contact> out;
  if (k < 0 || k >= size()) return out;
  const size_t at = offsets_[static_cast<size_t>(k)];
  const std::uint32_t count = get32(&data_[at]);
  for (size_t p = at + 4; p < at + 4 + record_ * static_cast<size_t>(count); p += record_) {
    core::Contact c{static_cast<std::int32_t>(get32(&data_[p])),
                    static_cast<std::int32_t>(get32(&data_[p + 4])), getf(&data_[p + 8])};
    if ((c.a < 0) != walls) continue;
    if (version_ >= 2) {
      c.ft = getf(&data_[p + 12]);
      c.px = getf(&data_[p + 16]), c.py = getf(&data_[p + 20]);
      c.nx = getf(&data_[p + 24]), c.ny = getf(&data_[p + 28]);
    }
    out.push_back(c);
  }
  return out;
}

}  // namespace io
