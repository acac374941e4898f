#include "io/spill.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <utility>
#include <vector>

#include "core/error.h"

namespace io {

namespace {

std::size_t page_size() {
  static const std::size_t p = static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
  return p;
}

// A file in `dir` that has no name: O_TMPFILE where the file system has it, else a name removed at once.
int hidden_file(const std::string& dir) {
  int fd = open(dir.c_str(), O_TMPFILE | O_RDWR | O_CLOEXEC, 0600);
  if (fd >= 0) return fd;
  // mkostemp's template: six X's it replaces with a unique name.
  std::string name = (std::filesystem::path(dir) / (".siloscope-spill-" + std::string(6, 'X'))).string();
  fd = mkostemp(name.data(), O_CLOEXEC);
  if (fd >= 0) unlink(name.c_str());
  return fd;
}

}  // namespace

SpillFile::SpillFile(const std::string& dir) : dir_(dir) {}

// The file is made when the first byte is needed: an empty array costs nothing. Where `dir` takes none (a
// file system without files of its own, say), the system's temporary directory is tried.
void SpillFile::open_file() {
  std::error_code ec;
  std::string tmp = std::filesystem::temp_directory_path(ec).string();
  if (ec || tmp.empty()) tmp = "/tmp";
  if (dir_.empty()) dir_ = tmp;
  fd_ = hidden_file(dir_);
  if (fd_ < 0 && dir_ != tmp) {
    const int first = errno;
    fd_ = hidden_file(tmp);
    if (fd_ >= 0) dir_ = tmp;
    errno = first;
  }
  if (fd_ < 0)
    throw core::RuntimeFault("cannot make a temporary file in " + dir_ + " (" + std::strerror(errno) +
                             "): a long film's detections are kept there while it is imported");
}

SpillFile::~SpillFile() {
  if (data_) munmap(data_, capacity_);
  if (fd_ >= 0) close(fd_);
}

SpillFile::SpillFile(SpillFile&& o) noexcept
    : fd_(std::exchange(o.fd_, -1)),
      data_(std::exchange(o.data_, nullptr)),
      capacity_(std::exchange(o.capacity_, 0)),
      dir_(std::move(o.dir_)) {}

SpillFile& SpillFile::operator=(SpillFile&& o) noexcept {
  if (this != &o) {
    if (data_) munmap(data_, capacity_);
    if (fd_ >= 0) close(fd_);
    fd_ = std::exchange(o.fd_, -1);
    data_ = std::exchange(o.data_, nullptr);
    capacity_ = std::exchange(o.capacity_, 0);
    dir_ = std::move(o.dir_);
  }
  return *this;
}

void SpillFile::reserve(std::size_t bytes) {
  const std::size_t p = page_size();
  bytes = (bytes + p - 1) / p * p;
  if (bytes <= capacity_) return;
  if (fd_ < 0) open_file();
  // The disk's blocks are taken now (a full disk is an error here, not a signal when a page is written
  // later); a file system without fallocate grows the file sparse.
  int err = posix_fallocate(fd_, static_cast<off_t>(capacity_), static_cast<off_t>(bytes - capacity_));
  if (err == EOPNOTSUPP || err == EINVAL) err = ftruncate(fd_, static_cast<off_t>(bytes)) == 0 ? 0 : errno;
  if (err != 0)
    throw core::RuntimeFault(
        "cannot grow a temporary file in " + dir_ + " to " + std::to_string((bytes >> 20) + 1) + " MB (" +
        std::strerror(err) +
        "): a long film's detections are kept beside the output while it is imported; free "
        "some room there or write the output on another disk");
  void* m = data_ ? mremap(data_, capacity_, bytes, MREMAP_MAYMOVE)
                  : mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_SHARED, fd_, 0);
  if (m == MAP_FAILED)
    throw core::RuntimeFault("cannot map a temporary file of " + std::to_string(bytes) + " bytes in " + dir_ +
                             " (" + std::strerror(errno) + ")");
  data_ = static_cast<char*>(m);
  capacity_ = bytes;
}

void SpillFile::release() const {
  if (data_) madvise(data_, capacity_, MADV_DONTNEED);
}

double kth_smallest(const Spill<double>& v, std::size_t k) {
  std::uint64_t prefix = 0;
  for (int shift = 48; shift >= 0; shift -= 16) {
    const std::uint64_t above = shift == 48 ? 0 : ~std::uint64_t{0} << (shift + 16);  // the bits found
    std::vector<std::size_t> count(std::size_t{1} << 16, 0);
    for (std::size_t i = 0; i < v.size(); ++i) {
      std::uint64_t b;
      std::memcpy(&b, &v[i], sizeof b);
      if ((b & above) == prefix) ++count[(b >> shift) & 0xffff];
      v.release_after(i);
    }
    v.release();
    std::size_t digit = 0;
    while (k >= count[digit]) k -= count[digit++];
    prefix |= static_cast<std::uint64_t>(digit) << shift;
  }
  double out;
  std::memcpy(&out, &prefix, sizeof out);
  return out;
}

}  // namespace io
