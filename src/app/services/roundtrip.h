// The round trip that validates detect and import without lab data: a siloscope recording is the ground
// truth; its movie, with what a camera adds (vision::add_camera at a level), is detected, linked and
// imported, and what comes back is measured against the recording's own trajectory and events.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace app {

struct RoundTripRow {
  double level = 0, drop = 0;
  long frames = 0;
  // Grains: whole disks in the picture found (recall) and detections that are grains (precision); position
  // error in diameters of the matched grain (median, 95th percentile); a grain's track id changing while the
  // grain stays in view (per 1000 grain-frames).
  double recall = 0, precision = 0, error_median_d = 0, error_p95_d = 0;
  long id_switches = 0;
  double switches_per_1000 = 0;
  // Clogs: the recording's clogs found again (start within 0.25 s), clogs found that are none, and the
  // median error of their start and end (s).
  long true_clogs = 0, found_clogs = 0, matched_clogs = 0;
  long arrested_agree = 0;  // matched clogs whose arrested flag is the recording's
  // Exits per species (by index), the recording's and the import's, until three frames before the last.
  std::vector<long> true_exits, found_exits;
  double start_error_s = 0, end_error_s = 0;
  // Arches of the matched clogs at the import's arch frame: members found (recall) and members that are
  // members (precision), pooled; span and rise errors (median |difference|, diameters), largest bead angle
  // (median |difference|, degrees).
  long arches_compared = 0;
  double member_recall = 0, member_precision = 0, span_error_d = 0, rise_error_d = 0, theta_error_deg = 0;
  double detect_s_per_frame = 0;  // the whole detection pass a frame: decoding, the camera's effects, linking
  // Frames during a clog with its arch standing, in the recording and in the import.
  double contact_tolerance = 0.1;
  long arch_frames_true = 0, arch_frames_found = 0;
  // The import's own check at each frame (not the clog's held arch): frames clogged, of them with an arch
  // found, and frames flowing with one found (a chain across the outlet in passing).
  long frames_clogged = 0, clogged_with_arch = 0, flowing_with_arch = 0;
};

// `recording`: a recording directory (with trajectory.sstraj), its movie beside it (single-panel camera, no
// camera path, slow motion or freezes). The tracks CSV goes to `tracks_csv`. Throws core::InputError when the
// recording cannot serve as ground truth.
// With `reuse_tracks`, an existing `tracks_csv` is imported again without detection (another tolerance).
RoundTripRow round_trip(const std::filesystem::path& recording, double level, double drop, std::uint64_t seed,
                        const std::filesystem::path& tracks_csv, double contact_tolerance = 0.1,
                        bool reuse_tracks = false);

}  // namespace app
