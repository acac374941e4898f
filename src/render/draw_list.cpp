#include "render/draw_list.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "render/grain_values.h"

namespace render {

namespace {
void copy(float* dst, Rgba c) {
  dst[0] = c.r, dst[1] = c.g, dst[2] = c.b, dst[3] = c.a;
}

double largest_force(const std::vector<ArchForce>& forces) {
  double largest = 0;
  for (const ArchForce& a : forces)
    largest = std::max(largest, std::hypot(static_cast<double>(a.fx), static_cast<double>(a.fy)));
  return largest;
}

// The forces on the arch from outside it, as arrows ending at their contact points (drawn with the chains:
// a shaft and two barbs each, in the walls' colour), the largest as long as the members' mean diameter.
void arch_force_arrows(const core::Frame& frame, const Style& style, DrawList& out) {
  const std::vector<ArchForce> arrows = arch_external_forces(frame);
  const double largest = largest_force(arrows);
  double size = 0;
  for (int id : frame.arch) size += 2.0 * frame.particles[static_cast<size_t>(id)].radius;
  size /= static_cast<double>(frame.arch.size());
  if (!(largest > 0)) return;
  const Rgba color = wall_color(style);
  const float width = static_cast<float>(0.09 * size);
  for (const ArchForce& a : arrows) {
    const double f = std::hypot(static_cast<double>(a.fx), static_cast<double>(a.fy));
    if (f < 0.02 * largest) continue;  // too short to read
    const double len = size * f / largest, ux = a.fx / f, uy = a.fy / f;
    const double tx = a.x - len * ux, ty = a.y - len * uy;  // the tail: the force points at the contact
    const double barb = std::min(0.35 * size, 0.6 * len);
    auto segment = [&](double x0, double y0, double x1, double y1) {
      SegmentInstance s{static_cast<float>(x0),
                        static_cast<float>(y0),
                        static_cast<float>(x1),
                        static_cast<float>(y1),
                        {},
                        0};
      copy(s.color, color);
      out.chains.push_back(s);
      out.chain_width_m.push_back(width);
    };
    segment(tx, ty, a.x, a.y);
    for (double side : {-1.0, 1.0}) {
      const double c = std::cos(0.45), s = side * std::sin(0.45);  // barbs 26 degrees off the shaft
      segment(a.x, a.y, a.x - barb * (c * ux - s * uy), a.y - barb * (s * ux + c * uy));
    }
  }
}
}  // namespace

std::vector<ArchForce> arch_external_forces(const core::Frame& frame) {
  auto member = [&](int i) {
    return i >= 0 && std::find(frame.arch.begin(), frame.arch.end(), i) != frame.arch.end();
  };
  std::vector<ArchForce> out;
  for (const auto* list : {&frame.contacts, &frame.wall_contacts})
    for (const core::Contact& c : *list) {
      if (!c.has_geometry() || member(c.a) == member(c.b)) continue;
      // The force on the member: on b it is force * n + ft * (ny, -nx); on a, the opposite.
      float fx = c.force * c.nx + c.ft * c.ny, fy = c.force * c.ny - c.ft * c.nx;
      if (!member(c.b)) fx = -fx, fy = -fy;
      out.push_back({c.px, c.py, fx, fy});
    }
  return out;
}

double largest_arch_force(const core::Frame& frame) {
  return largest_force(arch_external_forces(frame));
}

DrawList build_draw_list(const core::Frame& frame, const core::Geometry& geo, const Style& style,
                         const ArchStyle& arch, const std::vector<float>* values, double value_top) {
  const bool by_value = values && values->size() == frame.particles.size() && per_grain_values(style.color);
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
  if (show_arch && style.arch_forces) arch_force_arrows(frame, style, out);
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
