// The module siloscope_codecs.so (vision/codecs.h): OpenCV's picture and video readers, loaded by the binary
// when a command first reads a picture or a video.
#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>

#include "vision/codecs.h"

namespace {

class OpenCvVideo : public vision::VideoReader {
 public:
  bool open(const std::string& path) {
    try {
      if (!video_.open(path, cv::CAP_FFMPEG) || !video_.isOpened()) return false;
      fps = video_.get(cv::CAP_PROP_FPS);
      count = static_cast<long>(video_.get(cv::CAP_PROP_FRAME_COUNT));
      width = static_cast<int>(video_.get(cv::CAP_PROP_FRAME_WIDTH));
      height = static_cast<int>(video_.get(cv::CAP_PROP_FRAME_HEIGHT));
      return true;
    } catch (const cv::Exception&) {
      return false;
    }
  }
  bool read(cv::Mat& frame) override {
    try {
      return video_.read(frame) && !frame.empty();
    } catch (const cv::Exception&) {
      return false;
    }
  }

 private:
  cv::VideoCapture video_;
};

class OpenCvCodecs : public vision::Codecs {
 public:
  cv::Mat read_picture(const std::string& path, int flags) const override {
    try {
      return cv::imread(path, flags);
    } catch (const cv::Exception&) {
      return {};
    }
  }
  size_t count_pages(const std::string& path) const override {
    try {
      return cv::imcount(path, cv::IMREAD_COLOR);
    } catch (const cv::Exception&) {
      return 0;
    }
  }
  bool read_pages(const std::string& path, int start, int count, std::vector<cv::Mat>& pages) const override {
    try {
      return cv::imreadmulti(path, pages, start, count, cv::IMREAD_COLOR) && !pages.empty();
    } catch (const cv::Exception&) {
      return false;
    }
  }
  std::unique_ptr<vision::VideoReader> open_video(const std::string& path) const override {
    auto v = std::make_unique<OpenCvVideo>();
    if (!v->open(path)) return nullptr;
    return v;
  }
};

}  // namespace

// The module's one entry point (vision/codecs.cpp looks it up by this name).
extern "C" __attribute__((visibility("default"))) const vision::Codecs* siloscope_codecs_v1() {
  static const OpenCvCodecs codecs;
  return &codecs;
}
