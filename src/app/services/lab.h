// Camera frames to tracked particles, shared by `detect` and the round-trip benchmark: the calibration from
// pixels to the container's metres, and the detection and linking of every frame (vision/detect.h) into the
// CSV that `import` reads (trackpy's column names: frame, particle, x, y in pixels; r in pixels; t in s;
// species by name).
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>

#include "core/image.h"
#include "core/model.h"
#include "vision/detect.h"
#include "vision/lens.h"

namespace app {

// --rotation DEG (detect's and import's) in radians; throws core::InputError outside -45 to 45 degrees.
double rotation_radians(double degrees);

struct Calibration {
  double scale = 0;  // m per pixel
  double origin_x = 0,
         origin_y = 0;  // px (OpenCV's: the first pixel's centre is 0, 0) of the outlet's centre
  double rotation = 0;  // rad: the container turned counter-clockwise in the picture (a camera turned the
                        // other way)
  double residual = 0;  // m: the marked points' root-mean-square distance from where the fit puts them
  double fps = 0;       // frames per simulated or lab second (0: unknown)
  std::string from;     // "command line", "marked points", or the recording's metadata file

  // A pixel (x right, y down) in the container's metres, and back.
  core::Vec2 to_metres(double px, double py) const;
  core::Vec2 to_pixels(core::Vec2 m) const;
};

// A siloscope movie's own calibration, from the recording directory beside it (MOVIE without .mp4, holding
// metadata.toml): its camera, picture size and frame interval. Returns false with `why` when the input is not
// such a movie or its camera moves (a camera path, slow motion or freezes: pixels then change meaning during
// the film). `model` gets the recording's scene.
bool movie_calibration(const std::filesystem::path& input, Calibration& cal, core::Model& model,
                       std::string& why);

// Marked points "PX,PY=X,Y:PX,PY=X,Y[:...]" (pixels = metres in the container's frame), two or more: the
// scale, origin and rotation that carry the metres onto the pixels, by least squares (exact for two; with
// more, `residual` says how far the points lie from the fit). Pixels marked on the film are taken through
// `lens` first. Throws core::InputError naming `option`.
Calibration points_calibration(const std::string& text, const std::string& option,
                               const vision::Lens& lens = {});

struct DetectStats {
  long frames = 0, detections = 0, dropped_outside = 0, tracks = 0;
  bool bright = false;  // the disks were bright on a dark background (given or found)
  long first_as_dark = 0,
       first_as_bright = 0;  // the first frame's disks either way, when the polarity was found
  double seconds = 0;        // wall time of the whole pass: decoding, detection (on several threads), linking
  long species = 0;          // the scene's species
  double size_spread = 0;    // the spread of the tracks' median radii, in log size (lab::fit_size_species)
  double size_error_rate = 0;  // the share of grains the scene's size laws leave in another species' sizes
};

struct DetectJob {
  vision::DetectOptions detect;
  Calibration cal;            // of ideal pixels (the lens's distortion taken out)
  vision::Lens lens;          // the film's lens (none: the film's pixels are ideal)
  long first = 0, last = -1;  // frames to use (last < 0: to the end)
  double max_step = 0.8;      // radii
  int memory = 2;             // frames
  bool bright = false;        // bright disks on a dark background (inverted before detection)
  bool bright_given = false;  // `bright` as given; else found from the first frame (the polarity with clearly
                              // more disks: at least 10, and a tenth more)
  // For the round trip: what a camera adds to each frame (null: nothing), and detections dropped at random.
  std::function<cv::Mat(const cv::Mat&, long)> camera;
  double drop = 0;
  std::uint64_t seed = 1;
  std::function<void(long)> progress;
  // Each frame used, as decoded (before detection), in order, on the calling thread: detect --rectified.
  std::function<void(const cv::Mat&, long)> on_frame;
};

// The film as the tracks see it (detect --rectified): every frame carried through the lens to ideal pixels
// and turned upright (the container's axis vertical), the outlet's centre kept at its pixel and the scale
// unchanged; what lies outside the film is black. The width and height are made even (a movie's yuv420p) by
// one column or row more.
class Rectifier {
 public:
  Rectifier(const Calibration& cal, const vision::Lens& lens, int width, int height);
  // A frame (BGR, BGRA or grey) rectified into `out`, RGBA as record's movie writer takes it.
  void apply(const cv::Mat& frame, core::Image& out) const;
  // The rectified film's own calibration: the same scale and origin, no rotation, no lens.
  const Calibration& upright() const { return upright_; }
  int width() const { return map_.cols; }
  int height() const { return map_.rows; }

 private:
  cv::Mat map_, map_fraction_;  // cv::remap's fixed-point tables
  Calibration upright_;
};

// Every frame of `source` detected and linked; the CSV's text. Disks whose centre lies outside the container
// (by more than a diameter; below the outlet is inside) or inside the obstacle are dropped and counted.
std::string detect_tracks(vision::FrameSource& source, const DetectJob& job, const core::Model& model,
                          DetectStats& stats);

}  // namespace app
