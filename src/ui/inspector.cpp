// The inspector's state and typed actions (ui/inspector.h): navigation by frame, time, clog and arch, the
// camera, the look, selection and tracking, the arch table and the pictures it makes. Over 400 lines because
// they are one object's methods over one state, which the window, the script language and the tests all
// drive; the script's parser (inspector_script.cpp), the session (inspector_session.cpp) and the grain
// details (inspector_grains.cpp) are files of their own.
#include "ui/inspector.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>

#include "core/arch.h"
#include "core/error.h"
#include "core/format.h"
#include "core/interrupt.h"
#include "core/scene.h"
#include "render/draw_list.h"
#include "render/grain_values.h"

namespace ui {

Inspector::Inspector(const FrameSource& traj, const core::Model& model, const ImageFiles* files)
    : traj_(traj), files_(files), model_(model), geo_(model.setup.geo) {
  if (traj_.size() == 0) throw core::InputError("the trajectory holds no complete frame");
  overlay_data = render::overlay_data_for(model_);
  // Clogs: the run's own (the trajectory's events, the rows of clogs.csv), placed on the frames.
  const long n = traj_.size();
  long k = 0;
  for (const core::ClogEvent& c : traj_.clogs()) {
    while (k + 1 < n && traj_.time(k) < c.start - 1e-9) ++k;
    long last = k;
    while (last + 1 < n && traj_.time(last + 1) < c.end - 1e-9) ++last;
    clogs_.push_back({k, last, c.end - c.start, c.ended_by == core::ClogEnd::Rule, c});
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
  if (branch_) return render_branch(p, w, h);
  // Pictures (snapshots, clips) place the information box where it covers the fewest grains, as movies do
  // (with the discharge plot, the plot takes the free space and the box keeps the top-right corner); it
  // stays in the picture.
  render::OverlayOptions o = overlay;
  o.place_clear = !o.plot;
  o.may_leave = false;
  const core::Frame ref = reference_frame();
  const core::Frame f = current();
  // Where the container (zoomed as it is) leaves the boxes no clear space, the picture keeps a margin on its
  // right for them, as record's movies do.
  render::OverlayData od = overlay_data;
  if (o.any())
    od.margin_w = render::overlay_margin(
        [&](int width) { return std::vector<std::vector<render::View>>{views(width, h)}; }, geo_, o, 0, w, h,
        od.species_names, od.title, !render::color_scale_label(style).empty() || style.chains);
  const auto vs = views(w - od.margin_w, h);
  render::Annotations marks;
  marks.selected = static_cast<int>(selected);
  for (const auto& n : notes)
    if (f.t >= n.t0 - 1e-9 && f.t <= n.t1 + 1e-9)
      marks.texts.push_back({static_cast<float>(n.x), static_cast<float>(n.y), n.text});
  return p.paint({{&f, &geo_, &vs, &od, &marks, ref.particles.empty() ? nullptr : &ref}}, style, o, w, h);
}

long Inspector::in_range(long k) const {
  if (k < 0 || k >= traj_.size())
    throw core::InputError("frame " + std::to_string(k) + " is out of range (0 to " +
                           std::to_string(traj_.size() - 1) + ")");
  return k;
}

void Inspector::goto_frame(long k) {
  frame_ = in_range(k);
  log("goto frame " + std::to_string(k));
}

void Inspector::goto_time(double t) {
  if (t < traj_.time(0) - 1e-9 || t > traj_.time(traj_.size() - 1) + 1e-9)
    throw core::InputError("time " + core::format_g(t, 6) + " s is outside the trajectory (" +
                           core::format_g(traj_.time(0), 6) + " to " +
                           core::format_g(traj_.time(traj_.size() - 1), 6) + " s)");
  long best = 0;
  for (long k = 0; k < traj_.size(); ++k)
    if (std::abs(traj_.time(k) - t) < std::abs(traj_.time(best) - t)) best = k;
  frame_ = best;
  log("goto time " + core::format_shortest(t));
}

long Inspector::clog_at(long k) const {
  for (size_t i = 0; i < clogs_.size(); ++i)
    if (clogs_[i].first <= k && k <= clogs_[i].last) return static_cast<long>(i);
  return -1;
}

long Inspector::final_arch_frame(size_t i) const {
  const ClogSpan& c = clogs_[i];
  // The clog's last frame that shows an arch (a kick may have parted it at the end), then back while the same
  // grains stand: through the frames of its forming, when this is the arch that clogged (trajectories since
  // version 3 show it from its formation, core::ClogEvent::formed).
  long k = c.last;
  while (k > c.first && traj_.frame(k).arch.empty()) --k;
  const std::vector<int> final_arch = traj_.frame(k).arch;
  if (final_arch.empty()) return c.last;
  // Frames where a kick held its grains apart show no arch: passed over, back to the first frame that shows
  // it.
  long first = k;
  for (long j = k - 1; j >= c.first; --j) {
    const std::vector<int> a = traj_.frame(j).arch;
    if (a.empty()) continue;
    if (!core::same_grains(a, final_arch)) break;
    first = j;
  }
  return first;
}

std::string Inspector::clog_caption(size_t i) const {
  const core::ClogEvent& e = clogs_[i].event;
  // Each rule firing closes exactly one clog: its row of arches.csv is the count of rule-ended clogs so far.
  long row = 0;
  for (size_t j = 0; j <= i; ++j) row += clogs_[j].event.ended_by == core::ClogEnd::Rule;
  char text[200];
  const char* how = e.ended_by == core::ClogEnd::Rule          ? "ended by the rule"
                    : e.ended_by == core::ClogEnd::Vibration   ? "broken by the drive"
                    : e.ended_by == core::ClogEnd::Spontaneous ? "ended by itself"
                                                               : "open when the run ended";
  std::snprintf(text, sizeof text, "clog %zu of %zu, %.3f-%.3f s, %s%s", i + 1, clogs_.size(), e.start, e.end,
                how, e.arrested ? " (arrested)" : "");
  std::string out = text;
  if (e.ended_by == core::ClogEnd::Rule) out += ", arches.csv row " + std::to_string(row);
  return out;
}

void Inspector::goto_clog(long k) {
  if (k < 1 || k > static_cast<long>(clogs_.size()))
    throw core::InputError("clog " + std::to_string(k) + " does not exist; the trajectory has " +
                           std::to_string(clogs_.size()) + " clogs (numbered from 1)");
  frame_ = clogs_[static_cast<size_t>(k - 1)].first;
  log("goto clog " + std::to_string(k));
}

void Inspector::goto_clog_arch(long k) {
  if (k < 1 || k > static_cast<long>(clogs_.size()))
    throw core::InputError("clog " + std::to_string(k) + " does not exist; the trajectory has " +
                           std::to_string(clogs_.size()) + " clogs (numbered from 1)");
  frame_ = final_arch_frame(static_cast<size_t>(k - 1));
  log("goto clog " + std::to_string(k) + " arch");
}

void Inspector::next_arch_change(bool later) {
  const std::vector<int> here = traj_.frame(frame_).arch;
  long k = frame_;
  for (k += later ? 1 : -1; k >= 0 && k < traj_.size(); k += later ? 1 : -1)
    if (!core::same_grains(traj_.frame(k).arch, here)) break;
  if (k < 0 || k >= traj_.size())
    throw core::InputError(std::string("the arch does not change ") + (later ? "after" : "before") +
                           " this frame");
  frame_ = k;
  log(later ? "next arch" : "prev arch");
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
  // By the clogs' starts: the first one after this frame, or the last one before it.
  const ClogSpan* hit = nullptr;
  if (later) {
    for (const auto& c : clogs_)
      if (c.first > frame_) {
        hit = &c;
        break;
      }
  } else {
    for (auto it = clogs_.rbegin(); it != clogs_.rend(); ++it)
      if (it->first < frame_) {
        hit = &*it;
        break;
      }
  }
  if (!hit) throw core::InputError(std::string("there is no ") + (later ? "later" : "earlier") + " clog");
  frame_ = hit->first;
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

void Inspector::zoom_to(double f) {
  if (!(f >= 0.1 && f <= 100))
    throw core::InputError("zoom " + core::format_shortest(f) + ": the magnification must be 0.1 to 100");
  zoom = f;
  log("zoom to " + core::format_shortest(f));
}

void Inspector::pan_to(double x, double y) {
  pan = {x, y};
  log("pan to " + core::format_shortest(x) + " " + core::format_shortest(y));
}

void Inspector::pan_by(double dx, double dy) {
  pan.x += dx;
  pan.y += dy;
  log("pan " + std::to_string(dx) + " " + std::to_string(dy));
}

void Inspector::switch_color(render::Style& st, render::ColorMode m, ColorMins& mins) {
  if (st.color == m) return;
  mins.at(static_cast<size_t>(st.color)) = st.color_min;
  st.color = m;
  st.color_min = mins.at(static_cast<size_t>(m));
}

void Inspector::set_color(render::ColorMode m, const std::string& name) {
  switch_color(style, m, color_mins_);
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

void Inspector::set_look(const render::Style& st, const render::OverlayOptions& o,
                         const std::vector<render::TimedNote>& n,
                         const std::vector<render::Rgba>& species_colors) {
  const std::vector<int> tracked = style.tracked;
  const double trail = style.trail_s;
  style = st;
  style.tracked = tracked;
  style.trail_s = trail;
  overlay = o;
  notes = n;
  overlay_data.species_colors = species_colors;
  for (const auto& line : state_lines())
    if (line.rfind("palette", 0) == 0 || line.rfind("color", 0) == 0 || line.rfind("overlay", 0) == 0 ||
        line.rfind("background", 0) == 0 || line.rfind("font-scale", 0) == 0 ||
        line.rfind("species-color", 0) == 0 || line.rfind("arch", 0) == 0 || line.rfind("chains", 0) == 0)
      log(line);
  for (const auto& note : notes)
    log("annotate " + core::format_g(note.t0, 9) + ":" + core::format_g(note.t1, 9) + ":" +
        core::format_g(note.x, 9) + "," + core::format_g(note.y, 9) + ":" + note.text);
}

void Inspector::show_arch(bool on) {
  style.show_arch = on;
  log(on ? "arch on" : "arch off");
}

void Inspector::track_region(double x0, double y0, double x1, double y1) {
  const std::string text = core::format_g(x0, 6) + "," + core::format_g(y0, 6) + "," + core::format_g(x1, 6) +
                           "," + core::format_g(y1, 6);
  if (x0 > x1) std::swap(x0, x1);
  if (y0 > y1) std::swap(y0, y1);
  std::vector<int> ids;
  const auto& ps = traj_.frame(frame_).particles;
  for (size_t i = 0; i < ps.size(); ++i)
    if (ps[i].x >= x0 && ps[i].x <= x1 && ps[i].y >= y0 && ps[i].y <= y1) ids.push_back(static_cast<int>(i));
  if (ids.empty()) throw core::InputError("track region " + text + ": no grain's centre is in the box");
  style.tracked = ids;
  log("track region " + text);
}

void Inspector::track_arch_of(bool clog, long k) {
  // Found as goto finds it (a clog's final arch: `goto clog K arch`), without moving (the frame and the
  // history stay).
  const long keep = frame_;
  const size_t logged = history_.size();
  clog ? goto_clog_arch(k) : goto_arch(k);
  const std::vector<int> ids = traj_.frame(frame_).arch;
  frame_ = keep;
  history_.resize(logged);
  const std::string line = std::string("track ") + (clog ? "clog " : "arch ") + std::to_string(k);
  if (ids.empty()) throw core::InputError(line + ": no arch stands in that frame");
  style.tracked = ids;
  log(line);
}

std::string Inspector::print_frame() {
  const core::Frame f = current();
  std::ostringstream o;
  o << "frame " << frame_ << " t = " << f.t << " s, clog timer " << f.since_last_exit << " s, ";
  if (f.clog_open)
    o << "clog " << f.clog_number << " open" << (f.clog_arrested ? " (arrested)" : "");
  else if (f.arch_forming)
    o << "clog " << f.clog_number << " forming (its arch stands, not yet confirmed)";
  else
    o << "flowing";
  o << ", arch [";
  for (size_t k = 0; k < f.arch.size(); ++k) o << (k ? " " : "") << f.arch[k];
  o << "]";
  last_output = o.str();
  std::printf("%s\n", last_output.c_str());
  return last_output;
}

std::string Inspector::print_clogs() {
  std::string all;
  for (size_t k = 0; k < clogs_.size(); ++k) {
    const ClogSpan& c = clogs_[k];
    char line[160];
    std::snprintf(line, sizeof line, "clog %zu %.6f %.6f %s %s frames %ld-%ld\n", k + 1, c.event.start,
                  c.event.end, core::clog_end_name(c.event.ended_by),
                  c.event.arrested ? "arrested" : "not-arrested", c.first, c.last);
    all += line;
  }
  std::printf("%s", all.c_str());
  last_output = all;
  log("clogs");
  return all;
}

std::string Inspector::vector_table(int w, int h, double& width_m, double& height_m,
                                    std::string& caption) const {
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
  gv.settle_scale(st);
  const std::string table =
      render::draw_list_csv(render::build_draw_list(f, geo_, st, {}, &values, render::color_scale_max(st)),
                            v->cam.cx, v->cam.cy, v->cam.angle, half_w, half_h);
  char head[160];
  std::snprintf(head, sizeof head, "t = %.3f s (frame %ld), clog timer %.2f s, arch: %zu grains", f.t, frame_,
                f.since_last_exit, f.arch.size());
  std::string text = head;
  const std::string scale = render::color_scale_label(st);
  if (!scale.empty()) {
    char range[96];
    std::snprintf(range, sizeof range, " from %.3g to %.3g (%s)", st.color_min, render::color_scale_max(st),
                  render::colormap_name(st.colormap));
    text += "\ncolour: " + scale + range;
  }
  width_m = 2 * half_w;
  height_m = 2 * half_h;
  caption = text;
  return table;
}

std::string Inspector::vector_key() const {
  // As the bitmap pictures, by the overlay's elements: the information box (the caption already gives the
  // time, the clog timer and the arch's size), the legend, the colour bar and the scale bar.
  const render::OverlayOptions& o = overlay;
  const core::Frame f = current();
  render::Style st = style;
  st.species_colors = overlay_data.species_colors;
  std::string k;
  char line[200];
  if (o.time || o.counts || o.timer) {
    if (!overlay_data.title.empty()) k += "info\t" + overlay_data.title + "\n";
    if (o.counts) {
      std::string exits = "info\texits:";
      for (size_t s = 0; s < overlay_data.species_names.size(); ++s)
        exits += (s ? ", " : " ") + std::to_string(f.exits_of(static_cast<int>(s))) + " " +
                 overlay_data.species_names[s];
      k += exits + "\n";
    }
    if (o.timer) {
      if (f.clog_open)
        std::snprintf(line, sizeof line, "info\tclog %d open%s\n", f.clog_number,
                      f.clog_arrested ? " (arrested)" : "");
      else if (f.arch_forming)
        std::snprintf(line, sizeof line, "info\tclog %d forming\n", f.clog_number);
      else
        std::snprintf(line, sizeof line, "info\tflowing\n");
      k += line;
    }
  }
  const std::string scale = render::color_scale_label(st);
  if (o.legend) {
    if (scale.empty())
      for (size_t s = 0; s < overlay_data.species_names.size(); ++s)
        k += "species\t" + overlay_data.species_names[s] + "\t" +
             render::hex_rgb(render::species_color(st, static_cast<core::Species>(s))) + "\n";
    if (st.show_arch && !f.arch.empty())
      k += "arch\tarch members\t" + render::hex_rgb(render::arch_color(st)) + "\n";
  }
  if (!scale.empty() && (o.legend || o.colorbar)) {
    std::snprintf(line, sizeof line, "\t%.6g\t%.6g\t%s\n", st.color_min, render::color_scale_max(st),
                  render::colormap_name(st.colormap));
    k += "colorbar\t" + scale + line;
  }
  if (o.scale) {
    std::snprintf(line, sizeof line, "scale\t%.6g\t1 d = %.3g cm\n", overlay_data.diameter,
                  100 * overlay_data.diameter);
    k += line;
  }
  // The background and text size always (overlay none: the picture alone, in its look).
  return std::string("background\t") + (st.dark ? "dark" : "white") + "\nfont_scale\t" +
         core::format_g(o.font_scale, 6) + "\n" + k;
}

std::string Inspector::snapshot(const std::string& pattern, int w, int h, Painter* painter) {
  if (!painter || !files_) throw core::InputError("snapshot needs a renderer and files");
  const std::string path = output_name(pattern, "snapshot " + pattern);
  const std::string ext = std::filesystem::path(path).extension().string();
  if (ext == ".svg" || ext == ".pdf") {
    double width_m = 0, height_m = 0;
    std::string text;
    const std::string table = vector_table(w, h, width_m, height_m, text);
    files_->write_vector(path, table, width_m, height_m, text, vector_key());
  } else {
    painter->start_afresh();  // the picture of this state alone, as a replayed script makes it
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
  painter->start_afresh();
  const long copies = freeze.copies(fps);
  for (long k = from; k <= to; ++k) {
    core::throw_if_interrupted();  // the clip's partial file goes with its writer
    frame_ = k;
    const core::Image img = render_current(*painter, width, height);
    movie->add(img);
    // A freeze: by the movie's own rule (render::freeze_fires): the first frame showing a clog's arch, or the
    // last frame before the rule fires.
    const core::Frame now = traj_.frame(k);
    const std::optional<core::Frame> before =
        k > 0 ? std::optional<core::Frame>(traj_.frame(k - 1)) : std::nullopt;
    const bool rule_next = k + 1 < traj_.size() && traj_.long_arches(k + 1) > traj_.long_arches(k);
    const bool event = freeze && render::freeze_fires(freeze, before ? &*before : nullptr, now, rule_next);
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

}  // namespace ui
