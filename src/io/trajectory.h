// Trajectory files (.sstraj): every recorded frame of a run and the run's events, for the inspector and for
// users' own analysis. Version 3, little-endian, documented in docs/trajectory.md (with a numpy reader):
//
//   header, 64 bytes:  char magic[8] = "SILOTRAJ"; u32 version = 3; u32 header_bytes; u32 n_particles;
//                      u32 max_arch; u32 frame_bytes; u32 n_species; f64 frame_interval_s; f64 clog_timeout_s
//                      (0: the rule is off); f64 clog_min_gap_s; f64 radius_original_m
//   then:              f32 radius_m[n]; u8 species[n]; zero padding to 8 bytes;
//                      u32 scene_bytes; the run's metadata (TOML text); zero padding to 8 bytes
//   frames, from header_bytes on, each frame_bytes long:
//                      f64 t_s; f64 since_last_exit_s; i64 exits_original; i64 exits_added; i32 long_arches;
//                      i32 arch_count; i32 arch[max_arch] (the open clog's arch, or the forming one, ids left
//                      to right, -1 padded); f64 clog_start_s; f64 rule_due_in_s (inf: rule off); i32
//                      clog_number; u32 flags (bit 0: a clog is open, bit 1: it is arrested, bit 2: the arch
//                      is forming, the clog clog_number not yet confirmed); f32 x_m[n]; f32 y_m[n]; f32
//                      angle_rad[n]; f32 vx_m_s[n]; f32 vy_m_s[n]; f32 force_n[n]
//   events, when the run ended normally (written at close):
//                      char magic[8] = "SILOEVTS"; u32 n_exits; u32 n_clogs; u32 n_arches; u32 reserved;
//                      n_exits x {f64 t_s; i32 id; u32 species};
//                      n_clogs x {f64 start_s; f64 end_s; u32 ended_by; u32 arrested; f64 formed_s (NaN:
//                      no arch)};
//                      n_arches x {f64 t_s; f64 clog_duration_s; f64 span_m; f64 height_m; f64 max_angle_deg;
//                                  u32 count; u32 method; count x {i32 id; u32 species; f32 x_m; f32 y_m}};
//                      then u64 events_offset; char magic[8] = "SILOEND" (the file's last 16 bytes)
//
// Frames are appended as the run goes; a reader takes every complete frame, so a file cut off by a crash
// reads up to its last whole frame (its events then come from the frames' clog states). Version 2 files (no
// formation: clogs of 24 bytes, flags up to 3) and version 1 files
// (frames of t, timer, exits_original, exits_added, long_arches, the arch: no clog state, no events) still
// open: their clogs are rebuilt from the frames' timers.
#pragma once

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "core/events.h"
#include "core/frame.h"
#include "core/model.h"

namespace io {

constexpr std::uint32_t kTrajectoryVersion = 3;
constexpr int kTrajectoryMaxArch = 32;

// Where each field sits in a frame record of a version (bytes from the frame's start; version 1 has no clog
// state: those offsets are 0 and unused).
struct FrameLayout {
  size_t t = 0, since_last_exit = 8, clog_start = 0, rule_due_in = 0, long_arches = 32, clog_number = 0,
         clog_flags = 0, arch_count = 36, arch = 40, exits = 16, particles = 168;
  std::uint32_t n_species = 2;
  size_t bytes(std::uint32_t n_particles) const { return particles + 24 * size_t(n_particles); }
};
FrameLayout frame_layout(std::uint32_t version, std::uint32_t n_species);

struct TrajectoryInfo {
  std::uint32_t n_particles = 0;
  std::uint32_t n_species = 2;  // exits are counted per species
  double frame_interval = 0;    // s of simulated time between frames
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
  // A frame, and what the steps reported since the previous one (kept for the events block).
  void add(const core::Frame& f, int long_arches, const core::StepEvents& since_last = {});
  // Events reported after the last frame (the clog the run's end closed).
  void add_events(const core::StepEvents& e);
  void close();  // the events block, flush; throws core::RuntimeFault on a write error (a full disk)
  long frames() const { return frames_; }
  static size_t frame_bytes(std::uint32_t n, std::uint32_t n_species = 2,
                            std::uint32_t version = kTrajectoryVersion);

 private:
  std::FILE* f_ = nullptr;
  std::string path_;
  std::uint32_t n_;
  FrameLayout layout_;
  long frames_ = 0;
  std::uint64_t bytes_ = 0;  // written so far
  std::vector<unsigned char> buf_;
  core::Events events_;
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
  std::uint32_t version() const { return version_; }
  // The run's events: exits, clogs (the rows of clogs.csv) and the rule's removals (arches.csv). Complete
  // when events_complete(); otherwise (a cut-off file, or version 1) the clogs are rebuilt from the frames
  // and the last may lack its end (its end is then the last frame's time, ended_by RunEnd).
  const core::Events& events() const { return events_; }
  // The run's scene as its metadata holds it, compiled once (null when the metadata holds no valid scene).
  const core::Model* model() const { return model_.get(); }
  bool events_complete() const { return events_complete_; }

 private:
  TrajectoryInfo info_;
  std::vector<unsigned char> data_;  // the whole file; frames are read in place
  size_t header_ = 0, frame_bytes_ = 0;
  FrameLayout layout_;
  long count_ = 0;
  std::vector<int> long_arches_;
  const unsigned char* record(long k) const {
    return data_.data() + header_ + static_cast<size_t>(k) * frame_bytes_;
  }
  bool truncated_ = false;
  std::uint32_t version_ = kTrajectoryVersion;
  core::Events events_;
  bool events_complete_ = false;
  std::unique_ptr<core::Model> model_;  // the metadata's scene compiled, when it holds a valid one
  std::vector<std::uint8_t> sides_;     // each grain's shape (0: disk)
  void parse(std::vector<unsigned char> data, const std::string& p);
  size_t read_events(const std::string& p);  // returns where the frames end
  void check_frames(const std::string& p) const;
  void rebuild_clogs();
};

}  // namespace io
