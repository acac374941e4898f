// Camera frames to tracked particles (app/services/lab.h).
#include "app/services/lab.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <future>
#include <random>

#ifdef __GLIBC__
#include <malloc.h>
#endif

#include <opencv2/imgproc.hpp>

#include "core/error.h"
#include "core/format.h"
#include "lab/size_species.h"
#include "vision/linker.h"

namespace app {

namespace fs = std::filesystem;

namespace {

// Where grains can be, in pixels: the container's width (and a diameter beyond each side, the slack of the
// filter below) from above its top to the picture's bottom, where exited grains fall; with room for a disk
// and the background's estimate around it. Its left and top edges on multiples of 4, so the background's
// quarter-size copy sees the same blocks as on the whole picture.
cv::Rect grain_region(const core::Geometry& geo, const Calibration& cal, const vision::Lens& lens,
                      double rmax, int width, int height) {
  // The container's corners in pixels; below them, falling grains drift sideways as the picture is turned.
  double left = INFINITY, right = -INFINITY, top = INFINITY;
  for (int i = 0; i <= 8; ++i)  // along its outline: a lens bends the sides
    for (int j = 0; j <= 8; ++j) {
      if (i % 8 && j % 8) continue;
      const double x = i == 8 ? geo.x_right : geo.x_left + i * (geo.x_right - geo.x_left) / 8;
      const double y = j == 8 ? geo.total_height : j * geo.total_height / 8;
      const core::Vec2 q = cal.to_pixels({x, y});
      const cv::Point2d p = lens.raw({q.x, q.y});
      left = std::min(left, p.x), right = std::max(right, p.x), top = std::min(top, p.y);
    }
  const double slack_px = 2 * rmax + 2 * 1.25 * rmax + 8 + std::fabs(std::tan(cal.rotation)) * height;
  const int x0 = std::max(0, static_cast<int>(std::floor(left - slack_px)) & ~3);
  const int x1 = std::min(width, static_cast<int>(std::ceil(right + slack_px)));
  const int y0 = std::max(0, static_cast<int>(std::floor(top - slack_px)) & ~3);
  if (x1 - x0 < 8 || height - y0 < 8)
    return cv::Rect(0, 0, width, height);  // off the picture: look everywhere
  return cv::Rect(x0, y0, x1 - x0, height - y0);
}

// The walls' pixels (and the obstacle's rim): their edges are not a disk's rim. As wide as 0.8 of the
// largest radius, from the geometry and the calibration. A turned camera or a lens's distortion: the outlines
// drawn through points along them (a straight wall is curved on the film).
cv::Mat wall_mask(const core::Geometry& geo, const Calibration& cal, const vision::Lens& lens, double rmax,
                  int width, int height) {
  cv::Mat ignore = cv::Mat::zeros(height, width, CV_8U);
  auto px = [&](core::Vec2 p) {
    const core::Vec2 q = cal.to_pixels(p);
    const cv::Point2d r = lens.raw({q.x, q.y});
    return cv::Point(static_cast<int>(std::lround(r.x)), static_cast<int>(std::lround(r.y)));
  };
  const int thick = std::max(3, static_cast<int>(std::lround(0.8 * rmax)));
  const core::Obstacle& ob = geo.obstacle;
  if (cal.rotation == 0 && !lens.present) {
    for (core::Wall w :
         {core::Wall::HopperLeft, core::Wall::HopperRight, core::Wall::SiloLeft, core::Wall::SiloRight})
      cv::line(ignore, px(geo.walls[static_cast<size_t>(w)].a), px(geo.walls[static_cast<size_t>(w)].b), 255,
               thick);
    // The obstacle whole, its rim and inside: no grain is there, and its own shading is no disk's.
    for (int fill : {thick, -1})
      if (ob.kind == core::Obstacle::Kind::Disk)
        cv::circle(ignore, px(ob.centre), static_cast<int>(std::lround(0.5 * ob.width / cal.scale)), 255,
                   fill);
      else if (ob.kind == core::Obstacle::Kind::Bar)
        cv::rectangle(ignore, px({ob.centre.x - 0.5 * ob.width, ob.centre.y + 0.5 * ob.height}),
                      px({ob.centre.x + 0.5 * ob.width, ob.centre.y - 0.5 * ob.height}), 255, fill);
    return ignore;
  }
  auto along = [&](core::Vec2 a, core::Vec2 b, std::vector<cv::Point>& out) {
    for (int k = 0; k < 16; ++k) out.push_back(px(a + (static_cast<double>(k) / 16) * (b - a)));
  };
  for (core::Wall w :
       {core::Wall::HopperLeft, core::Wall::HopperRight, core::Wall::SiloLeft, core::Wall::SiloRight}) {
    std::vector<cv::Point> line;
    along(geo.walls[static_cast<size_t>(w)].a, geo.walls[static_cast<size_t>(w)].b, line);
    line.push_back(px(geo.walls[static_cast<size_t>(w)].b));
    cv::polylines(ignore, line, false, 255, thick);
  }
  std::vector<cv::Point> outline;
  if (ob.kind == core::Obstacle::Kind::Disk)
    for (int k = 0; k < 64; ++k)
      outline.push_back(
          px(ob.centre + 0.5 * ob.width * core::Vec2{std::cos(k * M_PI / 32), std::sin(k * M_PI / 32)}));
  else if (ob.kind == core::Obstacle::Kind::Bar) {
    const double hw = 0.5 * ob.width, hh = 0.5 * ob.height;
    const core::Vec2 c[4] = {ob.centre + core::Vec2{-hw, -hh}, ob.centre + core::Vec2{hw, -hh},
                             ob.centre + core::Vec2{hw, hh}, ob.centre + core::Vec2{-hw, hh}};
    for (int k = 0; k < 4; ++k) along(c[k], c[(k + 1) % 4], outline);
  }
  if (!outline.empty()) {
    cv::fillPoly(ignore, std::vector<std::vector<cv::Point>>{outline}, 255);
    cv::polylines(ignore, outline, true, 255, thick);
  }
  return ignore;
}

// One frame's disks, in ideal pixels: the camera's effects (the round trip's), the polarity, then detection
// inside `region` only, the centres carried through the lens.
std::vector<vision::Circle> detect_frame(cv::Mat frame, long k, const DetectJob& job, bool bright,
                                         const vision::DetectOptions& detect, const cv::Rect& region) {
  cv::Mat picture = job.camera ? job.camera(frame, k) : frame;
  cv::Mat inside = picture(region);
  if (bright) cv::bitwise_not(inside, inside);
  std::vector<vision::Circle> found = vision::detect_disks(inside, detect);
  // A disk cut by the picture's edge by more than a fifth of its radius is not kept: its centre cannot be
  // told (the distance to the background peaks towards the edge; a small disk at the top of the three
  // species' film was found 6 px off its centre in every frame), as trackpy leaves out features at the edge.
  std::vector<vision::Circle> whole;
  for (vision::Circle& c : found) {
    c.x += region.x, c.y += region.y;
    const double m = 0.8 * c.r;
    if (c.x >= m && c.y >= m && c.x <= picture.cols - 1 - m && c.y <= picture.rows - 1 - m)
      whole.push_back(c);
  }
  found = std::move(whole);
  if (job.lens.present) {
    std::vector<cv::Point2d> at;
    for (const vision::Circle& c : found) at.emplace_back(c.x, c.y);
    job.lens.ideal(at);
    for (size_t i = 0; i < found.size(); ++i) found[i].x = at[i].x, found[i].y = at[i].y;
  }
  return found;
}

// The CSV's text: the header, then each row (ending in a comma) completed by its track's species.
std::string with_species(const std::string& rows, const std::vector<long>& row_track,
                         const std::vector<int>& species, const std::vector<std::string>& names) {
  std::string csv = "frame,particle,x,y,r,t,species\n";
  csv.reserve(csv.size() + rows.size() + 16 * row_track.size());
  size_t from = 0;
  for (long id : row_track) {
    const size_t end = rows.find('\n', from);
    csv.append(rows, from, end - from);
    csv += names[static_cast<size_t>(species[static_cast<size_t>(id)])];
    csv += '\n';
    from = end + 1;
  }
  return csv;
}

}  // namespace

Rectifier::Rectifier(const Calibration& cal, const vision::Lens& lens, int width, int height) {
  upright_ = cal;
  upright_.rotation = 0;
  upright_.residual = 0;
  upright_.from = "rectified (" + cal.from + ")";
  cv::Mat mx(height + (height & 1), width + (width & 1), CV_32F), my(mx.size(), CV_32F);
  for (int v = 0; v < mx.rows; ++v)
    for (int u = 0; u < mx.cols; ++u) {
      const core::Vec2 ideal = cal.to_pixels(upright_.to_metres(u, v));
      const cv::Point2d raw = lens.raw({ideal.x, ideal.y});
      mx.at<float>(v, u) = static_cast<float>(raw.x);
      my.at<float>(v, u) = static_cast<float>(raw.y);
    }
  cv::convertMaps(mx, my, map_, map_fraction_, CV_16SC2);
}

void Rectifier::apply(const cv::Mat& frame, core::Image& out) const {
  cv::Mat bgr = frame;
  if (frame.channels() == 1) cv::cvtColor(frame, bgr, cv::COLOR_GRAY2BGR);
  if (frame.channels() == 4) cv::cvtColor(frame, bgr, cv::COLOR_BGRA2BGR);
  cv::Mat upright;
  cv::remap(bgr, upright, map_, map_fraction_, cv::INTER_LINEAR, cv::BORDER_CONSTANT, cv::Scalar(0, 0, 0));
  out.width = upright.cols, out.height = upright.rows;
  out.rgba.resize(static_cast<size_t>(upright.cols) * static_cast<size_t>(upright.rows) * 4);
  cv::Mat rgba(upright.rows, upright.cols, CV_8UC4, out.rgba.data());
  cv::cvtColor(upright, rgba, cv::COLOR_BGR2RGBA);
}

std::string detect_tracks(vision::FrameSource& source, const DetectJob& job, const core::Model& model,
                          DetectStats& stats) {
  const core::Geometry& geo = model.setup.geo;
  const std::vector<std::string> names = model.setup.species_names();
  vision::Linker linker(job.max_step, job.memory, job.detect.band);
  std::mt19937_64 rng(job.seed);
  std::uniform_real_distribution<double> u(0, 1);
  // The rows without their species, which each track takes at the end from the median of its radii (one
  // frame's radius of a disk pressed among others can read a species' band off; the median of a track's does
  // not, and a track keeps one species).
  std::string rows;
  std::vector<long> row_track;
  lab::TrackSizes radii;
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
#ifdef __GLIBC__
  // Each frame's pictures (a few MB each) from the allocator's own free memory: by default glibc maps every
  // block over 128 kB afresh and returns it when freed, and the kernel's page faults on every new map then
  // took two thirds of detect's time (the tracks are the same either way).
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
  mallopt(M_TRIM_THRESHOLD, 256 << 20);
#endif
  double rmax = 0;
  for (double r : job.detect.radius_px) rmax = std::max(rmax, r);
  cv::Rect region(0, 0, source.width(), source.height());
  vision::DetectOptions detect = job.detect;
  if (source.width() > 0) {
    region = grain_region(geo, job.cal, job.lens, rmax, source.width(), source.height());
    if (detect.ignore.empty())
      detect.ignore = wall_mask(geo, job.cal, job.lens, rmax, source.width(), source.height());
    detect.ignore = detect.ignore(region).clone();
  }
  bool bright = job.bright;
  bool polarity_known = job.bright_given;
  // Frames decoded here while up to kAhead are detected on other threads; linked in their order.
  constexpr size_t kAhead = 3;
  std::deque<std::pair<long, std::future<std::vector<vision::Circle>>>> pending;
  auto link_next = [&] {
    const long k = pending.front().first;
    const std::vector<vision::Circle> found = pending.front().second.get();
    pending.pop_front();
    std::vector<vision::Circle> kept;
    for (const vision::Circle& c : found) {
      if (job.drop > 0 && u(rng) < job.drop) continue;
      const core::Vec2 p = job.cal.to_metres(c.x, c.y);
      const double slack = 2 * c.r * job.cal.scale;
      // A centre inside the obstacle (by more than half a radius) is its own shading, not a grain.
      const bool in_obstacle = geo.obstacle.present() && geo.obstacle.gap(p) < -0.5 * c.r * job.cal.scale;
      if (p.y > geo.total_height + slack || p.x < geo.x_left - slack || p.x > geo.x_right + slack ||
          (p.y >= slack && geo.side_clearance(p, 0) < -slack) || in_obstacle) {
        ++stats.dropped_outside;
        continue;
      }
      kept.push_back(c);
    }
    const std::vector<long> ids = linker.link(kept);
    const double t = job.cal.fps > 0 ? static_cast<double>(k) / job.cal.fps : static_cast<double>(k);
    for (size_t i = 0; i < kept.size(); ++i) {
      const vision::Circle& c = kept[i];
      rows += std::to_string(k) + "," + std::to_string(ids[i]) + "," + core::format_g(c.x, 7) + "," +
              core::format_g(c.y, 7) + "," + core::format_g(c.r, 5) + "," + core::format_g(t, 9) + ",\n";
      row_track.push_back(ids[i]);
      radii.add(ids[i], c.r, c.fitted);
    }
    stats.detections += static_cast<long>(kept.size());
    ++stats.frames;
    if (job.progress) job.progress(k);
  };
  for (long k = 0;; ++k) {
    cv::Mat frame;  // a fresh buffer each frame: the one before may still be read by a detection
    if (!source.next(frame)) break;
    if (k < job.first) continue;
    if (job.last >= 0 && k > job.last) break;
    if (job.on_frame) job.on_frame(frame, k);
    if (!polarity_known) {
      cv::Mat picture = job.camera ? job.camera(frame, k) : frame, inverted;
      cv::bitwise_not(picture(region), inverted);
      stats.first_as_dark = static_cast<long>(vision::detect_disks(picture(region), detect).size());
      stats.first_as_bright = static_cast<long>(vision::detect_disks(inverted, detect).size());
      bright = stats.first_as_bright >= 10 && 10 * stats.first_as_bright > 11 * stats.first_as_dark;
      polarity_known = true;
    }
    pending.emplace_back(k, std::async(std::launch::async, detect_frame, frame, k, std::cref(job), bright,
                                       std::cref(detect), region));
    if (pending.size() > kAhead) link_next();
  }
  while (!pending.empty()) link_next();
  // Each track's species: the likeliest for the median of its radii, the scale and the sizes' spread refined
  // on the tracks near a species of one fixed size.
  const std::vector<int> species = radii.species(model.setup.species, -std::log(job.cal.scale),
                                                 &stats.size_spread, &stats.size_error_rate);
  stats.species = static_cast<long>(model.setup.species.size());
  const std::string csv = with_species(rows, row_track, species, names);
  stats.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  stats.tracks = linker.tracks();
  stats.bright = bright;
  return csv;
}

}  // namespace app
