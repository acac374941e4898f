// Contact files (.sscon): each recorded frame's contacts and their forces, beside a trajectory (whose frames
// keep each grain's summed force only), so that pictures and measures made later (the inspector, the stress
// colouring, exports) have the forces a recording had. Little-endian:
//
//   header, 16 bytes:  char magic[8] = "SILOCONT"; u32 version = 2; u32 n_particles
//   then per frame:    u32 frame (the trajectory's frame index); u32 count; count x record
//   version 2 record:  i32 a; i32 b; f32 normal_N; f32 tangential_N; f32 x_m, y_m; f32 nx, ny  (32 bytes)
//   version 1 record:  i32 a; i32 b; f32 normal_N  (12 bytes; grain-grain contacts only)
//
// In version 2, b is a grain and a is a grain or a wall (-1 - its core::Wall index); the force on b is
// normal * n + tangential * (ny, -nx), n the unit normal from a to b, (x, y) where they touch
// (core::Contact). Frames are appended as the run goes (in the trajectory's order); a reader takes every
// complete frame, so a file cut off by a crash reads up to its last whole frame. Both versions are read.
#pragma once

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "core/frame.h"

namespace io {

class ContactsWriter {
 public:
  ContactsWriter(const std::filesystem::path& path, std::uint32_t n_particles);
  ~ContactsWriter();
  ContactsWriter(const ContactsWriter&) = delete;
  ContactsWriter& operator=(const ContactsWriter&) = delete;
  // The next frame's: grain-grain contacts and those with walls (a < 0).
  void add(const std::vector<core::Contact>& contacts, const std::vector<core::Contact>& walls);
  void close();  // flush; throws core::RuntimeFault on a write error (a full disk)

 private:
  std::FILE* f_ = nullptr;
  std::string path_;
  std::uint32_t frames_ = 0;
  std::vector<unsigned char> buf_;
};

class Contacts {
 public:
  // Throws core::InputError naming the file and what is wrong (foreign, another version, another grain count,
  // ids out of range, frames out of order, more frames or contacts than a run of this size has). The file's
  // size is checked against max_bytes() before anything is read. io::Run opens a run's contacts (and ties
  // them to its trajectory); nothing else should.
  Contacts(const std::filesystem::path& path, std::uint32_t n_particles, long max_frames);
  // At most this many contacts in a frame: the contact graph of grains and walls in a plane is planar (3n - 6
  // edges over n grains and walls), with room for the slight overlaps of a soft solver and for a container
  // of many walls.
  static std::uint32_t max_per_frame(std::uint32_t n_particles) { return 3 * n_particles + 256; }
  static constexpr int kMaxWalls = 4096;  // a wall's index in a record is below this
  static std::uint64_t max_bytes(std::uint32_t n_particles, long max_frames);
  long size() const { return static_cast<long>(offsets_.size()); }
  std::uint32_t version() const { return version_; }
  // Whether the file holds tangential forces, contact points and walls (version 2).
  bool has_geometry() const { return version_ >= 2; }
  // Frame k's grain-grain contacts, and its contacts with walls (empty beyond the last complete frame).
  std::vector<core::Contact> frame(long k) const;
  std::vector<core::Contact> walls(long k) const;

 private:
  std::vector<core::Contact> read(long k, bool walls) const;
  std::uint32_t version_ = 0;
  size_t record_ = 0;
  std::vector<unsigned char> data_;
  std::vector<size_t> offsets_;  // of each frame's count
};

}  // namespace io
