// Camera frames to tracked particles (app/services/lab.h).
#include "app/services/lab.h"

#include <chrono>
#include <cmath>
#include <complex>
#include <deque>
#include <future>
#include <random>

#ifdef __GLIBC__
#include <malloc.h>
#endif

#include <toml++/toml.h>

#include <opencv2/imgproc.hpp>

#include "core/error.h"
#include "core/format.h"
#include "io/run.h"
#include "render/camera.h"

namespace app {

namespace fs = std::filesystem;

bool movie_calibration(const fs::path& input, Calibration& cal, core::Model& model, std::string& why) {
  fs::path dir;
  for (const fs::path& candidate : {fs::path(input).replace_extension(""), input.parent_path()})
    if (fs::is_regular_file(candidate / io::run_file::kMetadata)) {
      dir = candidate;
      break;
    }
  if (dir.empty()) {
    why = "no recording's metadata.toml beside it";
    return false;
  }
  const fs::path meta = dir / io::run_file::kMetadata;
  const io::Run run = io::Run::open(dir, "detect");
  const toml::table& t = run.metadata();
  const auto size = t["run"]["size"].value<std::string>();
  const auto camera = t["run"]["camera"].value<std::string>();
  const auto interval = t["run"]["frame_interval_s"].value<double>();
  if (!size || !camera || !interval || !(*interval > 0)) {
    why = meta.string() + " is not a recording's metadata (no [run] size, camera and frame_interval_s)";
    return false;
  }
  if (!t["run"]["camera_path"].value_or(std::string()).empty() ||
      !t["run"]["freeze"].value_or(std::string()).empty() || t["run"]["slowmo_frames"].value_or(0) != 0) {
    why = "its camera moves or its clock stops (a camera path, slow motion or freezes)";
    return false;
  }
  model = run.model();
  int w = 0, h = 0;
  render::parse_size(*size, "size", w, h);
  const render::CameraSpec spec = render::parse_camera(*camera);
  const std::vector<render::View> views = render::layout_views(spec, model.setup.geo, w, h);
  if (views.size() != 1) {
    why = "its camera '" + *camera + "' has " + std::to_string(views.size()) +
          " panels (film with one, e.g. --camera hopper or a window)";
    return false;
  }
  if (views[0].cam.angle != 0) {
    why = "its camera is turned (a tilted container): give --scale and --origin in the turned picture";
    return false;
  }
  const core::Vec2 o = views[0].world_to_pixel({0, 0});
  cal.scale = 1.0 / views[0].px_per_m();
  cal.origin_x = o.x - 0.5;  // OpenCV's pixel centres sit at whole numbers
  cal.origin_y = o.y - 0.5;
  cal.fps = 1.0 / *interval;
  cal.from = meta.string();
  return true;
}

double rotation_radians(double degrees) {
  if (!(std::fabs(degrees) <= 45))
    throw core::InputError(
        "--rotation " + core::format_g(degrees) +
        ": expected -45 to 45 degrees (the container turned counter-clockwise in the picture)");
  return degrees * M_PI / 180;
}

core::Vec2 Calibration::to_metres(double px, double py) const {
  const core::Vec2 up{(px - origin_x) * scale, (origin_y - py) * scale};  // the picture's axes, y up, in m
  if (rotation == 0) return up;
  const double c = std::cos(rotation), s = std::sin(rotation);
  return {c * up.x + s * up.y, -s * up.x + c * up.y};
}

core::Vec2 Calibration::to_pixels(core::Vec2 m) const {
  if (rotation != 0) {
    const double c = std::cos(rotation), s = std::sin(rotation);
    m = {c * m.x - s * m.y, s * m.x + c * m.y};
  }
  return {origin_x + m.x / scale, origin_y - m.y / scale};
}

Calibration points_calibration(const std::string& text, const std::string& option, const vision::Lens& lens) {
  auto fail = [&]() -> Calibration {
    throw core::InputError(option + " '" + text +
                           "': expected PX,PY=X,Y:PX,PY=X,Y[:...] (two or more pixels and where they are in "
                           "metres, the outlet's centre at 0,0)");
  };
  std::vector<double> v;
  std::string cur;
  for (size_t i = 0; i <= text.size(); ++i) {
    const char ch = i < text.size() ? text[i] : ':';
    if (ch == ',' || ch == '=' || ch == ':') {
      char* end = nullptr;
      if (cur.empty()) return fail();
      v.push_back(std::strtod(cur.c_str(), &end));
      if (*end != '\0' || !std::isfinite(v.back())) return fail();
      cur.clear();
    } else {
      cur += ch;
    }
  }
  if (v.size() % 4 != 0 || v.size() < 8) return fail();
  // Least squares in the complex plane: pixel (y up) = a metres + b, a = e^(i rotation) / scale.
  using C = std::complex<double>;
  const size_t n = v.size() / 4;
  std::vector<C> u(n), w(n);
  C ub = 0, wb = 0;
  for (size_t k = 0; k < n; ++k) {
    const cv::Point2d p = lens.ideal({v[4 * k], v[4 * k + 1]});  // marked on the film: through its lens
    u[k] = {p.x, -p.y};
    w[k] = {v[4 * k + 2], v[4 * k + 3]};
    ub += u[k] / static_cast<double>(n), wb += w[k] / static_cast<double>(n);
  }
  C num = 0;
  double den = 0, spread_px = 0;
  for (size_t k = 0; k < n; ++k) {
    num += (u[k] - ub) * std::conj(w[k] - wb);
    den += std::norm(w[k] - wb);
    spread_px += std::norm(u[k] - ub);
  }
  if (!(den > 0) || !(spread_px > 0))
    throw core::InputError(option + " '" + text + "': the points must differ (in pixels and in metres)");
  const C a = num / den, b = ub - a * wb;
  Calibration c;
  c.scale = 1 / std::abs(a);
  c.rotation = std::arg(a);
  if (std::fabs(c.rotation) < 1e-12) c.rotation = 0;  // points marked along the picture's axes
  c.origin_x = b.real();
  c.origin_y = -b.imag();
  double sum = 0;
  for (size_t k = 0; k < n; ++k) sum += std::norm((u[k] - b) / a - w[k]);
  c.residual = std::sqrt(sum / static_cast<double>(n));
  c.from = std::to_string(n) + " marked points";
  return c;
}

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
  vision::Linker linker(job.max_step, job.memory);
  std::mt19937_64 rng(job.seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::string csv = "frame,particle,x,y,r,t,species\n";
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
      csv += std::to_string(k) + "," + std::to_string(ids[i]) + "," + core::format_g(c.x, 7) + "," +
             core::format_g(c.y, 7) + "," + core::format_g(c.r, 5) + "," + core::format_g(t, 9) + "," +
             names[static_cast<size_t>(c.band)] + "\n";
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
  stats.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  stats.tracks = linker.tracks();
  stats.bright = bright;
  return csv;
}

}  // namespace app
