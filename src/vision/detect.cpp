// Disks in camera frames (vision/detect.h).
#include "vision/detect.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <random>

extern "C" {
#include <libavutil/log.h>
}
#include <opencv2/core/utils/logger.hpp>
#include <opencv2/imgproc.hpp>

#include "core/error.h"
#include "core/format.h"
#include "vision/codecs.h"

namespace vision {

namespace {

// The picture with its light made even: divided by the background (the disks closed away on a quarter-size
// copy, which keeps the large kernel cheap), dark disks on a bright background as 8 bits.
cv::Mat flatten(const cv::Mat& image, double rmax) {
  cv::Mat gray;
  if (image.channels() == 3)
    cv::cvtColor(image, gray, cv::COLOR_BGR2GRAY);
  else if (image.channels() == 4)
    cv::cvtColor(image, gray, cv::COLOR_BGRA2GRAY);
  else
    gray = image;
  cv::Mat small, bg;
  cv::resize(gray, small, cv::Size(), 0.25, 0.25, cv::INTER_AREA);
  const int k = 2 * static_cast<int>(std::ceil(0.25 * 2.4 * rmax)) + 1;
  cv::morphologyEx(small, small, cv::MORPH_CLOSE,
                   cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(k, k)));
  cv::GaussianBlur(small, small, cv::Size(), 0.25 * rmax);
  cv::resize(small, bg, gray.size(), 0, 0, cv::INTER_LINEAR);
  cv::Mat g32, b32, flat;
  gray.convertTo(g32, CV_32F);
  bg.convertTo(b32, CV_32F);
  cv::max(b32, 1.0, b32);
  cv::divide(g32, b32, flat, 230.0);
  cv::Mat out;
  flat.convertTo(out, CV_8U);
  cv::GaussianBlur(out, out, cv::Size(), 1.0);
  return out;
}

// The centre and radius refined to a fraction of a pixel: a least-squares circle (Kasa's) through the edge
// pixels near the found circle whose brightness grows outwards along the radius (the disk's own rim; a
// neighbour's rim, an outline's inner edge or a wall it leans on point otherwise).
// One least-squares fit through the rim pixels within `band` px of the circle c; false when too few.
bool fit_rim(Circle& c, double band, const cv::Mat& edges, const cv::Mat& gx, const cv::Mat& gy) {
  const double reach = c.r + band + 1;
  const int x0 = std::max(0, static_cast<int>(c.x - reach)),
            x1 = std::min(edges.cols - 1, static_cast<int>(c.x + reach));
  const int y0 = std::max(0, static_cast<int>(c.y - reach)),
            y1 = std::min(edges.rows - 1, static_cast<int>(c.y + reach));
  double sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0, sxz = 0, syz = 0, sz = 0;
  int n = 0;
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) {
      if (!edges.at<std::uint8_t>(y, x)) continue;
      const double dx = x - c.x, dy = y - c.y, d = std::hypot(dx, dy);
      if (std::fabs(d - c.r) > band || d < 1e-9) continue;
      const double ex = gx.at<float>(y, x), ey = gy.at<float>(y, x), e = std::hypot(ex, ey);
      if (e < 1e-9 || (ex * dx + ey * dy) / (e * d) < 0.8) continue;  // dark inside, bright outside
      const double z = dx * dx + dy * dy;
      sx += dx, sy += dy, sxx += dx * dx, syy += dy * dy, sxy += dx * dy, sxz += dx * z, syz += dy * z,
          sz += z;
      ++n;
    }
  if (n < std::max(12.0, 0.5 * c.r)) return false;
  // x^2 + y^2 + a x + b y + k = 0 in the least-squares sense (Kasa).
  cv::Matx33d A(sxx, sxy, sx, sxy, syy, sy, sx, sy, n);
  cv::Vec3d rhs(-sxz, -syz, -sz), s;
  if (!cv::solve(A, rhs, s, cv::DECOMP_LU)) return false;
  const double cx = -0.5 * s[0], cy = -0.5 * s[1], r2 = cx * cx + cy * cy - s[2];
  if (!(r2 > 0) || std::hypot(cx, cy) > band) return false;
  c.x += cx, c.y += cy, c.r = std::sqrt(r2);
  return true;
}

// The centre and radius refined to a fraction of a pixel: least-squares circles (Kasa's) through the edge
// pixels near the found circle whose brightness grows outwards along the radius (the disk's own rim; a
// neighbour's rim or an outline's inner edge point otherwise), first within 0.3 r, then within 0.06 r (at
// least 1.5 px) of the first fit, which leaves out the far side of a wall the disk leans on.
void refine(Circle& c, const cv::Mat& edges, const cv::Mat& gx, const cv::Mat& gy) {
  Circle first = c;
  if (!fit_rim(first, 0.3 * c.r, edges, gx, gy) || std::fabs(first.r - c.r) > 0.25 * c.r) return;
  Circle second = first;
  if (fit_rim(second, std::max(1.5, 0.06 * c.r), edges, gx, gy) && std::fabs(second.r - c.r) <= 0.25 * c.r)
    c = second;
  else
    c = first;
  c.fitted = true;
}

// Grey levels (of the flattened picture's 230) below Otsu's threshold where the foreground starts.
constexpr double kGapMargin = 10;

}  // namespace

std::vector<Circle> detect_disks(const cv::Mat& image, const DetectOptions& opt) {
  double rmax = 0, rmin = INFINITY;
  for (double r : opt.radius_px) rmax = std::max(rmax, r), rmin = std::min(rmin, r);
  const cv::Mat flat = flatten(image, rmax);
  // The disks as foreground (darker than the even background: Otsu's threshold, less 10 of the background's
  // 230 grey levels), and each foreground pixel's distance to the background: it peaks at a disk's centre
  // with the disk's radius, touching disks meeting at narrow necks where it is small. The 10 levels keep a
  // blurred camera's grey gaps between touching disks and a wall in the background: at Otsu's own threshold
  // two small disks resting on a wall merged into one larger (three species at camera level 2: recall 0.985,
  // 0.995 with the margin; docs/lab.md).
  cv::Mat fg, dist;
  const double otsu = cv::threshold(flat, fg, 0, 255, cv::THRESH_BINARY_INV | cv::THRESH_OTSU);
  cv::threshold(flat, fg, otsu - kGapMargin, 255, cv::THRESH_BINARY_INV);
  cv::distanceTransform(fg, dist, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  cv::Mat peaks;
  const int k = 2 * std::max(1, static_cast<int>(0.6 * rmin)) + 1;
  cv::dilate(dist, peaks, cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(k, k)));
  cv::Mat edges, gx, gy;
  cv::Canny(flat, edges, 0.5 * opt.edge_threshold, opt.edge_threshold);
  if (!opt.ignore.empty() && opt.ignore.size() == edges.size()) edges.setTo(0, opt.ignore);
  cv::Sobel(flat, gx, CV_32F, 1, 0);
  cv::Sobel(flat, gy, CV_32F, 0, 1);
  // Candidates: local maxima whose height is a species' radius (within the band), tallest first.
  std::vector<Circle> cand;
  for (int y = 1; y + 1 < dist.rows; ++y) {
    const float* d = dist.ptr<float>(y);
    const float* p = peaks.ptr<float>(y);
    for (int x = 1; x + 1 < dist.cols; ++x) {
      if (d[x] < p[x] || d[x] < rmin * (1 - opt.band)) continue;
      const double r = d[x] + 0.5;  // the distance runs to the first background pixel's centre
      int band = -1;
      double best = INFINITY;
      for (size_t b = 0; b < opt.radius_px.size(); ++b) {
        const double e = std::fabs(r / opt.radius_px[b] - 1);
        if (e <= opt.band && e < best) best = e, band = static_cast<int>(b);
      }
      if (band < 0) continue;
      // Sub-pixel: the peak of a parabola through the 3 x 3 neighbourhood, along each axis.
      const double dxm = dist.at<float>(y, x - 1), dxp = dist.at<float>(y, x + 1);
      const double dym = dist.at<float>(y - 1, x), dyp = dist.at<float>(y + 1, x);
      const double ax = dxm - 2 * d[x] + dxp, ay = dym - 2 * d[x] + dyp;
      const double sx = ax < 0 ? std::clamp(0.5 * (dxm - dxp) / ax, -0.5, 0.5) : 0.0;
      const double sy = ay < 0 ? std::clamp(0.5 * (dym - dyp) / ay, -0.5, 0.5) : 0.0;
      cand.push_back({x + sx, y + sy, opt.radius_px[static_cast<size_t>(band)], band});
      cand.back().score = d[x];
    }
  }
  std::sort(cand.begin(), cand.end(), [](const Circle& a, const Circle& b) { return a.score > b.score; });
  // One disk per peak: a candidate whose centre lies inside a disk already kept (a plateau, or a small disk's
  // picture inside a large one) is the same disk.
  std::vector<Circle> out;
  for (Circle c : cand) {
    bool inside = false;
    for (const Circle& o : out)
      if (std::hypot(o.x - c.x, o.y - c.y) < 0.8 * std::max(o.r, c.r)) {
        inside = true;
        break;
      }
    if (inside) continue;
    refine(c, edges, gx, gy);
    out.push_back(c);
  }
  return out;
}

cv::Mat add_camera(const cv::Mat& clean, double level, std::uint64_t seed) {
  if (level <= 0) return clean.clone();
  cv::Mat img;
  clean.convertTo(img, CV_32FC3);
  const int w = img.cols, h = img.rows;
  // Perspective: the corners moved inwards or outwards by up to 0.1 L % of the width.
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  const double m = 0.001 * level * w;
  cv::Point2f src[4] = {{0, 0}, {float(w), 0}, {float(w), float(h)}, {0, float(h)}};
  cv::Point2f dst[4];
  for (int k = 0; k < 4; ++k) dst[k] = {src[k].x + float(m * u(rng)), src[k].y + float(m * u(rng))};
  cv::warpPerspective(img, img, cv::getPerspectiveTransform(src, dst), img.size(), cv::INTER_LINEAR,
                      cv::BORDER_REPLICATE);
  cv::GaussianBlur(img, img, cv::Size(), 0.6 * level);
  // Light falling off across the picture.
  cv::Mat light(h, w, CV_32FC3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float f = static_cast<float>(1.0 - 0.12 * level * (0.6 * x / w + 0.4 * y / h));
      light.at<cv::Vec3f>(y, x) = {f, f, f};
    }
  cv::multiply(img, light, img);
  cv::Mat noise(img.size(), CV_32FC3);
  cv::RNG cvrng(seed ^ 0x9e3779b97f4a7c15ULL);
  cvrng.fill(noise, cv::RNG::NORMAL, 0, 6.0 * level);
  img += noise;
  cv::Mat out;
  img.convertTo(out, CV_8UC3);
  return out;
}

struct FrameSource::Impl {
  std::unique_ptr<VideoReader> video;
  std::vector<std::filesystem::path> files;
  size_t next = 0;
  std::string path;
  // A multi-page TIFF: its pages read a few at a time (a stack can be larger than memory).
  size_t pages = 0;
  std::vector<cv::Mat> chunk;
  size_t chunk_start = 0;
};

namespace {
bool tiff_name(const std::filesystem::path& p) {
  const std::string ext = core::lower_extension(p.string());
  return ext == ".tif" || ext == ".tiff";
}
}  // namespace

std::vector<std::filesystem::path> pictures_in(const std::filesystem::path& dir) {
  std::vector<std::filesystem::path> files;
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(dir, ec)) {
    const std::string ext = core::lower_extension(e.path().string());
    if (ext == ".png" || ext == ".jpg" || ext == ".jpeg" || ext == ".bmp" || ext == ".tif" || ext == ".tiff")
      files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

FrameSource::FrameSource(const std::string& path) {
  codecs();  // the readers' module loaded (or its absence said) before anything is held
  impl_ = new Impl;
  namespace fs = std::filesystem;
  impl_->path = path;
  std::error_code ec;
  if (!fs::exists(path, ec)) {
    delete impl_;
    throw core::InputError(path + ": no such file or directory (a video, or a directory of frames)");
  }
  if (fs::is_directory(path, ec)) {
    impl_->files = pictures_in(path);
    if (impl_->files.empty()) {
      delete impl_;
      throw core::InputError(path + ": a directory with no frames (PNG, JPEG, BMP or TIFF files)");
    }
    count_ = static_cast<long>(impl_->files.size());
    const cv::Mat first = codecs().read_picture(impl_->files.front().string(), cv::IMREAD_COLOR);
    if (first.empty()) {
      const std::string f = impl_->files.front().string();
      delete impl_;
      throw core::InputError(f + ": cannot be decoded as an image");
    }
    width_ = first.cols, height_ = first.rows;
    return;
  }
  if (tiff_name(path)) {  // a stack of frames in one TIFF, or a single picture
    impl_->pages = codecs().count_pages(path);
    if (impl_->pages == 0 || !codecs().read_pages(path, 0, 1, impl_->chunk)) {
      delete impl_;
      throw core::InputError(path + ": cannot be decoded as a TIFF image or stack");
    }
    count_ = static_cast<long>(impl_->pages);
    width_ = impl_->chunk.front().cols, height_ = impl_->chunk.front().rows;
    impl_->chunk.clear();
    return;
  }
  // FFmpeg and OpenCV would print their own lines about a file they cannot read; the error below says it
  // once. (OpenCV sets FFmpeg's level when its backend starts, from OPENCV_FFMPEG_LOGLEVEL: -8 is
  // AV_LOG_QUIET.)
  setenv("OPENCV_FFMPEG_LOGLEVEL", "-8", 0);
  av_log_set_level(AV_LOG_QUIET);
  cv::utils::logging::setLogLevel(cv::utils::logging::LOG_LEVEL_SILENT);
  impl_->video = codecs().open_video(path);
  if (!impl_->video) {
    delete impl_;
    throw core::InputError(path +
                           ": cannot be decoded as a video (FFmpeg found no video stream it can read)");
  }
  fps_ = impl_->video->fps;
  count_ = impl_->video->count;
  width_ = impl_->video->width;
  height_ = impl_->video->height;
  if (width_ <= 0 || height_ <= 0) {
    delete impl_;
    throw core::InputError(path + ": cannot be decoded as a video (no frame size)");
  }
}

FrameSource::~FrameSource() {
  delete impl_;
}

bool FrameSource::next(cv::Mat& frame) {
  if (!impl_->files.empty()) {
    if (impl_->next >= impl_->files.size()) return false;
    const std::string f = impl_->files[impl_->next++].string();
    frame = codecs().read_picture(f, cv::IMREAD_COLOR);
    if (frame.empty()) throw core::InputError(f + ": cannot be decoded as an image");
    if (frame.cols != width_ || frame.rows != height_)
      throw core::InputError(f + ": " + std::to_string(frame.cols) + "x" + std::to_string(frame.rows) +
                             " where the first frame is " + std::to_string(width_) + "x" +
                             std::to_string(height_));
    return true;
  }
  if (impl_->pages > 0) {
    if (impl_->next >= impl_->pages) return false;
    if (impl_->next >= impl_->chunk_start + impl_->chunk.size()) {
      impl_->chunk.clear();
      impl_->chunk_start = impl_->next;
      const int n = static_cast<int>(std::min<size_t>(32, impl_->pages - impl_->next));
      if (!codecs().read_pages(impl_->path, static_cast<int>(impl_->next), n, impl_->chunk))
        throw core::InputError(impl_->path + ": page " + std::to_string(impl_->next) + " of " +
                               std::to_string(impl_->pages) + " cannot be decoded");
    }
    frame = impl_->chunk[impl_->next - impl_->chunk_start];
    ++impl_->next;
    if (frame.cols != width_ || frame.rows != height_)
      throw core::InputError(impl_->path + ": page " + std::to_string(impl_->next - 1) + " is " +
                             std::to_string(frame.cols) + "x" + std::to_string(frame.rows) +
                             " where the first is " + std::to_string(width_) + "x" + std::to_string(height_));
    return true;
  }
  if (impl_->video->read(frame)) {
    ++read_;
    return true;
  }
  exhausted_ = true;
  return false;
}

}  // namespace vision
