// Tracked particles from a lab experiment (or from `siloscope detect`): a CSV of one row per particle per
// frame, read into metres in the container's frame (the outlet centred at x = 0, its line at y = 0, y up).
//
// Columns are found by name: the time (t, time, t_s) or the frame number (frame, with --fps), the particle's
// id (particle, id, track, track_id), x and y, and optionally the radius (r, radius) or diameter (diameter,
// d), the angle (angle, rad) and the species (species: a name of the geometry scene's species or its index).
// trackpy's columns (frame, particle, x, y, and its own others) work without a map, its `size` telling the
// species of a mixture apart; so do TrackMate's spots (TRACK_ID, POSITION_X, POSITION_Y, POSITION_T in
// seconds or FRAME, RADIUS, and its three lines of names and units under the header), and its XML (a file
// ending .xml: lab/trackmate_xml.h). Spots without a track
// id are skipped and counted. Any other naming is given with a column map "id=TrackID,x=X_px,...". The file
// may be any CSV dialect io::CsvTable reads. Pixel units are converted by a scale (m per pixel) and the pixel
// where the outlet's centre is (the origin); image rows grow downwards, so y is flipped unless y_up.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "core/setup.h"
#include "io/spill.h"

namespace lab {

// Which column holds what (empty: look for the default names).
struct ColumnMap {
  std::string time, frame, id, x, y, radius, diameter, angle, species, size;
};
// "id=TrackID,x=X" into a map; throws core::InputError naming `option`, the entry and the allowed names.
ColumnMap parse_column_map(const std::string& text, const std::string& option);

struct Units {
  double scale = 0;                   // m per pixel; 0: the positions are in metres already
  double origin_x = 0, origin_y = 0;  // the outlet centre, in the file's units (pixels with a scale)
  bool y_up = false;    // with a scale: y grows upwards in the file (image rows grow downwards otherwise)
  double rotation = 0;  // rad, with a scale: the container turned counter-clockwise in the picture
  double fps = 0;       // frames per second, when the file has frame numbers and no times
};

struct Detection {
  long id;            // the file's particle id
  double x, y;        // m, container frame
  double r;           // m (the species' radius when the file has none)
  double angle;       // rad (0 when the file has none)
  int species;        // index into the scene's species
  std::int32_t line;  // the file's line (for messages; a file of at most kMaxTrackBytes has fewer than 2^31)
};

struct TrackFrame {
  double t = 0;                // s, as the file gives it (frame / fps for frame numbers)
  long number = -1;            // the file's frame number (-1: none)
  std::span<Detection> found;  // by id, in Tracks::detections
  std::size_t first = 0;       // index of found's first in Tracks::detections
};

struct Tracks {
  std::string source;              // the file read
  std::vector<TrackFrame> frames;  // in time order, one per distinct frame of the file
  // Every frame's detections, one after another: kept in a hidden file beside the output (io/spill.h), so
  // that a film's length costs disk, not memory. Release its pages (detections.release()) after a pass.
  io::Spill<Detection> detections;
  bool has_radius = false, has_angle = false, has_species = false;
  std::vector<std::string> columns_used;  // "time=t", "id=particle", ... (for the metadata)
  long rows = 0;
  long untracked = 0;            // rows without a track id (a tracker's spots it linked to no track), skipped
  bool species_by_size = false;  // species told apart by a size column (trackpy's), each row by itself
  // Species from sizes or radii (0 when neither): the sizes' spread about their species' law (log size;
  // measured on the fixed-size species, else assumed), and the share of grains that even the likeliest
  // species gives another than their own (laws that overlap).
  double size_spread = 0, size_error_rate = 0;
};

// --origin "X,Y" (the outlet centre, in the file's or the picture's units). Throws core::InputError.
void parse_origin(const std::string& text, double& x, double& y);

// The largest track file read: about 40 million rows (an hour and a half of a 30 fps film of 250 grains),
// kept on disk as 48 bytes a detection (and 56 more while a file's rows not in frame order are put in place).
constexpr std::uintmax_t kMaxTrackBytes = std::uintmax_t{4} << 30;

// Reads and checks `path`: the needed columns present (the error names what was looked for and how to map
// it), numbers where numbers belong, no particle id twice in one frame, no position outside the container
// (a centre beyond its walls or above its top by more than a grain's diameter: a wrong scale or origin; the
// region below the outlet, where grains fall, is allowed). Throws core::InputError naming the file, its line,
// the column and the value. The detections are kept in a hidden file in `spill_dir` (empty: the system's
// temporary directory).
Tracks read_tracks(const std::string& path, const ColumnMap& map, const Units& units,
                   const core::Setup& setup, const core::Geometry& geo, const std::string& spill_dir = "");

}  // namespace lab
