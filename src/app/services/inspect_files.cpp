#include "app/services/inspect_files.h"

#include "record/mp4.h"
#include "record/png.h"

namespace app {

namespace {
record::VideoSettings settings(int width, int height, int fps) {
  record::VideoSettings v;
  v.width = width;
  v.height = height;
  v.fps = fps;
  return v;
}

class Mp4Sink : public ui::MovieSink {
 public:
  Mp4Sink(const std::string& path, const record::VideoSettings& v) : mp4_(path, v) {}
  void add(const core::Image& img) override { mp4_.add(img); }
  void finish() override { mp4_.finish(); }

 private:
  record::Mp4Writer mp4_;
};
}  // namespace

void RecordFiles::write_png(const std::string& path, const core::Image& img) const {
  record::write_png(path, img, true);
}

void RecordFiles::check_movie(int width, int height, int fps) const {
  record::validate(settings(width, height, fps));
}

std::unique_ptr<ui::MovieSink> RecordFiles::open_movie(const std::string& path, int width, int height,
                                                       int fps) const {
  return std::make_unique<Mp4Sink>(path, settings(width, height, fps));
}

}  // namespace app
