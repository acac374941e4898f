// A lab run from tracked particles: the same frames and events a simulation's recording has, found from
// positions alone (lab/tracks.h gives them in metres, in the container's frame).
//
//  - Grains: one per track, its radius the median of its detections (or its species' radius). Ids that change
//    are joined: a track that ends away from the outlet and one that starts within `join_distance` diameters
//    of where it ended, at most `max_gap` frames later, are the same grain. Gaps of at most `max_gap` frames
//    inside a track are filled by linear interpolation; longer gaps, and the frames before a grain appears
//    and after it leaves, park it far below the container (as a drained grain is parked).
//  - Particles: the run's particles are slots that grains pass through, as a simulation re-injects the grains
//    that left: a grain that enters takes the place of one of its species and size (within 2%) that left
//    earlier, so a long film's run holds about as many particles as the container holds grains.
//  - Exits: a grain whose centre falls wholly below the outlet line (y < -r), as in the simulation, or whose
//    track ends within a diameter above the outlet, inside its opening, before the last frame (it fell out of
//    the field of view between two frames).
//  - Contacts: two grains touch when the gap between them is at most `contact_tolerance` times the smaller
//    diameter (the literature's rule for images: no forces are measured), and a grain touches a wall or the
//    obstacle within the same gap.
//  - Clogs and arches: the simulation's own rules (core::ClogTracker): a clog opens when no grain has left
//  for
//    clog_min_gap; its arch is the blocking fewest-grains path across the outlet (core::find_arch) found at
//    each frame; it is arrested when the grains around the outlet moved less than arrest_shift radii over
//    arrest_hold (at least one frame); there is no rule (nothing removes an arch in a lab), so a clog ends at
//    the next exit or at the last frame.
#pragma once

#include <string>
#include <vector>

#include "core/arch.h"
#include "core/events.h"
#include "core/model.h"
#include "lab/tracks.h"

namespace lab {

struct ImportOptions {
  double contact_tolerance = 0.1;  // gap, as a fraction of the smaller diameter, that still counts as contact
  int max_gap = 3;                 // frames
  double join_distance = 0.5;      // diameters
  // The scene's arrest_shift as given (--set arrest_shift=...): taken as it is. Otherwise the tracks' own
  // noise sets a floor under it (ImportReport::arrest_floor).
  bool arrest_shift_given = false;
  // Where the tracks' points and the run's paths are kept while it is made (files without a name; empty: the
  // system's temporary directory): the output's directory.
  std::string spill_dir;
};

// What the import did with the file, for the metadata and the terminal.
struct ImportReport {
  long frames = 0, rows = 0, tracks = 0, grains = 0;
  long particles = 0;       // of the run: a grain that left gives its place to one that enters later
  long joined = 0;          // tracks joined to an earlier one (ids that changed)
  double noise = 0;         // m: the positions' noise, measured from the tracks (see Importer::measure_noise)
  double arrest_floor = 0;  // m: the smallest shift the arrest check asks of every grain (6 x noise)
  long split = 0;           // tracks split where they jumped farther than a grain moves (ids used again)
  long interpolated = 0;    // positions filled inside short gaps
  long long_gaps = 0;       // gaps longer than max_gap (the grain parked meanwhile)
  long exits_below = 0;     // exits seen below the outlet line
  long exits_lost = 0;      // exits inferred from a track ending inside the outlet
  long left_view = 0;       // tracks ending elsewhere before the last frame (left the field of view)
  long entered = 0;         // tracks starting after the first frame (entered the field of view)
  long interval_changes = 0;  // frame intervals more than 1% from the median (a changed frame rate)
  double interval_median = 0, interval_min = 0, interval_max = 0;  // s
  double time_offset = 0;             // s: the file's time of the first frame (the run starts there at t = 0)
  long frames_with_arch = 0;          // frames where a blocking arch is found (by distance), flowing or not
  long frames_clogged = 0;            // frames with a clog open
  long frames_clogged_with_arch = 0;  // ... where this frame's own check finds a blocking arch
  long frames_flowing_with_arch = 0;  // frames without a clog where the check finds one (a chain in passing)
};

struct ClogArch {
  int clog = 0;                 // row of clogs.csv
  double t = 0;                 // s: the frame the arch was taken from (the last at rest, else the last)
  std::vector<int> ids;         // grains, left to right
  std::vector<long> track_ids;  // the file's ids
  core::ArchDescriptors descriptors;
};

// Where each particle of the run is at every frame, as the import found it: detections, short gaps
// interpolated, unseen particles parked (m, rad, in the container's frame). Kept on disk (io/spill.h): a
// film's length costs disk, not memory.
struct Paths {
  explicit Paths(const std::string& spill_dir = "") : pos(spill_dir), angle(spill_dir), present(spill_dir) {}
  std::vector<double> t;  // s, per frame
  std::size_t n = 0;      // particles
  // Frame k's particle g at k * n + g.
  io::Spill<core::Vec2> pos;
  io::Spill<float> angle;
  io::Spill<std::uint8_t> present;  // seen (or interpolated) at that frame

  core::Vec2 pos_at(std::size_t k, std::size_t g) const { return pos[k * n + g]; }
  float angle_at(std::size_t k, std::size_t g) const { return angle[k * n + g]; }
  bool seen_at(std::size_t k, std::size_t g) const { return present[k * n + g] != 0; }
  // The pages read so far leave memory (they stay on disk).
  void release() const {
    pos.release();
    angle.release();
    present.release();
  }
};

struct Imported {
  // Per frame: time, clog state and arch; the particles are left empty and made when a frame is written
  // (particles_at): a 10-minute film's frames held whole took 170 MB beside the paths they are made from.
  std::vector<core::Frame> frames;
  std::vector<core::StepEvents> between;  // what happened since the previous frame, per frame
  core::StepEvents after;                 // the clog the end of the file closed
  core::Events events;
  std::vector<double> radius;          // per particle of the run
  std::vector<core::Species> species;  // per particle
  std::vector<long> track_id;          // per particle, the file's id of its first grain
  std::vector<ClogArch> clog_arches;
  Paths paths;
  ImportReport report;

  // Frame k's particles: positions and angles from the paths, velocities from the neighbouring frames (unseen
  // particles parked, at rest). Frames asked for in order release the paths' pages as they go.
  void particles_at(size_t k, std::vector<core::Particle>& out) const;
};

Imported import_tracks(Tracks& tracks, const core::Model& model, const ImportOptions& opt);

}  // namespace lab
