// H.264 MP4 movies through libavcodec/libavformat (the only place that includes libav headers).
// yuv420p with BT.709 colour, +faststart so browsers and presentation software play it while it loads.
// The file is written as NAME.partial and renamed to NAME by finish(): a crash or kill -9 never leaves a
// truncated file under the final name, and finish() after Ctrl-C gives a playable movie of what was recorded.
#pragma once

#include <filesystem>
#include <memory>
#include <string>

#include "core/image.h"

namespace record {

struct VideoSettings {
  int width = 1920, height = 1080;  // even, 16..8192
  int fps = 30;                     // the requested rate (validated)
  double frame_rate = 0;            // the rate written into the file, frames per video second (0: fps); the
                                    // recorder makes it speed / (whole steps per frame * dt), e.g. 1000/33
  int crf = 20;                     // 0 (lossless) .. 51; lower is better quality
  std::string preset = "veryfast";  // x264 preset: ultrafast .. veryslow
  std::string comment;              // stored in the file's metadata (we put the run's metadata.toml here)
};

// Throws core::InputError naming the setting if it is out of range.
void validate(const VideoSettings& v);

class Mp4Writer {
 public:
  Mp4Writer(std::filesystem::path final_path, const VideoSettings& settings);
  ~Mp4Writer();  // without finish(): removes the partial file
  Mp4Writer(const Mp4Writer&) = delete;
  Mp4Writer& operator=(const Mp4Writer&) = delete;

  void add(const core::Image& img);  // one frame; the image must have the movie's size
  void finish();                     // flush, write the index, rename into place
  long frames() const;
  // Seconds spent in colour conversion and in encoding (including muxing) so far.
  double convert_seconds() const;
  double encode_seconds() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace record
