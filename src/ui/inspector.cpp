#include "ui/inspector.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.h"
#include "core/scene.h"
#include "render/draw_list.h"
#include "render/grain_values.h"

namespace ui {

namespace {
long to_long(const std::string& s, const char* what) {
  char* end = nullptr;
  long v = std::strtol(s.c_str(), &end, 10);
  if (s.empty() || *end) throw core::InputError(std::string(what) + " '" + s + "' is not a whole number");
  return v;
}
double to_double(const std::string& s, const char* what) {
  char* end = nullptr;
  double v = std::strtod(s.c_str(), &end);
  if (s.empty() || *end || !std::isfinite(v))
    throw core::InputError(std::string(what) + " '" + s + "' is not a number");
  return v;
}
const char* kCommands =
    "goto, step, next, prev, zoom, pan, camera-path, color, colormap, chains, palette, overlay, arch, track, "
    "freeze, snapshot, export, print";
}  // namespace

Inspector::Inspector(const FrameSource& traj, const core::Scene& scene, const ImageFiles* files)
    : traj_(traj), files_(files), scene_(scene), geo_(core::make_geometry(scene)) {
  if (traj_.size() == 0) throw core::InputError("the trajectory holds no complete frame");
  overlay_data = render::overlay_data_for(scene_);
  // Clogs: maximal stretches of frames whose clog timer is at least clog_min_gap.
  const double gap = traj_.clog_min_gap();
  for (long k = 0; k < traj_.size(); ++k) {
    const double timer = traj_.since_last_exit(k);
    if (timer < gap) continue;
    long last = k;
    double longest = timer;
    while (last + 1 < traj_.size()) {
      const double next = traj_.since_last_exit(last + 1);
      if (next < gap || next < traj_.since_last_exit(last)) break;  // the timer restarted
      ++last;
      longest = next;
    }
    const bool removed = last + 1 < traj_.size() && traj_.long_arches(last + 1) > traj_.long_arches(last);
    // The clog began at its last exit, clog_min_gap before the timer said so: the bar starts there.
    const double start = traj_.time(k) - timer;
    long first = k;
    while (first > 0 && traj_.time(first - 1) >= start - 1e-9) --first;
    clogs_.push_back({first, last, longest, removed});
    k = last;
  }
}

void Inspector::set_frame(long k) {
  frame_ = std::clamp(k, 0L, traj_.size() - 1);
}

std::vector<render::View> Inspector::views(int w, int h) const {
  if (!path.empty()) return {path.view_at(traj_.time(frame_), geo_, w, h)};
  auto vs = render::layout_views(camera, geo_, w, h);
  // Zoom and pan apply to the most magnified view (the outlet in split), the one a user inspects.
  render::View* main = &vs.front();
  for (auto& v : vs)
    if (v.px_per_m() > main->px_per_m()) main = &v;
  main->cam.height /= zoom;
  main->cam.cx += pan.x;
  main->cam.cy += pan.y;
  return vs;
}

std::string Inspector::output_name(const std::string& pattern, const std::string& line) const {
  // {frame} -> the frame number (6 digits), {t} -> the time in s (3 decimals).
  std::string out = pattern;
  auto put = [&](const std::string& key, const std::string& value) {
    for (size_t p; (p = out.find(key)) != std::string::npos;) out.replace(p, key.size(), value);
  };
  char buf[32];
  std::snprintf(buf, sizeof buf, "%06ld", frame_);
  put("{frame}", buf);
  std::snprintf(buf, sizeof buf, "%.3f", traj_.time(frame_));
  put("{t}", buf);
  if (std::filesystem::exists(out))
    throw core::InputError("'" + line + "': " + out +
                           " exists; the inspector never writes over a file (choose another "
                           "name, or use {frame} or {t} in it)");
  return out;
}

core::Frame Inspector::reference_frame() const {
  // The first frame at or after the displacement's reference time (none: colouring by something else).
  if (style.color != render::ColorMode::Displacement) return {};
  for (long k = 0; k < traj_.size(); ++k)
    if (traj_.time(k) >= style.displacement_from - 1e-9) return traj_.frame(k);
  return {};
}

core::Image Inspector::render_current(Painter& p, int w, int h) const {
  // Pictures (snapshots, clips) place the information box where it covers the fewest grains, as movies do
  // (with the discharge plot, the plot takes the free space and the box keeps the top-right corner); it
  // stays in the picture.
  render::OverlayOptions o = overlay;
  o.place_clear = !o.plot;
  o.may_leave = false;
  const core::Frame ref = reference_frame();
  return p.paint(current(), geo_, views(w, h), style, o, overlay_data, w, h,
                 ref.particles.empty() ? nullptr : &ref);
}

long Inspector::in_range(long k) const {
  if (k < 0 || k >= traj_.size())
    throw core::InputError("frame " + std::to_string(k) + " is out of range (0 to " +
                           std::to_string(traj_.size() - 1) + ")");
  return k;
}

void Inspector::log(const std::string& command) {
  history_.push_back(command);
}

void Inspector::goto_frame(long k) {
  frame_ = in_range(k);
  log("goto frame " + std::to_string(k));
}

void Inspector::goto_time(double t) {
  if (t < traj_.time(0) - 1e-9 || t > traj_.time(traj_.size() - 1) + 1e-9)
    throw core::InputError("time " + std::to_string(t) + " s is outside the trajectory (" +
                           std::to_string(traj_.time(0)) + " to " +
                           std::to_string(traj_.time(traj_.size() - 1)) + " s)");
  long best = 0;
  for (long k = 0; k < traj_.size(); ++k)
    if (std::abs(traj_.time(k) - t) < std::abs(traj_.time(best) - t)) best = k;
  frame_ = best;
  log("goto time " + std::to_string(t));
}

void Inspector::goto_clog(long k) {
  if (k < 1 || k > static_cast<long>(clogs_.size()))
    throw core::InputError("clog " + std::to_string(k) + " does not exist; the trajectory has " +
                           std::to_string(clogs_.size()) + " clogs (numbered from 1)");
  frame_ = clogs_[static_cast<size_t>(k - 1)].last;
  log("goto clog " + std::to_string(k));
}

void Inspector::goto_arch(long k) {
  long found = -1;
  for (long f = 1; f < traj_.size() && found < 0; ++f)
    if (traj_.long_arches(f) >= k && traj_.long_arches(f - 1) < k) found = f - 1;
  if (k < 1 || found < 0)
    throw core::InputError("long-lasting arch " + std::to_string(k) + " is not in the trajectory (it has " +
                           std::to_string(traj_.long_arches(traj_.size() - 1)) + ")");
  frame_ = found;
  log("goto arch " + std::to_string(k));
}

void Inspector::goto_start() {
  frame_ = 0;
  log("goto start");
}

void Inspector::goto_end() {
  frame_ = traj_.size() - 1;
  log("goto end");
}

void Inspector::step_frames(long n) {
  frame_ = in_range(frame_ + n);
  log("step " + std::to_string(n));
}

void Inspector::next_clog(bool later) {
  const ClogSpan* hit = nullptr;
  if (later) {
    for (const auto& c : clogs_)
      if (c.last > frame_) {
        hit = &c;
        break;
      }
  } else {
    for (auto it = clogs_.rbegin(); it != clogs_.rend(); ++it)
      if (it->last < frame_) {
        hit = &*it;
        break;
      }
  }
  if (!hit) throw core::InputError(std::string("there is no ") + (later ? "later" : "earlier") + " clog");
  frame_ = hit->last;
  log(later ? "next clog" : "prev clog");
}

void Inspector::set_camera(const render::CameraSpec& c) {
  camera = c;
  zoom = 1.0;
  pan = {0, 0};
  log("zoom " + c.text);
}

void Inspector::zoom_by(double f) {
  if (!(f > 0)) throw core::InputError("the zoom factor must be > 0");
  zoom = std::clamp(zoom * f, 0.1, 100.0);
  log("zoom by " + std::to_string(f));
}

void Inspector::pan_by(double dx, double dy) {
  pan.x += dx;
  pan.y += dy;
  log("pan " + std::to_string(dx) + " " + std::to_string(dy));
}

void Inspector::set_color(render::ColorMode m, const std::string& name) {
  style.color = m;
  log("color " + name);
}

void Inspector::set_palette(render::Palette p, const std::string& name) {
  style.palette = p;
  log("palette " + name);
}

void Inspector::set_overlay(const std::string& spec) {
  overlay = render::parse_overlay(spec);
  log("overlay " + spec);
}

void Inspector::show_arch(bool on) {
  style.show_arch = on;
  log(on ? "arch on" : "arch off");
}

std::string Inspector::print_frame() {
  const core::Frame f = current();
  std::ostringstream o;
  o << "frame " << frame_ << " t = " << f.t << " s, clog timer " << f.since_last_exit << " s, arch [";
  for (size_t k = 0; k < f.arch.size(); ++k) o << (k ? " " : "") << f.arch[k];
  o << "]";
  last_output = o.str();
  std::printf("%s\n", last_output.c_str());
  return last_output;
}

std::string Inspector::snapshot(const std::string& pattern, int w, int h, Painter* painter) {
  if (!painter || !files_) throw core::InputError("snapshot needs a renderer and files");
  const std::string path = output_name(pattern, "snapshot " + pattern);
  const std::string ext = std::filesystem::path(path).extension().string();
  if (ext == ".svg" || ext == ".pdf") {
    // Vector: the main view (the most magnified: the outlet in split) as circles, polygons and paths.
    const std::vector<render::View> vs = views(w, h);
    const render::View* v = &vs.front();
    for (const auto& c : vs)
      if (c.px_per_m() > v->px_per_m()) v = &c;
    const core::Frame f = current();
    render::Style st = style;
    st.species_colors = overlay_data.species_colors;
    const double half_h = 0.5 * v->cam.height, half_w = half_h * v->rect.w / std::max(1, v->rect.h);
    // The grains' values as the pictures colour them (displacement from the reference frame, coordination).
    render::GrainValues gv;
    const core::Frame ref = reference_frame();
    const std::vector<float>& values = gv.update(f, st, ref.particles.empty() ? nullptr : &ref);
    if (st.color == render::ColorMode::Displacement && !(st.displacement_max > 0))
      st.displacement_max = std::max(gv.largest(), st.color_min + 1e-6);
    const std::string table =
        render::draw_list_csv(render::build_draw_list(f, geo_, st, {}, &values, render::color_scale_max(st)),
                              v->cam.cx, v->cam.cy, v->cam.angle, half_w, half_h);
    char caption[160];
    std::snprintf(caption, sizeof caption, "t = %.3f s (frame %ld), clog timer %.2f s, arch: %zu grains", f.t,
                  frame_, f.since_last_exit, f.arch.size());
    std::string text = caption;
    const std::string scale = render::color_scale_label(st);
    if (!scale.empty()) {
      char range[96];
      std::snprintf(range, sizeof range, " from %.3g to %.3g (%s)", st.color_min, render::color_scale_max(st),
                    render::colormap_name(st.colormap));
      text += "\ncolour: " + scale + range;
    }
    files_->write_vector(path, table, 2 * half_w, 2 * half_h, text);
  } else {
    files_->write_png(path, render_current(*painter, w, h));
  }
  last_output = path;
  log("snapshot " + pattern + " " + std::to_string(w) + "x" + std::to_string(h));
  return path;
}

std::string Inspector::export_frames(const std::string& pattern, long from, long to, int width, int height,
                                     int fps, Painter* painter) {
  in_range(from);
  in_range(to);
  if (to < from) throw core::InputError("TO must not be before FROM");
  if (!painter || !files_) throw core::InputError("export needs a renderer and files");
  files_->check_movie(width, height, fps);
  const std::string path = output_name(pattern, "export " + pattern);
  auto movie = files_->open_movie(path, width, height, fps);
  const long keep = frame_;
  const long copies = freeze_at ? std::max(0L, std::lround(freeze_s * fps) - 1) : 0;
  for (long k = from; k <= to; ++k) {
    frame_ = k;
    const core::Image img = render_current(*painter, width, height);
    movie->add(img);
    // A freeze: the clog timer crossing clog_min_gap here, or the rule firing before the next frame.
    const bool event = freeze_at == 1 ? k > 0 && traj_.since_last_exit(k - 1) < traj_.clog_min_gap() &&
                                            traj_.since_last_exit(k) >= traj_.clog_min_gap()
                                      : freeze_at == 2 && k + 1 < traj_.size() &&
                                            traj_.long_arches(k + 1) > traj_.long_arches(k);
    for (long c = 0; event && c < copies; ++c) movie->add(img);
  }
  frame_ = keep;
  movie->finish();
  last_output = path + " (frames " + std::to_string(from) + " to " + std::to_string(to) + ")";
  log("export " + pattern + " " + std::to_string(from) + " " + std::to_string(to) + " " +
      std::to_string(width) + "x" + std::to_string(height) + " " + std::to_string(fps));
  return path;
}

std::string Inspector::export_clog(const std::string& pattern, int width, int height, int fps,
                                   Painter* painter) {
  // The clog at (or after) this frame, from 1 s before it forms to 0.5 s after it ends.
  const ClogSpan* hit = nullptr;
  for (const auto& c : clogs_)
    if (c.last >= frame_) {
      hit = &c;
      break;
    }
  if (!hit) throw core::InputError("there is no clog at or after frame " + std::to_string(frame_));
  const double dt = traj_.frame_interval();
  const long from = std::max(0L, hit->first - std::lround(1.0 / dt));
  const long to = std::min(traj_.size() - 1, hit->last + std::lround(0.5 / dt));
  return export_frames(pattern, from, to, width, height, fps, painter);
}

namespace {
// A script line's words, a comment cut off.
std::vector<std::string> words_of(const std::string& line) {
  std::stringstream ss(line);
  std::vector<std::string> a;
  for (std::string word; ss >> word;) {
    if (word[0] == '#') break;
    a.push_back(word);
  }
  return a;
}
}  // namespace

void Inspector::execute(const std::string& line, Painter* painter) {
  const std::vector<std::string> a = words_of(line);
  if (a.empty()) return;
  const std::string& cmd = a[0];
  auto need = [&](size_t n, const char* usage) {
    if (a.size() != n + 1) throw core::InputError(std::string("usage: ") + usage);
  };
  try {
    if (cmd == "goto") {
      if (a.size() == 2 && a[1] == "start") return goto_start();
      if (a.size() == 2 && a[1] == "end") return goto_end();
      need(2, "goto frame N | goto time T | goto clog K | goto arch K | goto start | goto end");
      if (a[1] == "frame") return goto_frame(to_long(a[2], "frame"));
      if (a[1] == "time") return goto_time(to_double(a[2], "time"));
      if (a[1] == "clog") return goto_clog(to_long(a[2], "clog"));
      if (a[1] == "arch") return goto_arch(to_long(a[2], "arch"));
      throw core::InputError("goto frame|time|clog|arch|start|end");
    }
    if (cmd == "step") return need(1, "step N"), step_frames(to_long(a[1], "step"));
    if (cmd == "next" || cmd == "prev") {
      need(1, "next clog | prev clog");
      if (a[1] != "clog") throw core::InputError("usage: next clog | prev clog");
      return next_clog(cmd == "next");
    }
    if (cmd == "zoom") {
      if (a.size() == 3 && a[1] == "by") return zoom_by(to_double(a[2], "zoom factor"));
      need(1, "zoom hopper|outlet|split|window:X0,Y0,X1,Y1 | zoom by F");
      return set_camera(render::parse_camera(a[1]));
    }
    if (cmd == "pan")
      return need(2, "pan DX DY (metres)"), pan_by(to_double(a[1], "DX"), to_double(a[2], "DY"));
    if (cmd == "color") {
      // color MODE [MAX|MIN:MAX|auto] [from T]: the mode, the scale's range (auto: each frame's largest
      // displacement; speed and force keep their defaults) and, for displacement, the reference time.
      const char* usage =
          "color species|speed|force|displacement|coordination|id [MAX|MIN:MAX|auto] [from T]";
      if (a.size() < 2 || a.size() > 5) throw core::InputError(std::string("usage: ") + usage);
      const render::ColorMode m = render::parse_color_mode(a[1]);
      size_t k = 2;
      render::Style next = style;
      next.color = m;
      if (k < a.size() && a[k] != "from") render::set_color_range(next, a[k++]);
      if (k < a.size()) {
        if (a[k] != "from" || k + 2 != a.size() || m != render::ColorMode::Displacement)
          throw core::InputError(std::string("usage: ") + usage + " (from T: displacement only)");
        next.displacement_from = to_double(a[k + 1], "from");
      }
      style = next;
      return set_color(m, line.substr(line.find_first_not_of(" \t") + 6));
    }
    if (cmd == "chains") {
      // chains MIN[:MAX] | off: the force chains (record --force-chains), from the run's contacts.sscon.
      need(1, "chains MIN[:MAX]|off (newtons)");
      if (a[1] == "off") return style.chains = false, log("chains off");
      if (!traj_.has_contacts())
        throw core::InputError(
            "chains: this trajectory has no contacts beside it (contacts.sscon: record and run "
            "--trajectory-fps write one; runs made before they did have none)");
      render::set_chains(style, a[1], "chains");
      return log("chains " + a[1]);
    }
    if (cmd == "camera-path") {
      // camera-path T:CAMERA,... | off: pictures follow the key frames by each frame's time (record
      // --camera-path).
      need(1, "camera-path T:CAMERA,T:CAMERA,... | camera-path off");
      if (a[1] == "off") return path = {}, log("camera-path off");
      path = render::parse_camera_path(a[1]);
      return log("camera-path " + a[1]);
    }
    if (cmd == "freeze") {
      // freeze clog|rule SECONDS | off: clips hold the picture at each event (record --freeze).
      if (a.size() == 2 && a[1] == "off") return freeze_at = 0, log("freeze off");
      need(2, "freeze clog|rule SECONDS | freeze off");
      const double sec = to_double(a[2], "SECONDS");
      if ((a[1] != "clog" && a[1] != "rule") || !(sec > 0) || sec > 60)
        throw core::InputError(
            "usage: freeze clog|rule SECONDS (0 < SECONDS <= 60, video seconds) | freeze off");
      freeze_at = a[1] == "clog" ? 1 : 2;
      freeze_s = sec;
      return log("freeze " + a[1] + " " + a[2]);
    }
    if (cmd == "colormap")
      return need(1, "colormap viridis|magma|inferno|cividis"), style.colormap = render::parse_colormap(a[1]),
                                                                log("colormap " + a[1]);
    if (cmd == "palette")
      return need(1, "palette paper|colorblind"), set_palette(render::parse_palette(a[1]), a[1]);
    if (cmd == "overlay")
      return need(1, "overlay all|none|time,counts,rate,timer,arch,legend,scale"), set_overlay(a[1]);
    if (cmd == "arch") {
      need(1, "arch on|off");
      if (a[1] != "on" && a[1] != "off") throw core::InputError("usage: arch on|off");
      return show_arch(a[1] == "on");
    }
    if (cmd == "track") {
      // track IDS (comma-separated) | off: a ring and a trail of the last 2 s on each, as record --track.
      // track region X0,Y0,X1,Y1: the grains whose centres are in the box in this frame; track arch K: the
      // members of the K-th long-lasting arch (the arch shown on the frame before the rule removed it);
      // track clog K: the arch standing where clog K is shown (goto clog K).
      if (a.size() == 3 && (a[1] == "region" || a[1] == "arch" || a[1] == "clog")) {
        std::vector<int> ids;
        if (a[1] == "region") {
          double x0, y0, x1, y1;
          char tail = 0;
          if (std::sscanf(a[2].c_str(), "%lf,%lf,%lf,%lf%c", &x0, &y0, &x1, &y1, &tail) != 4)
            throw core::InputError("usage: track region X0,Y0,X1,Y1 (metres)");
          if (x0 > x1) std::swap(x0, x1);
          if (y0 > y1) std::swap(y0, y1);
          const auto& ps = traj_.frame(frame_).particles;
          for (size_t i = 0; i < ps.size(); ++i)
            if (ps[i].x >= x0 && ps[i].x <= x1 && ps[i].y >= y0 && ps[i].y <= y1)
              ids.push_back(static_cast<int>(i));
          if (ids.empty())
            throw core::InputError("track region " + a[2] + ": no grain's centre is in the box");
        } else {
          // Found as goto finds it, without moving (the frame and the history stay).
          const long keep = frame_;
          const size_t logged = history_.size();
          a[1] == "arch" ? goto_arch(to_long(a[2], "K")) : goto_clog(to_long(a[2], "K"));
          ids = traj_.frame(frame_).arch;
          frame_ = keep;
          history_.resize(logged);
          if (ids.empty())
            throw core::InputError("track " + a[1] + " " + a[2] + ": no arch stands in that frame");
        }
        style.tracked = ids;
        log("track " + a[1] + " " + a[2]);
        return;
      }
      need(1, "track ID[,ID...]|off | track region X0,Y0,X1,Y1 | track arch K | track clog K");
      style.tracked.clear();
      if (a[1] == "off") return;
      const long n = static_cast<long>(traj_.frame(frame_).particles.size());
      std::stringstream ids(a[1]);
      for (std::string id; std::getline(ids, id, ',');) {
        const long v = to_long(id, "ID");
        if (v < 0 || v >= n)
          throw core::InputError("track: grain " + id + " does not exist; ids run from 0 to " +
                                 std::to_string(n - 1));
        style.tracked.push_back(static_cast<int>(v));
      }
      return;
    }
    if (cmd == "print") return (void)print_frame();
    if (cmd == "snapshot") {
      if (a.size() < 2 || a.size() > 3) throw core::InputError("usage: snapshot FILE.png|.svg|.pdf [WxH]");
      int w = 1920, h = 1080;
      if (a.size() == 3) render::parse_size(a[2], "snapshot size", w, h);
      return (void)snapshot(a[1], w, h, painter);
    }
    if (cmd == "export") return export_command(a, painter);
  } catch (const core::InputError& e) {
    throw core::InputError("'" + line + "': " + e.what());
  }
  throw core::InputError("unknown command '" + cmd + "'; commands are " + kCommands);
}

void Inspector::export_command(const std::vector<std::string>& a, Painter* painter) {
  const bool clog = a.size() >= 3 && a[1] == "clog";
  if (clog ? a.size() > 5 : (a.size() < 4 || a.size() > 6))
    throw core::InputError(
        clog ? "usage: export clog FILE.mp4 [WxH] [FPS]"
             : "usage: export FILE.mp4 FROM TO [WxH] [FPS] | export clog FILE.mp4 [WxH] [FPS]");
  const size_t opt = clog ? 3 : 4;  // index of the first optional argument
  int width = 1280, height = 720;
  if (a.size() > opt) render::parse_size(a[opt], "export size", width, height);
  const int fps = a.size() > opt + 1
                      ? static_cast<int>(to_long(a[opt + 1], "FPS"))
                      : std::max(1, static_cast<int>(std::lround(1.0 / traj_.frame_interval())));
  if (clog)
    export_clog(a[2], width, height, fps, painter);
  else
    export_frames(a[1], to_long(a[2], "FROM"), to_long(a[3], "TO"), width, height, fps, painter);
}

int run_script(Inspector& insp, Painter& painter, const std::string& path) {
  core::check_text_file(path, "inspector script", "");
  std::ifstream in(path);
  if (!in) throw core::InputError(path + ": cannot open script");
  int line_no = 0, commands = 0;
  for (std::string line; std::getline(in, line);) {
    ++line_no;
    try {
      const size_t before = line.find_first_not_of(" \t");
      if (before == std::string::npos || line[before] == '#') continue;
      insp.execute(line, &painter);
      ++commands;
    } catch (const core::InputError& e) {
      throw core::InputError(path + ":" + std::to_string(line_no) + ": " + e.what());
    }
  }
  return commands;
}

}  // namespace ui
