// Disks in camera frames: located in each frame (on a background-flattened picture, the peaks of each disk
// pixel's distance to the background, whose height is a species' radius; centres refined by a circle fitted
// to the disk's edge) and linked frame to frame into tracks (vision/linker.h), so a film of a lab silo
// becomes the tracked particles `siloscope import` reads. Pixels in, pixels out (x to the right, y down, as
// images and trackpy have them); the calibration to metres is the caller's. OpenCV (Debian's libopencv-*-dev)
// does the image work.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace vision {

struct Circle {
  double x = 0, y = 0, r = 0;  // px
  int band = 0;                // the size band it was found in (a species)
  double score = 0;            // how strongly it was found (its distance-to-background peak, px)
  // r measured by the fit to its rim; otherwise r is the band's radius (a blurred or crowded rim): the size
  // is then only known to lie within the band.
  bool fitted = false;
};

struct DetectOptions {
  std::vector<double> radius_px;  // each species' radius in pixels (one Hough pass per band)
  double band = 0.25;             // a band spans radius * (1 -+ band)
  double edge_threshold = 60;     // Canny's high threshold on the flattened 8-bit image (for the refinement)
  cv::Mat ignore;                 // 8-bit, nonzero where edges are not a disk's (the walls); empty: none
};

// Every disk found in one frame (BGR or grey).
std::vector<Circle> detect_disks(const cv::Mat& image, const DetectOptions& opt);

// What a camera adds to a clean picture, for the round trip (level 0: nothing): blur of 0.6 L px, Gaussian
// noise of 6 L grey levels, light falling off by 12 L % across the picture, a perspective that moves the
// corners by 0.1 L % of the width. Deterministic for a seed.
cv::Mat add_camera(const cv::Mat& clean, double level, std::uint64_t seed);

// The pictures of a directory (PNG, JPEG, BMP, TIFF, whatever the case of their extension), in name order.
std::vector<std::filesystem::path> pictures_in(const std::filesystem::path& dir);

// The frames of a video file, or of a directory of images (PNG, JPEG, BMP, TIFF in name order), one at a
// time. Throws core::InputError naming the path when it cannot be opened or a frame cannot be decoded.
class FrameSource {
 public:
  explicit FrameSource(const std::string& path);
  ~FrameSource();
  FrameSource(const FrameSource&) = delete;
  FrameSource& operator=(const FrameSource&) = delete;
  bool next(cv::Mat& frame);             // false after the last frame
  double fps() const { return fps_; }    // the video's frame rate (0: unknown, a directory)
  long count() const { return count_; }  // frames, when known (-1: unknown)
  // A video that ended before the frames its header announces (cut short: a copy or a recording interrupted);
  // call after next() returned false.
  bool ended_early() const { return exhausted_ && read_ + 1 < count_; }
  long frames_read() const { return read_; }
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  struct Impl;
  Impl* impl_;
  double fps_ = 0;
  long count_ = -1;
  int width_ = 0, height_ = 0;
  long read_ = 0;           // video frames read
  bool exhausted_ = false;  // a video (only) gave no further frame
};

}  // namespace vision
