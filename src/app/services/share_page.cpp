#include "app/services/share_page.h"

#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>
#include <vector>

#include "app/services/cli.h"
#include "core/error.h"
#include "core/format.h"
#include "core/interrupt.h"
#include "render/draw_list.h"
#include "render/overlay.h"
#include "render/palette.h"

namespace app {

namespace {
namespace fs = std::filesystem;

// JSON text of a string, safe inside a <script> element (<, > and & as \u escapes).
std::string json_string(const std::string& s) {
  std::string out = "\"";
  for (size_t i = 0; i < s.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(s[i]);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += static_cast<char>(c);
    } else if (c < 0x20 || c == '<' || c == '>' || c == '&') {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", c);
      out += buf;
    } else {
      out += static_cast<char>(c);
    }
  }
  return out + "\"";
}

std::string json_number(double v) {
  return std::isfinite(v) ? core::format_g(v, 9) : "null";
}

std::string base64(const std::string& bytes) {
  static const char* abc = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const unsigned v = (static_cast<unsigned char>(bytes[i]) << 16) |
                       (static_cast<unsigned char>(bytes[i + 1]) << 8) |
                       static_cast<unsigned char>(bytes[i + 2]);
    out += abc[(v >> 18) & 63], out += abc[(v >> 12) & 63], out += abc[(v >> 6) & 63], out += abc[v & 63];
  }
  if (i < bytes.size()) {
    unsigned v = static_cast<unsigned char>(bytes[i]) << 16;
    if (i + 1 < bytes.size()) v |= static_cast<unsigned char>(bytes[i + 1]) << 8;
    out += abc[(v >> 18) & 63], out += abc[(v >> 12) & 63];
    out += i + 1 < bytes.size() ? abc[(v >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

// Little-endian values appended to a byte string (the page's reader is a DataView with littleEndian true).
template <class T>
void put(std::string& out, T v) {
  unsigned char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__
  std::reverse(b, b + sizeof(T));
#endif
  out.append(reinterpret_cast<const char*>(b), sizeof(T));
}

std::string deflate(const std::string& raw) {
  uLongf bound = compressBound(static_cast<uLong>(raw.size()));
  std::string out(bound, '\0');
  if (compress2(reinterpret_cast<Bytef*>(&out[0]), &bound, reinterpret_cast<const Bytef*>(raw.data()),
                static_cast<uLong>(raw.size()), 9) != Z_OK)
    throw core::RuntimeFault("share: deflating the frames failed");
  out.resize(bound);
  return out;
}

std::string read_viewer_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw core::RuntimeFault("share: the viewer's file " + path.string() + " cannot be read");
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string html_escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '<')
      out += "&lt;";
    else if (c == '>')
      out += "&gt;";
    else if (c == '&')
      out += "&amp;";
    else if (c == '"')
      out += "&quot;";
    else
      out += c;
  }
  return out;
}

// The template with each "{{NAME}}" replaced by its value, in one pass (a value is never read as the
// template); every name must be used.
std::string fill(const std::string& tmpl, const std::vector<std::pair<std::string, std::string>>& values) {
  std::string out;
  std::vector<bool> used(values.size(), false);
  size_t at = 0;
  while (true) {
    const size_t open = tmpl.find("{{", at);
    if (open == std::string::npos) break;
    const size_t close = tmpl.find("}}", open);
    if (close == std::string::npos) break;
    const std::string name = tmpl.substr(open + 2, close - open - 2);
    size_t k = 0;
    while (k < values.size() && values[k].first != name) ++k;
    out.append(tmpl, at, open - at);
    if (k < values.size()) {
      out += values[k].second;
      used[k] = true;
    } else {
      out.append(tmpl, open, close + 2 - open);
    }
    at = close + 2;
  }
  out.append(tmpl, at, std::string::npos);
  for (size_t k = 0; k < values.size(); ++k)
    if (!used[k]) throw core::RuntimeFault("share: the viewer's template has no {{" + values[k].first + "}}");
  return out;
}

constexpr std::uint16_t kAbsent = 0xFFFF;  // a position code: the grain is not in this frame (a lab's track)

// The frames chosen by the window and the stride.
std::vector<long> chosen_frames(const io::Trajectory& tr, const ShareOptions& o, double duration) {
  const double to = o.to < 0 ? std::numeric_limits<double>::infinity() : o.to;
  if (!(o.from >= 0) || !(to > o.from))
    throw core::InputError("--from " + core::format_g(o.from) +
                           (o.to < 0 ? std::string(" (to the run's end)") : " --to " + core::format_g(o.to)) +
                           ": expected 0 <= FROM < TO (the run lasts " + core::format_g(duration) + " s)");
  if (o.stride < 1 || o.stride > 10000)
    throw core::InputError("--stride " + std::to_string(o.stride) +
                           ": expected a whole number from 1 to 10000");
  std::vector<long> ks;
  long first = -1;
  for (long k = 0; k < tr.size(); ++k) {
    const double t = tr.time(k);
    if (t < o.from - 1e-9 || t > to + 1e-9) continue;
    if (first < 0) first = k;
    if ((k - first) % o.stride == 0) ks.push_back(k);
  }
  if (ks.empty())
    throw core::InputError("--from " + core::format_g(o.from) +
                           (o.to < 0 ? std::string(" (to the run's end)") : " --to " + core::format_g(o.to)) +
                           ": no frame of the recording lies in this window (its frames run from " +
                           core::format_g(tr.size() ? tr.time(0) : 0) + " to " +
                           core::format_g(tr.size() ? tr.time(tr.size() - 1) : 0) + " s)");
  return ks;
}

// How the frames are quantized: the extent of the positions, the largest speed and force, the shapes.
struct Packing {
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0, qx = 0, qy = 0, vq = 0, fmax = 0;
  bool polygons = false;
};

Packing measure(const io::Trajectory& tr, const std::vector<long>& ks, const core::Geometry& geo) {
  Packing m;
  m.x0 = geo.x_left, m.x1 = geo.x_right, m.y0 = 0, m.y1 = geo.total_height;
  double vmax = 0;
  for (long k : ks) {
    core::throw_if_interrupted();
    for (const auto& p : tr.frame(k).particles) {
      if (p.sides >= 3) m.polygons = true;
      if (std::isfinite(p.x) && std::isfinite(p.y)) {
        m.x0 = std::min<double>(m.x0, p.x - p.radius), m.x1 = std::max<double>(m.x1, p.x + p.radius);
        m.y0 = std::min<double>(m.y0, p.y - p.radius), m.y1 = std::max<double>(m.y1, p.y + p.radius);
      }
      if (std::isfinite(p.vx) && std::isfinite(p.vy)) vmax = std::max<double>(vmax, std::hypot(p.vx, p.vy));
      if (std::isfinite(p.force)) m.fmax = std::max<double>(m.fmax, p.force);
    }
  }
  const double pad = geo.grain_diameter;
  m.x0 -= pad, m.x1 += pad, m.y0 -= pad, m.y1 += pad;
  m.qx = (m.x1 - m.x0) / 65534.0, m.qy = (m.y1 - m.y0) / 65534.0;
  m.vq = std::max(vmax, 1e-6) / 32000.0;  // m/s per unit
  return m;
}

// A plane: one code per grain per frame, each frame's codes less the previous frame's (wrapping), so that
// grains at rest are runs of zeros for deflate.
template <class T>
struct Plane {
  std::string bytes;
  std::vector<T> prev;
  explicit Plane(size_t n) : prev(n, 0) {}
  void add(size_t i, T code) {
    put<T>(bytes, static_cast<T>(code - prev[i]));
    prev[i] = code;
  }
};

// The packed frames (docs/share.md): per grain, then per frame, then each quantity's plane.
std::string pack(const io::Trajectory& tr, const std::vector<long>& ks, const Packing& m, size_t ns) {
  const size_t n = tr.info().n_particles;
  std::string grains, per_frame[9], archs;
  Plane<std::uint16_t> px(n), py(n), pvx(n), pvy(n);
  Plane<std::uint8_t> pangle(n), pforce(n);
  auto position = [](double v, double lo, double q) -> std::uint16_t {
    if (!std::isfinite(v)) return kAbsent;
    return static_cast<std::uint16_t>(std::clamp(std::lround((v - lo) / q), 0L, 65534L));
  };
  auto velocity = [&](double v) -> std::uint16_t {
    const long c = std::isfinite(v) ? std::clamp(std::lround(v / m.vq), -32767L, 32767L) : 0L;
    return static_cast<std::uint16_t>(static_cast<std::int16_t>(c));
  };
  for (size_t j = 0; j < ks.size(); ++j) {
    core::throw_if_interrupted();
    const core::Frame f = tr.frame(ks[j]);
    if (j == 0) {
      for (const auto& p : f.particles) put<float>(grains, p.radius);
      for (const auto& p : f.particles) put<std::uint8_t>(grains, static_cast<std::uint8_t>(p.species));
      for (const auto& p : f.particles) put<std::uint8_t>(grains, p.sides);
    }
    const size_t arch = std::min<size_t>(f.arch.size(), 255);
    put<double>(per_frame[0], f.t);
    put<float>(per_frame[1], static_cast<float>(f.since_last_exit));
    put<float>(per_frame[2], static_cast<float>(f.clog_start));
    put<float>(per_frame[3], static_cast<float>(f.container_x));
    put<float>(per_frame[4], static_cast<float>(f.container_y));
    put<std::int32_t>(per_frame[5], f.clog_number);
    put<std::uint8_t>(per_frame[6],
                      static_cast<std::uint8_t>((f.clog_open ? 1 : 0) | (f.clog_arrested ? 2 : 0) |
                                                (f.arch_forming ? 4 : 0)));
    put<std::uint8_t>(per_frame[7], static_cast<std::uint8_t>(arch));
    for (size_t s = 0; s < ns; ++s)
      put<std::int32_t>(per_frame[8], static_cast<std::int32_t>(f.exits_of(static_cast<int>(s))));
    for (size_t a = 0; a < arch; ++a) put<std::int32_t>(archs, f.arch[a]);
    for (size_t i = 0; i < n; ++i) {
      const core::Particle& p = f.particles[i];
      const bool here = std::isfinite(p.x) && std::isfinite(p.y);
      px.add(i, here ? position(p.x, m.x0, m.qx) : kAbsent);
      py.add(i, here ? position(p.y, m.y0, m.qy) : kAbsent);
      pvx.add(i, velocity(p.vx));
      pvy.add(i, velocity(p.vy));
      // The angle modulo the polygon's symmetry, in 256 steps.
      std::uint8_t angle = 0;
      if (p.sides >= 3 && std::isfinite(p.angle)) {
        double u = std::fmod(p.angle / (2 * M_PI / p.sides), 1.0);
        angle = static_cast<std::uint8_t>(std::lround((u < 0 ? u + 1 : u) * 256) & 255);
      }
      pangle.add(i, angle);
      // The summed contact force on a square-root scale up to the largest force in the page.
      pforce.add(
          i, p.force > 0 && m.fmax > 0
                 ? static_cast<std::uint8_t>(std::lround(255 * std::sqrt(std::min(1.0, p.force / m.fmax))))
                 : 0);
    }
  }
  std::string raw = grains;
  for (const std::string& part : per_frame) raw += part;
  raw += archs;
  raw += px.bytes + py.bytes + pvx.bytes + pvy.bytes;
  if (m.polygons) raw += pangle.bytes;
  if (m.fmax > 0) raw += pforce.bytes;
  return raw;
}
// The container for the viewer: the walls (at rest), the obstacle, the tilt and the sizes its cameras use.
std::string geometry_json(const core::Geometry& geo) {
  std::ostringstream j;
  j << "{\"walls\":[";
  bool first = true;
  for (core::Wall k : {core::Wall::HopperLeft, core::Wall::HopperRight, core::Wall::SiloLeft,
                       core::Wall::SiloRight, core::Wall::Top}) {
    const core::Segment& s = geo.walls[static_cast<int>(k)];
    j << (first ? "" : ",") << "[" << json_number(s.a.x) << "," << json_number(s.a.y) << ","
      << json_number(s.b.x) << "," << json_number(s.b.y) << "]";
    first = false;
  }
  j << "],\"obstacle\":";
  if (geo.obstacle.present())
    j << "{\"kind\":\"" << (geo.obstacle.kind == core::Obstacle::Kind::Disk ? "disk" : "bar")
      << "\",\"x\":" << json_number(geo.obstacle.centre.x) << ",\"y\":" << json_number(geo.obstacle.centre.y)
      << ",\"w\":" << json_number(geo.obstacle.width) << ",\"h\":" << json_number(geo.obstacle.height) << "}";
  else
    j << "null";
  j << ",\"tilt\":" << json_number(geo.tilt) << ",\"x_left\":" << json_number(geo.x_left)
    << ",\"x_right\":" << json_number(geo.x_right) << ",\"height\":" << json_number(geo.total_height)
    << ",\"half_aperture\":" << json_number(geo.half_aperture)
    << ",\"grain_diameter\":" << json_number(geo.grain_diameter) << "}";
  return j.str();
}

// The look for the viewer: background, walls, the arch's halo, the colour scale and its map.
std::string look_json(const Look& look, const core::Geometry& geo) {
  const render::Style& st = look.style;
  std::ostringstream j;
  const render::ArchStyle arch;
  std::string ramp;
  for (int k = 0; k <= 32; ++k)
    ramp += (k ? "," : "") + json_string(render::hex_rgb(render::colormap(st, k / 32.0)));
  j << "{\"background\":" << json_string(render::hex_rgb(render::background_color(st)))
    << ",\"dark\":" << (st.dark ? "true" : "false")
    << ",\"walls\":" << json_string(render::hex_rgb(render::wall_color(st)))
    << ",\"arch\":" << json_string(render::hex_rgb(render::arch_color(st)))
    << ",\"picked\":" << json_string(render::hex_rgb(render::tracked_color(st)))
    << ",\"color\":" << json_string(render::color_mode_name(st.color))
    << ",\"speed_max\":" << json_number(st.speed_max) << ",\"force_max\":" << json_number(st.force_max)
    << ",\"color_min\":" << json_number(st.color_min)
    << ",\"displacement_from\":" << json_number(st.displacement_from)
    << ",\"displacement_max\":" << json_number(st.displacement_max)
    << ",\"coordination_max\":" << json_number(st.coordination_max) << ",\"colormap\":[" << ramp << "]"
    << ",\"halo_m\":" << json_number(arch.halo_m * geo.grain_diameter / 0.13)
    << ",\"fade_below\":" << json_number(arch.fade_below)
    << ",\"font_scale\":" << json_number(look.overlay.font_scale) << "}";
  return j.str();
}

// What the viewer needs besides the frames (docs/share.md).
std::string header_json(const io::Run& run, const Look& look, const ShareOptions& o, const Packing& m,
                        size_t nf) {
  const io::Trajectory& tr = run.trajectory();
  const core::Model& model = run.model();
  const size_t n = tr.info().n_particles, ns = std::max<size_t>(1, model.setup.species.size());
  const render::OverlayData od = render::overlay_data_for(model);
  const render::Style& st = look.style;
  std::ostringstream j;
  j << "{\"format\":1,\"siloscope\":" << json_string(io::version_string())
    << ",\"command\":" << json_string(command_line()) << ",\"name\":" << json_string(run.name())
    << ",\"title\":" << json_string(od.title) << ",\"imported\":" << (run.imported() ? "true" : "false")
    << ",\"n\":" << n << ",\"frames\":" << nf << ",\"species\":[";
  for (size_t s = 0; s < ns; ++s) {
    const auto sp = static_cast<core::Species>(s);
    j << (s ? "," : "") << "{\"name\":"
      << json_string(s < od.species_names.size() ? od.species_names[s] : core::species_name(sp))
      << ",\"color\":" << json_string(render::hex_rgb(render::species_color(st, sp))) << "}";
  }
  j << "],\"extent\":[" << json_number(m.x0) << "," << json_number(m.y0) << "," << json_number(m.x1) << ","
    << json_number(m.y1) << "],\"q\":[" << json_number(m.qx) << "," << json_number(m.qy)
    << "],\"vq\":" << json_number(m.vq) << ",\"angles\":" << (m.polygons ? "true" : "false")
    << ",\"fmax\":" << json_number(m.fmax) << ",\"duration\":" << json_number(model.scene.duration)
    << ",\"frame_interval\":" << json_number(tr.info().frame_interval * o.stride)
    << ",\"clog_min_gap\":" << json_number(model.scene.clog_min_gap)
    << ",\"clog_timeout\":" << json_number(model.setup.clog_rule ? model.scene.clog_timeout : 0)
    << ",\"diameter\":" << json_number(od.diameter) << ",\"geometry\":" << geometry_json(model.setup.geo)
    << ",\"look\":" << look_json(look, model.setup.geo) << ",\"clogs\":[";
  const core::Events& ev = run.events();
  for (size_t c = 0; c < ev.clogs.size(); ++c) {
    const core::ClogEvent& e = ev.clogs[c];
    j << (c ? "," : "") << "{\"start\":" << json_number(e.start) << ",\"end\":" << json_number(e.end)
      << ",\"ended_by\":\"" << core::clog_end_name(e.ended_by)
      << "\",\"arrested\":" << (e.arrested ? "true" : "false") << ",\"formed\":" << json_number(e.formed)
      << "}";
  }
  j << "],\"exits\":" << ev.exits.size() << "}";
  return j.str();
}
}  // namespace

SharePage share_page(const io::Run& run, const Look& look, const ShareOptions& o, const fs::path& viewer) {
  const io::Trajectory& tr = run.trajectory();
  const core::Model& model = run.model();
  const std::vector<long> ks = chosen_frames(tr, o, model.scene.duration);
  const Packing m = measure(tr, ks, model.setup.geo);
  const std::string raw = pack(tr, ks, m, std::max<size_t>(1, model.setup.species.size()));
  const std::string packed = deflate(raw);
  core::throw_if_interrupted();
  const std::string tmpl = read_viewer_file(viewer / (o.embed ? "embed.html" : "viewer.html"));
  SharePage out;
  out.html = fill(tmpl, {{"VERSION", html_escape(io::version_string())},
                         {"TITLE", html_escape(run.name())},
                         {"CSS", read_viewer_file(viewer / "viewer.css")},
                         {"HEADER", header_json(run, look, o, m, ks.size())},
                         {"METADATA", json_string(run.metadata_text())},
                         {"DATA", base64(packed)},
                         {"JS", read_viewer_file(viewer / "viewer.js")}});
  out.frames = static_cast<long>(ks.size());
  out.raw_bytes = raw.size();
  out.data_bytes = packed.size();
  return out;
}

}  // namespace app
