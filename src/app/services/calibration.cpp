// A film's calibration: pixels to metres, from a siloscope movie's own metadata or from points the user marks
// (app/services/lab.h).
#include <cmath>
#include <complex>

#include <toml++/toml.h>

#include "app/services/lab.h"
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

}  // namespace app
