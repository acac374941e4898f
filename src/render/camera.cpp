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

CameraSpec parse_camera(const std::string& spec) {
  CameraSpec c;
  c.text = spec;
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
  throw core::InputError(
      "camera '" + spec +
      "': expected hopper, outlet, split or window:X0,Y0,X1,Y1 (metres, X1 > X0, Y1 > Y0)");
}

std::vector<View> layout_views(const CameraSpec& camera, const core::Geometry& geo, int w, int h) {
  const double margin = 0.04 * geo.total_height;
  const double t = geo.tilt;
  auto hopper = [&](Rect r) {
    return View{
        fit(geo.x_left - margin, -margin, geo.x_right + margin, geo.total_height + margin, r.w, r.h, t), r,
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
    return View{fit(-half, -0.25 * k, half, top, r.w, r.h, t), r, "outlet"};
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
      const double ca = std::abs(std::cos(t)), sa = std::abs(std::sin(t));
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
      return {View{fit(camera.x0, camera.y0, camera.x1, camera.y1, w, h, t), {0, 0, w, h}, "window"}};
  }
  return {};
}

CameraPath parse_camera_path(const std::string& spec) {
  CameraPath path;
  path.text = spec;
  const std::string allowed =
      "expected T:CAMERA,T:CAMERA,... with times in seconds, increasing, and each camera hopper, outlet or "
      "window:X0,Y0,X1,Y1";
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
      cam = parse_camera(item.substr(colon + 1));
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

View CameraPath::view_at(double t, const core::Geometry& geo, int w, int h) const {
  auto at = [&](size_t k) { return layout_views(keys[k].camera, geo, w, h).front(); };
  if (t <= keys.front().t) return at(0);
  if (t >= keys.back().t) return at(keys.size() - 1);
  size_t k = 1;
  while (keys[k].t < t) ++k;
  View a = at(k - 1);
  const View b = at(k);
  const double u = (t - keys[k - 1].t) / (keys[k].t - keys[k - 1].t), s = u * u * (3 - 2 * u);
  const double ha = a.cam.height, hb = b.cam.height;
  if (std::fabs(hb - ha) <= 1e-9 * ha) {  // a pan: the centre moves, the size stays
    a.cam.cx += s * (b.cam.cx - a.cam.cx);
    a.cam.cy += s * (b.cam.cy - a.cam.cy);
  } else {
    // A zoom at a steady rate about the one point that sits at the same place in both keys' pictures: every
    // point inside both keys' windows stays inside the picture throughout (its place in the picture moves
    // monotonically from one key's to the other's), so a glide from the hopper to the outlet never loses the
    // outlet (centre and height interpolated apart, it dropped below the frame half way).
    const double h = ha * std::pow(hb / ha, s);
    const double px = (a.cam.cx * hb - b.cam.cx * ha) / (hb - ha),
                 py = (a.cam.cy * hb - b.cam.cy * ha) / (hb - ha);
    a.cam.cx = px + (a.cam.cx - px) * h / ha;
    a.cam.cy = py + (a.cam.cy - py) * h / ha;
    a.cam.height = h;
  }
  a.name = "path";
  return a;
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
