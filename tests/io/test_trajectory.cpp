// Trajectory files (io/trajectory.h): written, read back, cut off, corrupted, foreign.
#include <catch2/catch.hpp>

#include <cstring>
#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "fixtures.h"
#include "helpers.h"
#include "io/contacts.h"
#include "io/metadata.h"
#include "io/trajectory.h"

namespace fs = std::filesystem;
using Catch::Matchers::Contains;
using test::cli;
using test::kScene;

namespace {
const std::string kShort = " --duration 1 --set settle_time=2 --quiet";
fs::path temp_dir(const std::string& name) {
  return test::temp_dir("io_" + name);
}
}  // namespace

TEST_CASE(
    "trajectories round-trip, a cut-off file reads up to its last whole frame, foreign files are refused",
    "[io]") {
  fs::path d = temp_dir("traj");
  fs::path p = test::synthetic_trajectory(d);
  io::Trajectory t(p);
  REQUIRE(t.size() == 5);
  CHECK_FALSE(t.truncated());
  CHECK(t.frame(3).particles[0].x == Approx(0.1f));
  CHECK(t.frame(3).arch == std::vector<int>{0, 1});
  CHECK(t.frame(1).particles[1].species == core::Species::Added);
  CHECK(t.long_arches(4) == 1);
  // Cut it in the middle of frame 3.
  const auto size = fs::file_size(p);
  fs::resize_file(p, size - io::TrajectoryWriter::frame_bytes(2) - 100);
  io::Trajectory cut(p);
  CHECK(cut.size() == 3);
  CHECK(cut.truncated());
  std::ofstream(d / "foreign.sstraj") << "this is not a trajectory at all, just text";
  CHECK_THROWS_WITH(io::Trajectory(d / "foreign.sstraj"), Contains("not a siloscope trajectory"));
  CHECK_THROWS_WITH(io::Trajectory(d / "missing.sstraj"), Contains("cannot open"));
  // A header whose frame interval is zero would make playback divide by zero: refused.
  {
    std::vector<unsigned char> bytes;
    std::ifstream in(p, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    std::fill(bytes.begin() + 32, bytes.begin() + 40, 0);
    CHECK_THROWS_WITH(io::Trajectory(bytes, "zero.sstraj"), Contains("out of range"));
  }
  fs::resize_file(p, 40);
  CHECK_THROWS_AS(io::Trajectory(p), core::InputError);
}

TEST_CASE("a trajectory frame holding NaN or inf is reported with its frame number", "[trust][io]") {
  fs::path d = temp_dir("traj_nan");
  REQUIRE(cli("run " + kScene + kShort + " --trajectory-fps 10 --out " + (d / "r").string()).code == 0);
  const std::string path = (d / "r" / "trajectory.sstraj").string();
  std::ifstream in(path, std::ios::binary);
  std::vector<unsigned char> data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  io::Trajectory good(data, "good");
  REQUIRE(good.size() >= 5);
  // The y coordinate of particle 3 in frame 4 (frames follow the header; see docs/trajectory.md).
  const size_t n = good.info().n_particles,
               fb = io::TrajectoryWriter::frame_bytes(static_cast<std::uint32_t>(n));
  const size_t header = data.size() - fb * static_cast<size_t>(good.size());
  const size_t at = header + 4 * fb + 40 + 4 * io::kTrajectoryMaxArch + 4 * (n + 3);
  for (float bad : {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
    std::vector<unsigned char> broken = data;
    std::memcpy(&broken[at], &bad, 4);
    try {
      io::Trajectory t(broken, "broken.sstraj");
      FAIL("a non-finite coordinate was accepted");
    } catch (const std::exception& e) {
      CHECK_THAT(e.what(),
                 Catch::Matchers::Contains("frame 4") && Catch::Matchers::Contains("y of particle 3"));
    }
  }
}

TEST_CASE(
    "finite garbage in a frame is refused: time running backwards, falling exit counts, a disk at 1e30 m",
    "[trust][io]") {
  fs::path d = temp_dir("traj_garbage");
  REQUIRE(cli("run " + kScene + kShort + " --trajectory-fps 10 --out " + (d / "r").string()).code == 0);
  std::ifstream in((d / "r" / "trajectory.sstraj").string(), std::ios::binary);
  std::vector<unsigned char> data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  io::Trajectory good(data, "good");
  REQUIRE(good.size() >= 5);
  const size_t n = good.info().n_particles,
               fb = io::TrajectoryWriter::frame_bytes(static_cast<std::uint32_t>(n));
  const size_t frame4 = data.size() - fb * static_cast<size_t>(good.size()) + 4 * fb;
  auto refused = [&](size_t offset, const void* bytes, size_t size, const std::string& what) {
    std::vector<unsigned char> broken = data;
    std::memcpy(&broken[frame4 + offset], bytes, size);
    try {
      io::Trajectory t(broken, "broken.sstraj");
      FAIL("accepted: " + what);
    } catch (const core::InputError& e) {
      CHECK_THAT(e.what(), Catch::Matchers::Contains("frame 4") && Catch::Matchers::Contains(what));
    }
  };
  const double back = good.time(2);  // frame 4 at the time of frame 2
  refused(0, &back, 8, "does not come after");
  const std::int64_t negative = -3;
  refused(16, &negative, 8, "exit counts (-3");
  const float far = 1e30f;
  refused(40 + 4 * io::kTrajectoryMaxArch + 4 * 5, &far, 4, "x of particle 5 is 1e+30 m, far outside");
}

TEST_CASE("contacts files: each frame's contacts read back, a cut file read to its last whole frame",
          "[io]") {
  const auto d = test::temp_dir("contacts");
  const auto p = d / "contacts.sscon";
  {
    io::ContactsWriter w(p, 4);
    w.add({{0, 1, 2.5f}, {2, 3, 0.0f}});
    w.add({});
    w.add({{1, 3, 7.25f}});
    w.close();
  }
  io::Contacts c(p, 4);
  REQUIRE(c.size() == 3);
  const auto f0 = c.frame(0);
  REQUIRE(f0.size() == 2);
  CHECK(f0[0].a == 0);
  CHECK(f0[0].b == 1);
  CHECK(f0[0].force == 2.5f);
  CHECK(c.frame(1).empty());
  CHECK(c.frame(2)[0].force == 7.25f);
  CHECK(c.frame(3).empty());  // beyond the last frame: none
  // Cut inside the last frame: two frames remain.
  std::filesystem::resize_file(p, std::filesystem::file_size(p) - 5);
  CHECK(io::Contacts(p, 4).size() == 2);
  // Foreign, another grain count, an id out of range: named.
  CHECK_THROWS_WITH(io::Contacts(p, 5), Catch::Contains("holds 4 grains where the trajectory has 5"));
  std::ofstream(d / "x.sscon") << "SILOTRAJ and more bytes";
  CHECK_THROWS_WITH(io::Contacts(d / "x.sscon", 4), Catch::Contains("no SILOCONT header"));
  {
    io::ContactsWriter w(d / "bad.sscon", 4);
    w.add({{0, 9, 1.0f}});
    w.close();
  }
  CHECK_THROWS_WITH(io::Contacts(d / "bad.sscon", 4), Catch::Contains("names grain 9; ids run from 0 to 3"));
}
