// Arrays too large to hold in memory for a long film (its detections, the grains' paths at every frame): kept
// in a file no one sees (O_TMPFILE, or a name removed as soon as it is made), mapped into memory. The pages
// read or written stay in the process only until release(): they are the file's, and return to it, so what a
// long film costs is disk, not memory. The file disappears with the object (or with the process, however it
// ends): nothing is left behind.
#pragma once

#include <cstddef>
#include <cstring>
#include <string>
#include <type_traits>

namespace io {

// An untyped growable mapping of a hidden file.
class SpillFile {
 public:
  // `dir`: where the file goes (the output's directory, on the disk the user chose); empty: the system's
  // temporary directory. The file is made when the first byte is reserved (reserve throws
  // core::RuntimeFault when it cannot be made or grown).
  explicit SpillFile(const std::string& dir = "");
  ~SpillFile();
  SpillFile(SpillFile&& o) noexcept;
  SpillFile& operator=(SpillFile&& o) noexcept;
  SpillFile(const SpillFile&) = delete;
  SpillFile& operator=(const SpillFile&) = delete;

  // Makes room for `bytes` (contents kept; new bytes are zero); the mapping may move.
  void reserve(std::size_t bytes);
  char* data() const { return data_; }
  // The pages touched so far leave the process (their contents stay in the file).
  void release() const;

 private:
  void open_file();
  int fd_ = -1;
  char* data_ = nullptr;
  std::size_t capacity_ = 0;  // bytes mapped
  std::string dir_;
};

// A vector of trivially copyable T in a SpillFile.
template <class T>
class Spill {
  static_assert(std::is_trivially_copyable_v<T>);

 public:
  explicit Spill(const std::string& dir = "") : file_(dir) {}

  std::size_t size() const { return n_; }
  bool empty() const { return n_ == 0; }
  T* data() const { return reinterpret_cast<T*>(file_.data()); }
  T* begin() const { return data(); }
  T* end() const { return data() + n_; }
  T& operator[](std::size_t i) const { return data()[i]; }

  void push_back(const T& v) {
    if (n_ == cap_) grow(n_ + 1);
    std::memcpy(static_cast<void*>(data() + n_), &v, sizeof(T));
    ++n_;
  }
  // New elements are zero bytes.
  void resize(std::size_t n) {
    if (n > cap_) grow(n);
    if (n < n_) std::memset(static_cast<void*>(data() + n), 0, (n_ - n) * sizeof(T));
    n_ = n;
  }
  void release() const { file_.release(); }
  // For a pass over the array: release() after every kPassBlock elements (call with each index read).
  static constexpr std::size_t kPassBlock = std::size_t{1} << 20;
  void release_after(std::size_t i) const {
    if (i % kPassBlock == kPassBlock - 1) release();
  }

 private:
  void grow(std::size_t n) {
    std::size_t c = cap_ ? cap_ : 1024;
    while (c < n) c *= 2;
    file_.reserve(c * sizeof(T));
    cap_ = c;
  }
  SpillFile file_;
  std::size_t n_ = 0, cap_ = 0;
};

// The k-th smallest (from 0) of values >= 0, exactly as a sort would give it, without holding them in memory:
// their bits order them as their values do, so four passes of a 16-bit histogram find it.
double kth_smallest(const Spill<double>& v, std::size_t k);

}  // namespace io
