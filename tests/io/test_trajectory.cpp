// Trajectory files (io/trajectory.h): written, read back, cut off, corrupted, foreign.
#include <catch2/catch.hpp>

#include <cstring>
#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "core/forces.h"
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
// Where the frames start (the header's u32 at byte 12; docs/trajectory.md).
size_t header_bytes(const std::vector<unsigned char>& data) {
  std::uint32_t h = 0;
  std::memcpy(&h, &data[12], 4);
  return h;
}
std::vector<unsigned char> bytes_of(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
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
  // The events block: the clog and the rule's removal, as reported.
  REQUIRE(t.events_complete());
  REQUIRE(t.events().clogs.size() == 1);
  CHECK(t.events().clogs[0].ended_by == core::ClogEnd::Rule);
  REQUIRE(t.events().arches.size() == 1);
  CHECK(t.events().arches[0].ids == std::vector<int>{0, 1});
  CHECK(t.frame(3).clog_open);
  CHECK(t.frame(3).clog_number == 1);
  CHECK_FALSE(t.frame(4).clog_open);
  // Cut it in the middle of frame 3: the frames before it read, and the clog is rebuilt from them (still open
  // at the last whole frame: censored there).
  const size_t header = header_bytes(bytes_of(p)), fb = io::TrajectoryWriter::frame_bytes(2);
  fs::resize_file(p, header + 3 * fb + fb / 2);
  io::Trajectory cut(p);
  CHECK(cut.size() == 3);
  CHECK(cut.truncated());
  CHECK_FALSE(cut.events_complete());
  REQUIRE(cut.events().clogs.size() == 1);
  CHECK(cut.events().clogs[0].ended_by == core::ClogEnd::RunEnd);
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
  const size_t header = header_bytes(data);
  const size_t at = header + 4 * fb + (fb - 24 * n) + 4 * (n + 3);
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
  const size_t frame4 = header_bytes(data) + 4 * fb;
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
  refused(io::frame_layout(io::kTrajectoryVersion, 2).exits, &negative, 8, "species 0 (-3)");
  const float far = 1e30f;
  refused(fb - 24 * n + 4 * 5, &far, 4, "x of particle 5 is 1e+30 m, far outside");
}

namespace {
core::Contact contact(int a, int b, float fn, float ft = 0.5f, float nx = 0.6f, float ny = 0.8f) {
  core::Contact c{a, b, fn};
  c.ft = ft, c.px = 0.25f, c.py = -1.5f, c.nx = nx, c.ny = ny;
  return c;
}
}  // namespace

TEST_CASE("contacts files: each frame's contacts read back, a cut file read to its last whole frame",
          "[io]") {
  const auto d = test::temp_dir("contacts");
  const auto p = d / "contacts.sscon";
  {
    io::ContactsWriter w(p, 4);
    w.add({contact(0, 1, 2.5f, -0.75f), contact(2, 3, 0.0f)}, {contact(-3, 2, 4.0f, 1.0f, 0, -1)});
    w.add({}, {});
    w.add({contact(1, 3, 7.25f)}, {});
    w.close();
  }
  io::Contacts c(p, 4, 3);
  REQUIRE(c.size() == 3);
  CHECK(c.has_geometry());
  const auto f0 = c.frame(0);
  REQUIRE(f0.size() == 2);
  CHECK(f0[0].a == 0);
  CHECK(f0[0].b == 1);
  CHECK(f0[0].force == 2.5f);
  CHECK(f0[0].ft == -0.75f);
  CHECK(f0[0].px == 0.25f);
  CHECK(f0[0].py == -1.5f);
  CHECK(f0[0].nx == 0.6f);
  CHECK(f0[0].ny == 0.8f);
  // Contacts with walls apart: the wall's code, the grain, the force, the normal from the wall.
  const auto w0 = c.walls(0);
  REQUIRE(w0.size() == 1);
  CHECK(w0[0].a == -3);
  CHECK(w0[0].b == 2);
  CHECK(w0[0].force == 4.0f);
  CHECK(w0[0].ny == -1.0f);
  CHECK(c.walls(2).empty());
  CHECK(c.frame(1).empty());
  CHECK(c.frame(2)[0].force == 7.25f);
  CHECK(c.frame(3).empty());  // beyond the last frame: none
  // Cut inside the last frame: two frames remain.
  std::filesystem::resize_file(p, std::filesystem::file_size(p) - 5);
  CHECK(io::Contacts(p, 4, 3).size() == 2);
  // Foreign, another grain count, an id out of range: named.
  CHECK_THROWS_WITH(io::Contacts(p, 5, 3), Catch::Contains("holds 4 grains where the trajectory has 5"));
  std::ofstream(d / "x.sscon") << "SILOTRAJ and more bytes";
  CHECK_THROWS_WITH(io::Contacts(d / "x.sscon", 4, 3), Catch::Contains("no SILOCONT header"));
  {
    io::ContactsWriter w(d / "bad.sscon", 4);
    w.add({contact(0, 9, 1.0f)}, {});
    w.close();
  }
  CHECK_THROWS_WITH(io::Contacts(d / "bad.sscon", 4, 3),
                    Catch::Contains("names grain 9; ids run from 0 to 3"));
  {
    io::ContactsWriter w(d / "normal.sscon", 4);
    w.add({contact(0, 1, 1.0f, 0.0f, 0.5f, 0.5f)}, {});
    w.close();
  }
  CHECK_THROWS_WITH(io::Contacts(d / "normal.sscon", 4, 3),
                    Catch::Contains("contact normal of length 0.7") && Catch::Contains("a unit vector"));
  {
    io::ContactsWriter w(d / "nan.sscon", 4);
    w.add({contact(0, 1, 1.0f, std::nanf(""))}, {});
    w.close();
  }
  CHECK_THROWS_WITH(io::Contacts(d / "nan.sscon", 4, 3),
                    Catch::Contains("frame 0 holds a non-finite number"));
  // Bounded before it is read: more bytes than the frames of a run of this size can take (a valid header
  // padded to gigabytes: sparse, so no disk is used), or more contacts in a frame than grains in a plane
  // have.
  std::filesystem::resize_file(p, std::uintmax_t(20) << 30);
  CHECK_THROWS_WITH(io::Contacts(p, 4, 3), Catch::Contains("more than the contacts of 3 frames of 4 grains"));
  {
    io::ContactsWriter w(d / "many.sscon", 4);
    w.add(std::vector<core::Contact>(300, contact(0, 1, 1.0f)), {});
    w.close();
  }
  CHECK_THROWS_WITH(io::Contacts(d / "many.sscon", 4, 3),
                    Catch::Contains("grains in a plane have at most 268"));
}

TEST_CASE("contacts files of version 1 (normal forces of grain pairs only) still read", "[io]") {
  const auto d = test::temp_dir("contacts_v1");
  const auto p = d / "contacts.sscon";
  {
    std::ofstream out(p, std::ios::binary);
    auto u32 = [&](std::uint32_t v) { out.write(reinterpret_cast<const char*>(&v), 4); };
    auto f32 = [&](float v) { out.write(reinterpret_cast<const char*>(&v), 4); };
    out.write("SILOCONT", 8);
    u32(1), u32(4);
    u32(0), u32(2), u32(0), u32(1), f32(2.5f), u32(2), u32(3), f32(1.0f);
    u32(1), u32(0);
  }
  io::Contacts c(p, 4, 3);
  REQUIRE(c.size() == 2);
  CHECK_FALSE(c.has_geometry());
  const auto f0 = c.frame(0);
  REQUIRE(f0.size() == 2);
  CHECK(f0[1].a == 2);
  CHECK(f0[1].b == 3);
  CHECK(f0[1].force == 1.0f);
  CHECK(f0[1].ft == 0.0f);
  CHECK_FALSE(f0[1].has_geometry());
  CHECK(c.walls(0).empty());
  // No geometry, no stress: a frame with these contacts gives no pressures.
  core::Frame f;
  f.particles.resize(4);
  f.contacts = f0;
  CHECK(core::pressures(f).empty());
}

TEST_CASE("a version-1 trajectory still opens: its clogs rebuilt from the timers, no arch in a flowing frame",
          "[io]") {
  // The synthetic file rewritten as version 1: frames of t, timer, two exit counts, rule firings and the arch
  // (no clog state), no events block.
  const fs::path d = temp_dir("traj_v1");
  const std::vector<unsigned char> v2 = bytes_of(test::synthetic_trajectory(d));
  const size_t header = header_bytes(v2);
  const io::FrameLayout l2 = io::frame_layout(2, 2), l1 = io::frame_layout(1, 2);
  const size_t fb2 = l2.bytes(2), fb1 = l1.bytes(2);
  std::vector<unsigned char> v1(v2.begin(), v2.begin() + static_cast<long>(header));
  const std::uint32_t one = 1, fb1_u32 = static_cast<std::uint32_t>(fb1);
  std::memcpy(&v1[8], &one, 4);
  std::memcpy(&v1[24], &fb1_u32, 4);
  for (size_t k = 0; k < 5; ++k) {
    const auto* f = &v2[header + k * fb2];
    std::vector<unsigned char> r(fb1, 0);
    auto copy = [&](size_t to, size_t from, size_t n) { std::memcpy(&r[to], f + from, n); };
    copy(l1.t, l2.t, 8);
    copy(l1.since_last_exit, l2.since_last_exit, 8);
    copy(l1.exits, l2.exits, 16);
    copy(l1.long_arches, l2.long_arches, 4);
    copy(l1.arch_count, l2.arch_count, 4);
    copy(l1.arch, l2.arch, 4 * io::kTrajectoryMaxArch);
    copy(l1.particles, l2.particles, 24 * 2);
    v1.insert(v1.end(), r.begin(), r.end());
  }
  // Frame 1 of version 1 stored an "arch" while flowing (timer 0): it is not shown.
  const std::int32_t count = 2, a = 0, b = 1;
  std::memcpy(&v1[header + fb1 + l1.arch_count], &count, 4);
  std::memcpy(&v1[header + fb1 + l1.arch], &a, 4);
  std::memcpy(&v1[header + fb1 + l1.arch + 4], &b, 4);
  io::Trajectory t(v1, "old.sstraj");
  CHECK(t.version() == 1);
  REQUIRE(t.size() == 5);
  CHECK_FALSE(t.events_complete());
  CHECK(t.frame(1).arch.empty());
  CHECK(t.frame(3).arch == std::vector<int>{0, 1});
  CHECK(t.frame(3).clog_open);
  REQUIRE(t.events().clogs.size() == 1);
  CHECK(t.events().clogs[0].ended_by == core::ClogEnd::Rule);
  CHECK(t.frame(3).particles[0].x == Approx(0.1f));
  CHECK(t.frame(3).exits.size() == 2);
}

TEST_CASE("a recording made with the clog rule off opens (clog_timeout 0 in the header)", "[io]") {
  const fs::path d = temp_dir("traj_rule_off");
  REQUIRE(
      cli("run " + kScene + kShort + " --set clog_timeout=0 --trajectory-fps 10 --out " + (d / "r").string())
          .code == 0);
  io::Trajectory t(d / "r" / "trajectory.sstraj");
  CHECK(t.info().clog_timeout == 0);
  CHECK(t.events_complete());
  CHECK(std::isinf(t.frame(t.size() - 1).rule_due_in));
  REQUIRE(cli("export " + (d / "r").string() + " --format xyz").code == 0);
}
