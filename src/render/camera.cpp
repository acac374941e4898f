#include "render/camera.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "core/error.h"

namespace render {

core::Vec2 View::world_to_pixel(core::Vec2 p) const {
  const double s = px_per_m();
  return {rect.x + 0.5 * rect.w + (p.x - cam.cx) * s, rect.y + 0.5 * rect.h - (p.y - cam.cy) * s};
}

core::Vec2 View::pixel_to_world(core::Vec2 px) const {
  const double s = px_per_m();
  return {cam.cx + (px.x - rect.x - 0.5 * rect.w) / s, cam.cy - (px.y - rect.y - 0.5 * rect.h) / s};
}

std::array<float, 9> View::world_to_clip() const {
  const double sy = 2.0 / cam.height, sx = sy * rect.h / rect.w;
  // clip = (x - cx) * sx, (y - cy) * sy
  return {static_cast<float>(sx), 0, 0, 0, static_cast<float>(sy), 0, static_cast<float>(-cam.cx * sx),
          static_cast<float>(-cam.cy * sy), 1};
}

void parse_size(const std::string& text, const std::string& option, int& w, int& h, int min_w, int min_h) {
  char x = 0, extra = 0;
  if (std::sscanf(text.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || x != 'x' || w < min_w || h < min_h)
    throw core::InputError(option + " " + text + ": expected WIDTHxHEIGHT in pixels, at least " + std::to_string(min_w) +
                           "x" + std::to_string(min_h) + ", e.g. 1920x1080");
}

Camera fit(double x0, double y0, double x1, double y1, int w, int h) {
  Camera c;
  c.cx = 0.5 * (x0 + x1);
  c.cy = 0.5 * (y0 + y1);
  const double aspect = static_cast<double>(w) / h;
  c.height = std::max(y1 - y0, (x1 - x0) / aspect);
  return c;
}

std::vector<View> layout_views(const std::string& spec, const core::Geometry& geo, int w, int h) {
  const double margin = 0.04 * geo.total_height;
  auto hopper = [&](Rect r) {
    return View{fit(-geo.half_width - margin, -margin, geo.half_width + margin, geo.total_height + margin, r.w, r.h), r,
                "hopper"};
  };
  auto outlet = [&](Rect r) {
    // 1.3 m tall (10 original diameters): arches form up to ~0.6 m above the aperture; the grains falling out.
    const double half = std::min(geo.half_width + 0.05, 0.6);
    return View{fit(-half, -0.25, half, std::min(1.05, geo.total_height), r.w, r.h), r, "outlet"};
  };
  if (spec == "hopper") return {hopper({0, 0, w, h})};
  if (spec == "outlet") return {outlet({0, 0, w, h})};
  if (spec == "split") {
    // The whole container needs only a narrow strip; the outlet view gets the rest (and room for the panel).
    const double aspect = (2 * geo.half_width + 2 * margin) / (geo.total_height + 2 * margin);
    const int left = std::clamp(static_cast<int>(std::lround(1.15 * aspect * h)), std::max(1, w / 10), w / 2);
    View out = outlet({left, 0, w - left, h});
    out.cam.cx += 0.08 * out.cam.height * (w - left) / h;  // hopper a little left of centre: room for the panel
    return {hopper({0, 0, left, h}), out};
  }
  if (spec.rfind("window:", 0) == 0) {
    std::stringstream ss(spec.substr(7));
    double v[4];
    char comma;
    bool ok = static_cast<bool>(ss >> v[0] >> comma >> v[1] >> comma >> v[2] >> comma >> v[3]) && ss.peek() == EOF;
    if (ok && v[2] > v[0] && v[3] > v[1]) return {View{fit(v[0], v[1], v[2], v[3], w, h), {0, 0, w, h}, "window"}};
  }
  throw core::InputError("--camera " + spec +
                         ": expected hopper, outlet, split or window:X0,Y0,X1,Y1 (metres, X1 > X0, Y1 > Y0)");
}

}  // namespace render
