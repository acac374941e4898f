// Pictures and videos read with OpenCV's imgcodecs and videoio, behind an interface. Those two libraries
// bring about 100 shared libraries nothing else needs (GDAL, GDCM, GStreamer among them): linked into the
// binary, they cost every start of every command 0.2 s, a sweep's realizations and the inspector's launch
// included. They live in a module beside the binary (siloscope_codecs.so: BINDIR/lib/siloscope here,
// PREFIX/lib/siloscope installed), loaded the first time a command reads a picture or a video.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>  // its flags only (cv::IMREAD_COLOR, _GRAYSCALE): no call links it

namespace vision {

// A video's frames, one at a time.
class VideoReader {
 public:
  virtual ~VideoReader() = default;
  virtual bool read(cv::Mat& frame) = 0;  // false after the last frame (or one that cannot be decoded)
  double fps = 0;
  long count = -1;  // frames, as the header announces them
  int width = 0, height = 0;
};

// Nothing here throws: failures come back as an empty picture, false or null, for the caller to name.
class Codecs {
 public:
  virtual ~Codecs() = default;
  // A picture as 8-bit BGR (colour) or grey, as cv::imread's flags say; empty when it cannot be decoded.
  virtual cv::Mat read_picture(const std::string& path, int flags) const = 0;
  // A TIFF's pages: how many (0: not a TIFF that can be read), and `count` of them from `start`.
  virtual size_t count_pages(const std::string& path) const = 0;
  virtual bool read_pages(const std::string& path, int start, int count,
                          std::vector<cv::Mat>& pages) const = 0;
  // A video through FFmpeg; null when no video stream can be read.
  virtual std::unique_ptr<VideoReader> open_video(const std::string& path) const = 0;
};

// The module's readers, loaded on first use. Throws core::RuntimeFault naming where it looked when the module
// is missing (a build or an installation without it).
const Codecs& codecs();

}  // namespace vision
