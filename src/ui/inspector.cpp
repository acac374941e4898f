#include "ui/inspector.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.h"

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
    "goto, step, next, prev, zoom, pan, color, palette, overlay, arch, snapshot, export, print";
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
    clogs_.push_back({k, last, longest, removed});
    k = last;
  }
}

void Inspector::set_frame(long k) {
  frame_ = std::clamp(k, 0L, traj_.size() - 1);
}

std::vector<render::View> Inspector::views(int w, int h) const {
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

core::Image Inspector::render_current(Painter& p, int w, int h) const {
  return p.paint(current(), geo_, views(w, h), style, overlay, overlay_data, w, h);
}

void Inspector::execute(const std::string& line, Painter* painter) {
  std::stringstream ss(line);
  std::vector<std::string> a;
  for (std::string word; ss >> word;) {
    if (word[0] == '#') break;
    a.push_back(word);
  }
  if (a.empty()) return;
  const std::string& cmd = a[0];
  auto need = [&](size_t n, const char* usage) {
    if (a.size() < n + 1 || a.size() > n + 1) throw core::InputError("'" + line + "': usage: " + usage);
  };
  auto in_range = [&](long k) {
    if (k < 0 || k >= traj_.size())
      throw core::InputError("'" + line + "': frame " + std::to_string(k) + " is out of range (0 to " +
                             std::to_string(traj_.size() - 1) + ")");
    return k;
  };
  if (cmd == "goto") {
    if (a.size() == 2 && (a[1] == "start" || a[1] == "end")) {
      frame_ = a[1] == "start" ? 0 : traj_.size() - 1;
      return;
    }
    need(2, "goto frame N | goto time T | goto clog K | goto arch K | goto start | goto end");
    if (a[1] == "frame") {
      frame_ = in_range(to_long(a[2], "frame"));
    } else if (a[1] == "time") {
      const double t = to_double(a[2], "time");
      if (t < traj_.time(0) - 1e-9 || t > traj_.time(traj_.size() - 1) + 1e-9)
        throw core::InputError("'" + line + "': time " + a[2] + " s is outside the trajectory (" +
                               std::to_string(traj_.time(0)) + " to " +
                               std::to_string(traj_.time(traj_.size() - 1)) + " s)");
      long best = 0;
      for (long k = 0; k < traj_.size(); ++k)
        if (std::abs(traj_.time(k) - t) < std::abs(traj_.time(best) - t)) best = k;
      frame_ = best;
    } else if (a[1] == "clog") {
      const long k = to_long(a[2], "clog");
      if (k < 1 || k > static_cast<long>(clogs_.size()))
        throw core::InputError("'" + line + "': clog " + a[2] + " does not exist; the trajectory has " +
                               std::to_string(clogs_.size()) + " clogs (numbered from 1)");
      frame_ = clogs_[k - 1].last;
    } else if (a[1] == "arch") {
      const long k = to_long(a[2], "arch");
      long found = -1;
      for (long f = 1; f < traj_.size() && found < 0; ++f)
        if (traj_.long_arches(f) >= k && traj_.long_arches(f - 1) < k) found = f - 1;
      if (k < 1 || found < 0)
        throw core::InputError("'" + line + "': long-lasting arch " + a[2] +
                               " is not in the trajectory (it has " +
                               std::to_string(traj_.long_arches(traj_.size() - 1)) + ")");
      frame_ = found;
    } else {
      throw core::InputError("'" + line + "': goto frame|time|clog|arch|start|end");
    }
  } else if (cmd == "step") {
    need(1, "step N");
    frame_ = in_range(frame_ + to_long(a[1], "step"));
  } else if (cmd == "next" || cmd == "prev") {
    need(1, "next clog | prev clog");
    if (a[1] != "clog") throw core::InputError("'" + line + "': usage: next clog | prev clog");
    const ClogSpan* hit = nullptr;
    if (cmd == "next") {
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
    if (!hit)
      throw core::InputError("'" + line + "': there is no " + (cmd == "next" ? "later" : "earlier") +
                             " clog");
    frame_ = hit->last;
  } else if (cmd == "zoom") {
    if (a.size() == 3 && a[1] == "by") {
      const double f = to_double(a[2], "zoom factor");
      if (!(f > 0)) throw core::InputError("'" + line + "': the zoom factor must be > 0");
      zoom = std::clamp(zoom * f, 0.1, 100.0);
      return;
    }
    need(1, "zoom hopper|outlet|split|window:X0,Y0,X1,Y1 | zoom by F");
    camera = render::parse_camera(a[1]);
    zoom = 1.0;
    pan = {0, 0};
  } else if (cmd == "pan") {
    need(2, "pan DX DY (metres)");
    pan.x += to_double(a[1], "DX");
    pan.y += to_double(a[2], "DY");
  } else if (cmd == "color") {
    need(1, "color species|speed|force");
    style.color = render::parse_color_mode(a[1]);
  } else if (cmd == "palette") {
    need(1, "palette paper|colorblind");
    style.palette = render::parse_palette(a[1]);
  } else if (cmd == "overlay") {
    need(1, "overlay all|none|time,counts,rate,timer,arch,legend,scale");
    overlay = render::parse_overlay(a[1]);
  } else if (cmd == "arch") {
    need(1, "arch on|off");
    if (a[1] != "on" && a[1] != "off") throw core::InputError("'" + line + "': usage: arch on|off");
    style.show_arch = a[1] == "on";
  } else if (cmd == "print") {
    const core::Frame f = current();
    std::ostringstream o;
    o << "frame " << frame_ << " t = " << f.t << " s, clog timer " << f.since_last_exit << " s, arch [";
    for (size_t k = 0; k < f.arch.size(); ++k) o << (k ? " " : "") << f.arch[k];
    o << "]";
    last_output = o.str();
    std::printf("%s\n", last_output.c_str());
  } else if (cmd == "snapshot") {
    if (a.size() < 2 || a.size() > 3)
      throw core::InputError("'" + line + "': usage: snapshot FILE.png [WxH]");
    int w = 1920, h = 1080;
    if (a.size() == 3) render::parse_size(a[2], "snapshot size", w, h);
    if (!painter || !files_) throw core::InputError("'" + line + "': snapshot needs a renderer and files");
    const std::string path = output_name(a[1], line);
    files_->write_png(path, render_current(*painter, w, h));
    last_output = path;
  } else if (cmd == "export") {
    // export clog FILE.mp4 [WxH] [FPS]: the clog at (or after) this frame, from 1 s before it forms to 0.5 s
    // after it ends.
    long from = 0, to = 0;
    size_t opt = 4;  // index of the first optional argument
    std::string file;
    if (a.size() >= 3 && a[1] == "clog") {
      if (a.size() > 5) throw core::InputError("'" + line + "': usage: export clog FILE.mp4 [WxH] [FPS]");
      const ClogSpan* hit = nullptr;
      for (const auto& c : clogs_)
        if (c.last >= frame_) {
          hit = &c;
          break;
        }
      if (!hit)
        throw core::InputError("'" + line + "': there is no clog at or after frame " +
                               std::to_string(frame_));
      const double dt = traj_.frame_interval();
      from = std::max(0L, hit->first - std::lround(1.0 / dt));
      to = std::min(traj_.size() - 1, hit->last + std::lround(0.5 / dt));
      file = a[2];
      opt = 3;
    } else {
      if (a.size() < 4 || a.size() > 6)
        throw core::InputError(
            "'" + line + "': usage: export FILE.mp4 FROM TO [WxH] [FPS] | export clog FILE.mp4 [WxH] [FPS]");
      from = in_range(to_long(a[2], "FROM"));
      to = in_range(to_long(a[3], "TO"));
      if (to < from) throw core::InputError("'" + line + "': TO must not be before FROM");
      file = a[1];
    }
    int width = 1280, height = 720;
    if (a.size() > opt) render::parse_size(a[opt], "export size", width, height);
    const int fps = a.size() > opt + 1
                        ? static_cast<int>(to_long(a[opt + 1], "FPS"))
                        : std::max(1, static_cast<int>(std::lround(1.0 / traj_.frame_interval())));
    if (!painter || !files_) throw core::InputError("'" + line + "': export needs a renderer and files");
    files_->check_movie(width, height, fps);
    const std::string path = output_name(file, line);
    auto movie = files_->open_movie(path, width, height, fps);
    const long keep = frame_;
    for (long k = from; k <= to; ++k) {
      frame_ = k;
      movie->add(render_current(*painter, width, height));
    }
    frame_ = keep;
    movie->finish();
    last_output = path + " (frames " + std::to_string(from) + " to " + std::to_string(to) + ")";
  } else {
    throw core::InputError("unknown command '" + cmd + "'; commands are " + kCommands);
  }
}

int run_script(Inspector& insp, Painter& painter, const std::string& path) {
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
