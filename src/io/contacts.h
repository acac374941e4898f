// Contact files (.sscon): each recorded frame's grain-grain contacts and their normal forces, beside a
// trajectory (whose frames keep each grain's summed force only), so that pictures made later (the inspector)
// can draw force chains and count coordination as a recording did. Version 1, little-endian:
//
//   header, 16 bytes:  char magic[8] = "SILOCONT"; u32 version = 1; u32 n_particles
//   then per frame:    u32 frame (the trajectory's frame index); u32 count; count x {i32 a; i32 b; f32
//   force_N}
//
// Frames are appended as the run goes (in the trajectory's order); a reader takes every complete frame, so a
// file cut off by a crash reads up to its last whole frame.
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
  void add(const std::vector<core::Contact>& contacts);  // the next frame's
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
  // At most this many contacts in a frame: the contact graph of grains in a plane is planar (3n - 6 edges),
  // with room for the slight overlaps of a soft solver.
  static std::uint32_t max_per_frame(std::uint32_t n_particles) { return 3 * n_particles + 16; }
  static std::uint64_t max_bytes(std::uint32_t n_particles, long max_frames);
  long size() const { return static_cast<long>(offsets_.size()); }
  // Frame k's contacts (empty beyond the last complete frame).
  std::vector<core::Contact> frame(long k) const;

 private:
  std::vector<unsigned char> data_;
  std::vector<size_t> offsets_;  // of each frame's count
};

}  // namespace io
