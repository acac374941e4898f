// Cameras (render/camera.h): the presets and windows, their views laid out in a picture, camera paths with
// their glides, subjects followed, and freezes. Over 400 lines because every picture maker (record, the
// inspector, frame) asks the same one question of them, where each view looks now, and the glide's rule that
// keeps the next subject in the picture needs the views, the paths and the subjects together.
#include "render/camera.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "core/error.h"
#include "core/format.h"

namespace render {

core::Vec2 View::world_to_pixel(core::Vec2 p) const {
  const double s = px_per_m(), c = std::cos(cam.angle), n = std::sin(cam.angle);
  const double dx = p.x - cam.cx, dy = p.y - cam.cy;
  const double rx = c * dx - n * dy, ry = n * dx + c * dy;  // turned by the camera's angle
  return {rect.x + 0.5 * rect.w + rx * s, rect.y + 0.5 * rect.h - ry * s};
}

core::Vec2 View::pixel_to_world(core::Vec2 px) const {
  const double s = px_per_m(), c = std::cos(cam.angle), n = std::sin(cam.angle);
  const double rx = (px.x - rect.x - 0.5 * rect.w) / s, ry = -(px.y - rect.y - 0.5 * rect.h) / s;
  return {cam.cx + c * rx + n * ry, cam.cy - n * rx + c * ry};
}

std::array<float, 9> View::world_to_clip() const {
  const double sy = 2.0 / cam.height, sx = sy * rect.h / rect.w;
  const double c = std::cos(cam.angle), n = std::sin(cam.angle);
  // clip = S R (p - c): column-major.
  return {static_cast<float>(sx * c),
          static_cast<float>(sy * n),
          0,
          static_cast<float>(-sx * n),
          static_cast<float>(sy * c),
          0,
          static_cast<float>(-sx * (c * cam.cx - n * cam.cy)),
          static_cast<float>(-sy * (n * cam.cx + c * cam.cy)),
          1};
}

void parse_size(const std::string& text, const std::string& option, int& w, int& h, int min_w, int min_h) {
  char x = 0, extra = 0;
  if (std::sscanf(text.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || x != 'x' || w < min_w || h < min_h)
    throw core::InputError(option + " " + text + ": expected WIDTHxHEIGHT in pixels, at least " +
                           std::to_string(min_w) + "x" + std::to_string(min_h) + ", e.g. 1920x1080");
}

Camera fit(double x0, double y0, double x1, double y1, int w, int h, double angle) {
  Camera c;
  c.cx = 0.5 * (x0 + x1);
  c.cy = 0.5 * (y0 + y1);
  c.angle = angle;
  const double aspect = static_cast<double>(w) / h;
  // The window's extent on screen once turned.
  const double ca = std::abs(std::cos(angle)), sa = std::abs(std::sin(angle));
  const double ex = ca * (x1 - x0) + sa * (y1 - y0), ey = sa * (x1 - x0) + ca * (y1 - y0);
  c.height = std::max(ey, ex / aspect);
  return c;
}

core::Vec2 SubjectTrack::at(double time) const {
  if (t.empty()) return {0, 0};
  if (time <= t.front()) return {x.front(), y.front()};
  if (time >= t.back()) return {x.back(), y.back()};
  const size_t k = static_cast<size_t>(std::upper_bound(t.begin(), t.end(), time) - t.begin());
  const double u = (time - t[k - 1]) / (t[k] - t[k - 1]);
  return {x[k - 1] + u * (x[k] - x[k - 1]), y[k - 1] + u * (y[k] - y[k - 1])};
}

int hold_through_jumps(SubjectTrack& track, double jump, double hold, double glide) {
  const SubjectTrack seen = track;  // where the grain was: the glides aim at it
  int jumps = 0;
  for (size_t j = 1; j < seen.t.size(); ++j) {
    if (std::hypot(seen.x[j] - seen.x[j - 1], seen.y[j] - seen.y[j - 1]) <= jump) continue;
    ++jumps;
    const double t0 = seen.t[j - 1], x0 = seen.x[j - 1], y0 = seen.y[j - 1];
    size_t k = j;
    for (; k < seen.t.size() && seen.t[k] <= t0 + hold + glide; ++k) {
      const double u = std::clamp((seen.t[k] - t0 - hold) / glide, 0.0, 1.0);
      const double w = u * u * (3 - 2 * u);
      track.x[k] = x0 + w * (seen.x[k] - x0);
      track.y[k] = y0 + w * (seen.y[k] - y0);
    }
    j = k - 1;  // a jump within the hold or glide is part of this one; the next pair is (k - 1, k)
  }
  return jumps;
}

namespace {
const char* kCameraForms = "hopper, outlet, split or window:X0,Y0,X1,Y1 (metres, X1 > X0, Y1 > Y0)";
const char* kSubjectForms =
    "hopper, outlet, split, window:X0,Y0,X1,Y1 (metres, X1 > X0, Y1 > Y0), arch:K (the K-th clog's arch, K "
    ">= "
    "1) or grain:ID (a grain followed, ID >= 0)";
// A whole number of at most 9 digits, else -1.
long whole(const std::string& s) {
  if (s.empty() || s.size() > 9 || s.find_first_not_of("0123456789") != std::string::npos) return -1;
  return std::stol(s);
}
}  // namespace

CameraSpec parse_camera(const std::string& spec, bool with_subjects) {
  CameraSpec c;
  c.text = spec;
  for (const char* name : {"arch:", "grain:"}) {
    const std::string prefix = name;
    if (spec.rfind(prefix, 0) != 0) continue;
    if (!with_subjects)
      throw core::InputError(
          "camera '" + spec +
          "': arch:K and grain:ID are known only by simulating ahead, which `record` does; "
          "here use " +
          kCameraForms);
    const long v = whole(spec.substr(prefix.size()));
    const bool arch = prefix == "arch:";
    if (v < (arch ? 1 : 0))
      throw core::InputError("camera '" + spec + "': expected " +
                             (arch ? "arch:K with K a whole number >= 1 (the K-th clog, row K of clogs.csv)"
                                   : "grain:ID with ID a whole number >= 0 (as in the trajectory)"));
    c.kind = arch ? CameraSpec::Kind::Arch : CameraSpec::Kind::Grain;
    c.subject = static_cast<int>(v);
    return c;
  }
  if (spec == "hopper") {
    c.kind = CameraSpec::Kind::Hopper;
    return c;
  }
  if (spec == "outlet") {
    c.kind = CameraSpec::Kind::Outlet;
    return c;
  }
  if (spec == "split") {
    c.kind = CameraSpec::Kind::Split;
    return c;
  }
  if (spec.rfind("window:", 0) == 0) {
    std::stringstream ss(spec.substr(7));
    double v[4];
    char comma;
    bool ok =
        static_cast<bool>(ss >> v[0] >> comma >> v[1] >> comma >> v[2] >> comma >> v[3]) && ss.peek() == EOF;
    if (ok && std::isfinite(v[0]) && std::isfinite(v[3]) && v[2] > v[0] && v[3] > v[1]) {
      c.kind = CameraSpec::Kind::Window;
      c.x0 = v[0], c.y0 = v[1], c.x1 = v[2], c.y1 = v[3];
      return c;
    }
  }
  throw core::InputError("camera '" + spec + "': expected " + (with_subjects ? kSubjectForms : kCameraForms));
}

void frame_arch(CameraSpec& camera, const std::vector<core::Vec2>& centres, double max_radius,
                double grain_diameter) {
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  for (const auto& c : centres) {
    x0 = std::min(x0, c.x), x1 = std::max(x1, c.x);
    y0 = std::min(y0, c.y), y1 = std::max(y1, c.y);
  }
  const double pad = max_radius + 1.5 * grain_diameter;
  x0 -= pad, x1 += pad, y0 -= pad, y1 += pad;
  // Grown to six diameters mostly upwards: the grains the arch holds, more than the empty outlet below it.
  const double grow = std::max(0.0, 6 * grain_diameter - (y1 - y0));
  y0 -= 0.3 * grow, y1 += 0.7 * grow;
  camera.x0 = x0, camera.y0 = y0, camera.x1 = x1, camera.y1 = y1;
}

std::vector<View> layout_views(const CameraSpec& camera, const core::Geometry& geo, int w, int h, double t) {
  if (!camera.resolved())
    throw core::InputError("camera '" + camera.text +
                           "': its subject is found by simulating ahead, which has not been done here");
  const double margin = 0.04 * geo.total_height;
  const double tilt = geo.tilt;
  auto hopper = [&](Rect r) {
    return View{
        fit(geo.x_left - margin, -margin, geo.x_right + margin, geo.total_height + margin, r.w, r.h, tilt), r,
        "hopper"};
  };
  auto outlet = [&](Rect r) {
    // Ten original diameters tall: arches form up to ~5 diameters above the aperture; the grains falling out
    // below. Written in the paper's metres times the grain size over its 0.13 m (exactly 1 for the paper).
    const double k = geo.grain_diameter / 0.13, d = geo.grain_diameter;
    // A hopper: ten grains tall, at most 9.2 wide (the paper's whole hopper). A flat silo: as wide as the
    // container where it is at most 13 grains wide, else 13 grains and the outlet with 3 grains each side
    // (arches over a floor rest far out). Tall enough to show an obstacle whole.
    const double wide =
        geo.kind == core::ContainerKind::Flat ? std::max(6.5 * d, geo.half_aperture + 3 * d) : 0.6 * k;
    const double half = std::min(geo.half_width + 0.05 * k, wide);
    double top = std::min(1.05 * k, geo.total_height);
    if (geo.obstacle.present())
      top = std::max(top,
                     std::min(geo.total_height, geo.obstacle.centre.y + 0.5 * geo.obstacle.height + 0.5 * d));
    return View{fit(-half, -0.25 * k, half, top, r.w, r.h, tilt), r, "outlet"};
  };
  switch (camera.kind) {
    case CameraSpec::Kind::Hopper:
      return {hopper({0, 0, w, h})};
    case CameraSpec::Kind::Outlet:
      return {outlet({0, 0, w, h})};
    case CameraSpec::Kind::Split: {
      // The whole container needs only a narrow strip; the outlet view gets the rest (and room for the
      // panel).
      const double bw = geo.x_right - geo.x_left + 2 * margin, bh = geo.total_height + 2 * margin;
      const double ca = std::abs(std::cos(tilt)), sa = std::abs(std::sin(tilt));
      const double aspect = (ca * bw + sa * bh) / (sa * bw + ca * bh);
      const int left =
          std::clamp(static_cast<int>(std::lround(1.15 * aspect * h)), std::max(1, w / 10), w / 2);
      View out = outlet({left, 0, w - left, h});
      // The container a little left of centre, room for the panel on the right, as far as its left wall stays
      // in view (a container as wide as the view is not pushed out of it).
      const double k = geo.grain_diameter / 0.13;
      const double half_view = 0.5 * out.cam.height * (w - left) / h;
      const double half_box = std::min(geo.half_width + 0.05 * k, half_view);
      out.cam.cx += std::min(0.08 * out.cam.height * (w - left) / h, std::max(0.0, half_view - half_box));
      return {hopper({0, 0, left, h}), out};
    }
    case CameraSpec::Kind::Window:
      return {View{fit(camera.x0, camera.y0, camera.x1, camera.y1, w, h, geo.tilt), {0, 0, w, h}, "window"}};
    case CameraSpec::Kind::Arch:
      return {View{fit(camera.x0, camera.y0, camera.x1, camera.y1, w, h, geo.tilt), {0, 0, w, h}, "arch"}};
    case CameraSpec::Kind::Grain: {
      const core::Vec2 c = camera.track->at(t);
      const double half = 4 * geo.grain_diameter;
      return {
          View{fit(c.x - half, c.y - half, c.x + half, c.y + half, w, h, geo.tilt), {0, 0, w, h}, "grain"}};
    }
  }
  return {};
}

CameraPath subject_path(const CameraSpec& camera) {
  CameraPath path;
  if (!camera.names_subject()) return path;
  path.keys.push_back({0.0, camera});
  path.text = "0:" + camera.text;
  return path;
}

CameraPath parse_camera_path(const std::string& spec, bool with_subjects) {
  CameraPath path;
  path.text = spec;
  const std::string allowed =
      std::string(
          "expected T:CAMERA,T:CAMERA,... with times in seconds, increasing, and each camera hopper, "
          "outlet, window:X0,Y0,X1,Y1") +
      (with_subjects ? ", arch:K or grain:ID" : " (arch:K and grain:ID in record)");
  // Split at commas that start a new key (a window's own commas are followed by more numbers, not "T:").
  std::vector<std::string> items;
  std::string cur;
  std::stringstream ss(spec);
  for (std::string part; std::getline(ss, part, ',');) {
    const size_t colon = part.find(':');
    bool starts_key = false;
    if (colon != std::string::npos && colon > 0) {
      char* end = nullptr;
      const std::string head = part.substr(0, colon);  // alive while `end` points into it
      std::strtod(head.c_str(), &end);
      starts_key = *end == '\0';
    }
    if (starts_key || cur.empty()) {
      if (!cur.empty()) items.push_back(cur);
      cur = part;
    } else {
      cur += "," + part;
    }
  }
  if (!cur.empty()) items.push_back(cur);
  for (const auto& item : items) {
    const size_t colon = item.find(':');
    if (colon == std::string::npos || colon == 0)
      throw core::InputError("camera path '" + spec + "': key '" + item + "': " + allowed);
    char* end = nullptr;
    const std::string time = item.substr(0, colon);  // alive while `end` points into it
    const double t = std::strtod(time.c_str(), &end);
    if (*end != '\0' || !std::isfinite(t))
      throw core::InputError("camera path '" + spec + "': key '" + item + "': " + allowed);
    CameraSpec cam;
    try {
      cam = parse_camera(item.substr(colon + 1), with_subjects);
    } catch (const core::InputError& e) {
      throw core::InputError("camera path key '" + item + "': " + e.what());
    }
    if (cam.kind == CameraSpec::Kind::Split)
      throw core::InputError("camera path key '" + item +
                             "': split shows two views and a path moves one; use hopper, outlet or window");
    if (!path.keys.empty() && !(t > path.keys.back().t))
      throw core::InputError("camera path key '" + item + "': times must increase (the key before is at " +
                             core::format_g(path.keys.back().t, 6) + " s)");
    path.keys.push_back({t, cam});
  }
  if (path.keys.empty()) throw core::InputError("camera path '" + spec + "': " + allowed);
  return path;
}

namespace {
// The picture at s in [0, 1] between views a and b: a zoom at a steady rate (the height shown geometrically)
// about the one point that sits at the same place in both pictures, so every point inside both windows stays
// inside the picture throughout (its place in the picture moves monotonically from one to the other); a pan
// when the heights are equal.
View glide(View a, const View& b, double s) {
  const double ha = a.cam.height, hb = b.cam.height;
  if (std::fabs(hb - ha) <= 1e-9 * ha) {
    a.cam.cx += s * (b.cam.cx - a.cam.cx);
    a.cam.cy += s * (b.cam.cy - a.cam.cy);
    return a;
  }
  const double h = ha * std::pow(hb / ha, s);
  const double px = (a.cam.cx * hb - b.cam.cx * ha) / (hb - ha),
               py = (a.cam.cy * hb - b.cam.cy * ha) / (hb - ha);
  a.cam.cx = px + (a.cam.cx - px) * h / ha;
  a.cam.cy = py + (a.cam.cy - py) * h / ha;
  a.cam.height = h;
  return a;
}

// The part of the world a key is about (its subject), as a box in metres: the whole container, the outlet and
// the region of its arches, a window, an arch's window, a followed grain where it is at time t.
std::array<core::Vec2, 2> subject_box(const CameraSpec& c, const core::Geometry& geo, double t) {
  const double d = geo.grain_diameter;
  switch (c.kind) {
    case CameraSpec::Kind::Hopper:
    case CameraSpec::Kind::Split:
      return {core::Vec2{geo.x_left, 0}, core::Vec2{geo.x_right, geo.total_height}};
    case CameraSpec::Kind::Outlet:
      return {core::Vec2{-geo.half_aperture - d, 0}, core::Vec2{geo.half_aperture + d, 2 * d}};
    case CameraSpec::Kind::Window:
    case CameraSpec::Kind::Arch:
      return {core::Vec2{c.x0, c.y0}, core::Vec2{c.x1, c.y1}};
    case CameraSpec::Kind::Grain: {
      const core::Vec2 p = c.track->at(t);
      return {core::Vec2{p.x - d, p.y - d}, core::Vec2{p.x + d, p.y + d}};
    }
  }
  return {};
}

// Whether view v shows the box (its four corners; the world may be turned).
bool shows(const View& v, const std::array<core::Vec2, 2>& box) {
  return shows_disks(v, {box[0], {box[0].x, box[1].y}, {box[1].x, box[0].y}, box[1]}, {0, 0, 0, 0});
}

// The smallest view (a's size in pixels, its angle) that shows a's window and every point of `pts` (m).
View union_points(const View& a, const std::vector<core::Vec2>& pts) {
  double x0 = a.rect.x, x1 = a.rect.x + a.rect.w, y0 = a.rect.y, y1 = a.rect.y + a.rect.h;
  for (const core::Vec2& w : pts) {
    const core::Vec2 q = a.world_to_pixel(w);
    x0 = std::min(x0, q.x), x1 = std::max(x1, q.x), y0 = std::min(y0, q.y), y1 = std::max(y1, q.y);
  }
  View u = a;
  const core::Vec2 c = a.pixel_to_world({0.5 * (x0 + x1), 0.5 * (y0 + y1)});
  u.cam.cx = c.x, u.cam.cy = c.y;
  u.cam.height = a.cam.height * std::max((y1 - y0) / a.rect.h, (x1 - x0) / a.rect.w);
  return u;
}

// The smallest view (a's size in pixels, its angle) that shows both a's and b's windows.
View union_view(const View& a, const View& b) {
  std::vector<core::Vec2> corners;
  for (double px : {0.0, 1.0})
    for (double py : {0.0, 1.0})
      corners.push_back(b.pixel_to_world({b.rect.x + px * b.rect.w, b.rect.y + py * b.rect.h}));
  return union_points(a, corners);
}
}  // namespace

bool shows_disks(const View& v, const std::vector<core::Vec2>& centres, const std::vector<double>& radii) {
  for (size_t k = 0; k < centres.size(); ++k) {
    const core::Vec2 px = v.world_to_pixel(centres[k]);
    const double r = radii[k] * v.px_per_m();
    if (px.x - r < v.rect.x - 0.5 || px.x + r > v.rect.x + v.rect.w + 0.5 || px.y - r < v.rect.y - 0.5 ||
        px.y + r > v.rect.y + v.rect.h + 0.5)
      return false;
  }
  return true;
}

View widened_to_show(const View& v, const std::vector<core::Vec2>& centres, const std::vector<double>& radii,
                     double pad) {
  std::vector<core::Vec2> pts;
  for (size_t k = 0; k < centres.size(); ++k) {
    const double r = radii[k] + pad;
    for (double dx : {-r, r})
      for (double dy : {-r, r}) pts.push_back({centres[k].x + dx, centres[k].y + dy});
  }
  return union_points(v, pts);
}

View CameraPath::view_at(double t, const core::Geometry& geo, int w, int h) const {
  // A followed grain's key shows where the grain is now, in its glides too.
  auto at = [&](size_t k) { return layout_views(keys[k].camera, geo, w, h, t).front(); };
  if (t <= keys.front().t) return at(0);
  if (t >= keys.back().t) return at(keys.size() - 1);
  size_t k = 1;
  while (keys[k].t < t) ++k;
  const View a = at(k - 1), b = at(k);
  const double u = (t - keys[k - 1].t) / (keys[k].t - keys[k - 1].t);
  auto ease = [](double x) { return x * x * (3 - 2 * x); };
  View v;
  if (shows(a, subject_box(keys[k].camera, geo, t)) || shows(b, subject_box(keys[k - 1].camera, geo, t))) {
    // One shows the other's subject (the hopper and its outlet, an arch and the outlet): a zoom, which keeps
    // what both show in the picture throughout (centre and height interpolated apart, a glide from the hopper
    // to the outlet lost the outlet half way).
    v = glide(a, b, ease(u));
  } else {
    // Subjects apart (an arch and a grain far from it; two windows): the first half widens the picture until
    // both are in it, the second closes on the next key's subject, which then stays in the picture (a pan or
    // a zoom straight across showed neither for a while).
    const View both = union_view(a, b);
    v = u < 0.5 ? glide(a, both, ease(2 * u)) : glide(both, b, ease(2 * u - 1));
  }
  v.name = "path";
  return v;
}

bool freeze_fires(const Freeze& fz, const core::Frame* before, const core::Frame& now, bool rule_next) {
  if (fz.at == Freeze::At::Clog) {
    const bool shows = now.arch_forming || now.clog_open;
    const bool showed =
        before && (before->arch_forming || before->clog_open) && before->clog_number == now.clog_number;
    return shows && !showed;
  }
  return fz.at == Freeze::At::Rule && now.clog_open && rule_next && !now.arch.empty();
}

long Freeze::copies(double fps) const {
  return at == At::None ? 0 : std::max(0L, std::lround(seconds * fps) - 1);
}

Freeze parse_freeze(const std::string& event, const std::string& seconds, const std::string& what,
                    const std::string& form) {
  Freeze f;
  char* end = nullptr;
  const double s = std::strtod(seconds.c_str(), &end);
  if ((event != "clog" && event != "rule") || seconds.empty() || *end != '\0' || !(s > 0) || s > 60)
    throw core::InputError(what + ": expected " + form + ", 0 < SECONDS <= 60 (video seconds)");
  f.at = event == "clog" ? Freeze::At::Clog : Freeze::At::Rule;
  f.seconds = s;
  f.text = event + ":" + seconds;
  return f;
}

}  // namespace render
