#include "render/draw_list.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace render {

namespace {
void copy(float* dst, Rgba c) {
  dst[0] = c.r, dst[1] = c.g, dst[2] = c.b, dst[3] = c.a;
}
}  // namespace

DrawList build_draw_list(const core::Frame& frame, const core::Geometry& geo, const Style& style,
                         const ArchStyle& arch, const std::vector<float>* values, double value_top) {
  const bool by_value = values && values->size() == frame.particles.size() &&
                        (style.color == ColorMode::Displacement || style.color == ColorMode::Coordination);
  DrawList out;
  out.halo_m = static_cast<float>(arch.halo_m);
  out.halo_edge = halo_edge_color(style);
  out.bond_m = static_cast<float>(arch.bond_m);
  out.shapes.reserve(frame.particles.size() + 1);
  out.grains = frame.particles.size();
  std::vector<bool> member(frame.particles.size(), false);
  // A frame carries an arch only while a clog is open or its arch is forming (core/frame.h); an open clog's
  // is drawn faint while the outlet flowed less than fade_below ago, unless it is already arrested. A forming
  // arch is known, in hindsight, to be the one that clogs: drawn whole from its first frame.
  const bool show_arch = style.show_arch && !frame.arch.empty();
  const float arch_alpha =
      frame.arch_forming || frame.clog_arrested || frame.since_last_exit >= arch.fade_below ? 1.0f : 0.35f;
  if (show_arch)
    for (int id : frame.arch) member[static_cast<size_t>(id)] = true;
  const Rgba halo = arch_color(style);
  // Circumradius over equal-area radius of each polygon (0-2: a disk).
  float extent[9];
  for (int k = 0; k < 9; ++k) extent[k] = static_cast<float>(core::polygon_extent(k));
  for (size_t i = 0; i < frame.particles.size(); ++i) {
    const auto& p = frame.particles[i];
    const int sides = p.sides <= 8 ? p.sides : 0;
    ShapeInstance d{p.x, p.y, p.radius * extent[sides], {}, {}, {p.angle, static_cast<float>(sides), 0, 0}};
    copy(d.fill, by_value ? value_color(style, (*values)[i], value_top)
                          : particle_color(style, p, static_cast<int>(i)));
    copy(d.halo, member[i] ? Rgba{halo.r, halo.g, halo.b, arch_alpha} : Rgba{0, 0, 0, 0});
    if (!member[i] && !style.tracked.empty() &&
        std::find(style.tracked.begin(), style.tracked.end(), static_cast<int>(i)) != style.tracked.end())
      copy(d.halo, tracked_color(style));
    out.shapes.push_back(d);
  }
  // The container where it is now: a vibrating container carries its walls and obstacle along.
  const float ox = static_cast<float>(frame.container_x), oy = static_cast<float>(frame.container_y);
  const Rgba wc = wall_color(style);
  for (core::Wall k : {core::Wall::HopperLeft, core::Wall::HopperRight, core::Wall::SiloLeft,
                       core::Wall::SiloRight, core::Wall::Top}) {
    const auto& s = geo.walls[static_cast<int>(k)];
    SegmentInstance seg{static_cast<float>(s.a.x) + ox,
                        static_cast<float>(s.a.y) + oy,
                        static_cast<float>(s.b.x) + ox,
                        static_cast<float>(s.b.y) + oy,
                        {},
                        0};
    copy(seg.color, wc);
    out.walls.push_back(seg);
  }
  if (geo.obstacle.present()) {
    const core::Obstacle& ob = geo.obstacle;
    const float cx = static_cast<float>(ob.centre.x) + ox, cy = static_cast<float>(ob.centre.y) + oy;
    const float hw = static_cast<float>(0.5 * ob.width), hh = static_cast<float>(0.5 * ob.height);
    ShapeInstance d{cx, cy, std::hypot(hw, hh), {}, {}, {0, 0, 0, 0}};
    if (ob.kind == core::Obstacle::Kind::Disk)
      d.r = hw;
    else
      d.shape[1] = 100, d.shape[2] = hw, d.shape[3] = hh;
    copy(d.fill, wc);
    out.shapes.push_back(d);
  }
  if (style.chains) {
    // Width from a tenth of the smaller grain's radius (at chain_min) to its whole radius (at chain_max).
    const double span = std::max(1e-12, style.chain_max - style.chain_min);
    for (const auto& c : frame.contacts) {
      if (c.a < 0 || c.b < 0 || static_cast<size_t>(std::max(c.a, c.b)) >= frame.particles.size()) continue;
      if (!(c.force >= style.chain_min)) continue;
      const auto& a = frame.particles[static_cast<size_t>(c.a)];
      const auto& b = frame.particles[static_cast<size_t>(c.b)];
      const double u = std::clamp((c.force - style.chain_min) / span, 0.0, 1.0);
      SegmentInstance seg{a.x, a.y, b.x, b.y, {}, 0};
      copy(seg.color, chain_color(style, u));
      out.chains.push_back(seg);
      out.chain_width_m.push_back(static_cast<float>((0.15 + 0.85 * u) * std::min(a.radius, b.radius)));
    }
  }
  if (show_arch) {
    for (size_t k = 0; k + 1 < frame.arch.size(); ++k) {
      const auto& a = frame.particles[static_cast<size_t>(frame.arch[k])];
      const auto& b = frame.particles[static_cast<size_t>(frame.arch[k + 1])];
      // Neighbours in the arch that do not touch lean on an obstacle between them: no bond across it.
      const float reach = 1.05f * (a.radius * extent[a.sides <= 8 ? a.sides : 0] +
                                   b.radius * extent[b.sides <= 8 ? b.sides : 0]);
      if (std::hypot(a.x - b.x, a.y - b.y) > reach) continue;
      SegmentInstance seg{a.x, a.y, b.x, b.y, {}, 0};
      copy(seg.color, Rgba{0.1f, 0.1f, 0.1f, arch_alpha});
      out.bonds.push_back(seg);
    }
  }
  return out;
}

namespace {
std::string hex(const float* c) {
  char buf[16];
  auto b = [](float v) { return static_cast<int>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255)); };
  std::snprintf(buf, sizeof buf, "#%02x%02x%02x%02x", b(c[0]), b(c[1]), b(c[2]), b(c[3]));
  return buf;
}
}  // namespace

std::string draw_list_csv(const DrawList& list, double cx, double cy, double angle, double half_w,
                          double half_h) {
  const double ca = std::cos(angle), sa = std::sin(angle);
  auto to_view = [&](double x, double y, double& u, double& v) {
    u = ca * (x - cx) - sa * (y - cy);
    v = sa * (x - cx) + ca * (y - cy);
  };
  std::string out = "kind,x,y,r,angle,sides,half_w,half_h,x2,y2,width_m,fill,halo\n";
  char row[256];
  auto inside = [&](double u, double v, double reach) {
    return std::fabs(u) <= half_w + reach && std::fabs(v) <= half_h + reach;
  };
  auto segment = [&](const char* kind, const SegmentInstance& s, double width) {
    double u1, v1, u2, v2;
    to_view(s.ax, s.ay, u1, v1);
    to_view(s.bx, s.by, u2, v2);
    // Kept if its bounding box meets the window.
    if (std::max(u1, u2) < -half_w - width || std::min(u1, u2) > half_w + width ||
        std::max(v1, v2) < -half_h - width || std::min(v1, v2) > half_h + width)
      return;
    std::snprintf(row, sizeof row, "%s,%.6g,%.6g,0,0,0,0,0,%.6g,%.6g,%.6g,%s,\n", kind, u1, v1, u2, v2, width,
                  hex(s.color).c_str());
    out += row;
  };
  for (const auto& w : list.walls) segment("wall", w, list.wall_m);
  for (size_t k = 0; k < list.shapes.size(); ++k) {
    const ShapeInstance& d = list.shapes[k];
    double u, v;
    to_view(d.x, d.y, u, v);
    if (!inside(u, v, d.r + list.halo_m)) continue;
    const bool obstacle = k >= list.grains;
    std::snprintf(row, sizeof row, "%s,%.6g,%.6g,%.6g,%.6g,%d,%.6g,%.6g,0,0,0,%s,%s\n",
                  obstacle ? "obstacle" : "grain", u, v, d.r, d.shape[0] + angle,
                  static_cast<int>(d.shape[1]), d.shape[2], d.shape[3], hex(d.fill).c_str(),
                  d.halo[3] > 0 ? hex(d.halo).c_str() : "");
    out += row;
  }
  for (size_t k = 0; k < list.chains.size(); ++k)
    segment("chain", list.chains[k], k < list.chain_width_m.size() ? list.chain_width_m[k] : 0.01);
  for (const auto& b : list.bonds) segment("bond", b, list.bond_m);
  return out;
}

}  // namespace render
