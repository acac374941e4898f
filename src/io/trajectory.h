// Trajectory files (.sstraj): every recorded frame of a run, for the inspector and for users' own analysis.
// Version 1, little-endian, documented in docs/trajectory.md (with a numpy reader in a few lines):
//
//   header, 64 bytes:  char magic[8] = "SILOTRAJ"; u32 version = 1; u32 header_bytes; u32 n_particles;
//                      u32 max_arch; u32 frame_bytes; u32 reserved; f64 frame_interval_s; f64 clog_timeout_s;
//                      f64 clog_min_gap_s; f64 radius_original_m
//   then:              f32 radius_m[n]; u8 species[n] (0 original, 1 added); zero padding to 8 bytes;
//                      u32 scene_bytes; the run's metadata (TOML text); zero padding to 8 bytes
//   frames, from header_bytes on, each frame_bytes long:
//                      f64 t_s; f64 since_last_exit_s; i64 exits_original; i64 exits_added; i32 long_arches;
//                      i32 arch_count; i32 arch[max_arch] (ids left to right, -1 padded);
//                      f32 x_m[n]; f32 y_m[n]; f32 angle_rad[n]; f32 vx_m_s[n]; f32 vy_m_s[n]; f32 force_n[n]
//
// Frames are appended as the run goes; a reader takes every complete frame, so a file cut off by a crash
// reads up to its last whole frame.
#pragma once

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "core/frame.h"
#include "core/setup.h"

namespace io {

constexpr std::uint32_t kTrajectoryVersion = 1;
constexpr int kTrajectoryMaxArch = 32;

struct TrajectoryInfo {
  std::uint32_t n_particles = 0;
  double frame_interval = 0;  // s of simulated time between frames
  double clog_timeout = 5, clog_min_gap = 0.5, radius_original = 0.065;
  std::vector<float> radius;
  std::vector<core::Species> species;
  std::string metadata;  // TOML text with the scene
};

class TrajectoryWriter {
 public:
  TrajectoryWriter(const std::filesystem::path& path, const TrajectoryInfo& info);
  ~TrajectoryWriter();
  TrajectoryWriter(const TrajectoryWriter&) = delete;
  TrajectoryWriter& operator=(const TrajectoryWriter&) = delete;
  void add(const core::Frame& f, int long_arches);
  void close();  // flush; throws core::RuntimeFault on a write error (a full disk)
  long frames() const { return frames_; }
  static size_t frame_bytes(std::uint32_t n);

 private:
  std::FILE* f_ = nullptr;
  std::string path_;
  std::uint32_t n_;
  long frames_ = 0;
  std::vector<unsigned char> buf_;
};

// Reads a whole trajectory into memory (a 150 s run at 30 fps is ~28 MB).
class Trajectory {
 public:
  // Throws core::InputError naming the file and what is wrong (missing, foreign, truncated header, version).
  explicit Trajectory(const std::filesystem::path& path);
  // From bytes in memory; `name` names them in errors.
  Trajectory(const std::vector<unsigned char>& data, const std::string& name);
  const TrajectoryInfo& info() const { return info_; }
  long size() const { return count_; }
  bool truncated() const { return truncated_; }  // a partial last frame was dropped
  // Frame k as a core::Frame (arch, counters, positions, velocities, forces).
  core::Frame frame(long k) const;
  int long_arches(long k) const { return long_arches_[static_cast<size_t>(k)]; }
  double since_last_exit(long k) const;
  double time(long k) const;

 private:
  TrajectoryInfo info_;
  std::vector<unsigned char> data_;  // the whole file; frames are read in place
  size_t header_ = 0, frame_bytes_ = 0;
  long count_ = 0;
  std::vector<int> long_arches_;
  const unsigned char* record(long k) const {
    return data_.data() + header_ + static_cast<size_t>(k) * frame_bytes_;
  }
  bool truncated_ = false;
  std::unique_ptr<core::Setup> setup_;  // from the metadata's scene, when it holds a valid one
  std::vector<std::uint8_t> sides_;     // each grain's shape (0: disk)
  void parse(std::vector<unsigned char> data, const std::string& p);
};

}  // namespace io
