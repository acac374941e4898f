// io::Spill: an array kept in a hidden file, whose pages leave the process on release() and come back intact.
#include <catch2/catch.hpp>

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "helpers.h"
#include "io/spill.h"

namespace fs = std::filesystem;

namespace {

// This process's resident pages of mapped files, kB (/proc/self/status).
long rss_file_kb() {
  std::ifstream in("/proc/self/status");
  std::string key;
  long kb = -1;
  while (in >> key) {
    if (key == "RssFile:") {
      in >> kb;
      break;
    }
    in.ignore(1 << 12, '\n');
  }
  return kb;
}

}  // namespace

TEST_CASE("a spilled array keeps what was written through growth and release, and leaves no file", "[io]") {
  const fs::path dir = test::temp_dir("spill");
  {
    io::Spill<double> v(dir.string());
    CHECK(v.empty());
    for (int i = 0; i < 1000000; ++i) v.push_back(0.5 * i);  // grows (and moves) many times
    REQUIRE(v.size() == 1000000);
    v.release();
    double sum = 0;
    for (double x : v) sum += x;
    CHECK(sum == Approx(0.5 * 999999.0 * 1000000.0 / 2));
    CHECK(v[123456] == 0.5 * 123456);
    v.resize(10);
    v.resize(20);  // what a shrink dropped comes back as zero
    CHECK(v[9] == 4.5);
    CHECK(v[15] == 0);
    // Nothing in the directory: the file has no name.
    CHECK(fs::is_empty(dir));
  }
  CHECK(fs::is_empty(dir));
}

TEST_CASE("a spilled array's pages leave the process when released", "[io]") {
  io::Spill<char> v(test::temp_dir("spill_pages").string());
  const size_t bytes = size_t{64} << 20;
  v.resize(bytes);
  const long before = rss_file_kb();
  for (size_t i = 0; i < bytes; i += 4096) v[i] = static_cast<char>(i / 4096);
  const long touched = rss_file_kb();
  v.release();
  const long released = rss_file_kb();
  INFO("RssFile kB: before " << before << ", written " << touched << ", released " << released);
  CHECK(touched - before > 60 * 1024);               // the 64 MB written are resident ...
  CHECK(released - before < 4 * 1024);               // ... and gone after release
  CHECK(v[4096 * 1000] == static_cast<char>(1000));  // the contents stay
}

TEST_CASE("a spill whose directory takes no file goes to the system's temporary directory", "[io]") {
  io::Spill<int> v("/proc/no-such-directory");
  v.resize(100000);
  v[99999] = 7;
  v.release();
  CHECK(v[99999] == 7);
}

TEST_CASE("the k-th smallest of a spilled array is the sorted array's, ties and zeros included", "[io]") {
  io::Spill<double> v(test::temp_dir("spill_kth").string());
  std::vector<double> copy;
  unsigned state = 7;
  for (int i = 0; i < 50000; ++i) {
    state = state * 1664525u + 1013904223u;
    const double x = i % 7 == 0 ? 0.0 : i % 5 == 0 ? 0.25 : (state >> 8) * 1e-9;
    v.push_back(x);
    copy.push_back(x);
  }
  std::sort(copy.begin(), copy.end());
  for (size_t k : {size_t{0}, size_t{1}, size_t{7142}, size_t{7143}, size_t{25000}, size_t{49999}})
    CHECK(io::kth_smallest(v, k) == copy[k]);
}
