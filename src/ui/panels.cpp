#include "ui/panels.h"

#include <cmath>
#include <functional>

#include <imgui.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <utility>

#include "core/arch.h"
#include "core/error.h"

namespace ui {

namespace {
void remember(PanelState& ps, const char* name) {
  ImVec2 a = ImGui::GetItemRectMin(), b = ImGui::GetItemRectMax();
  ps.rects[name] = {a.x, a.y, b.x, b.y};
}
const char* kSizes[] = {"1920x1080", "3840x2160", "1280x720", "2048x2048"};
}  // namespace

void act(Inspector& insp, PanelState& ps, const std::function<void()>& action, bool writes) {
  try {
    insp.last_output.clear();
    action();
    // What it did, as the script line that repeats it (or the file it wrote).
    ps.message = writes && !insp.last_output.empty() ? "wrote " + insp.last_output
                 : insp.history().empty()            ? ""
                                                     : insp.history().back();
  } catch (const std::exception& e) {
    ps.message = e.what();
  }
}

void go_to(Inspector& insp, const std::string& text) {
  const size_t a = text.find_first_not_of(" \t"), b = text.find_last_not_of(" \t");
  const std::string t = a == std::string::npos ? "" : text.substr(a, b - a + 1);
  const std::string form = "'" + t + "': give a frame (120), a time (4.5 s) or a step (+30, -5)";
  if (t.empty()) throw core::InputError(form);
  char* end = nullptr;
  errno = 0;
  if (t.back() == 's') {
    const double s = std::strtod(t.c_str(), &end);
    if (end == t.c_str() ||
        t.find_first_not_of(" s", static_cast<size_t>(end - t.c_str())) != std::string::npos)
      throw core::InputError(form);
    return insp.goto_time(s);
  }
  const long n = std::strtol(t.c_str(), &end, 10);
  if (end == t.c_str() || *end != '\0' || errno == ERANGE) throw core::InputError(form);
  if (t[0] == '+' || t[0] == '-') return insp.step_frames(n);
  insp.goto_frame(n);
}

void final_arch(Inspector& insp) {
  long i = insp.clog_at(insp.frame_index());
  if (i < 0)
    for (size_t j = 0; j < insp.clogs().size() && i < 0; ++j)
      if (insp.clogs()[j].first > insp.frame_index()) i = static_cast<long>(j);
  if (i < 0) throw core::InputError("there is no clog here or later");
  insp.goto_clog_arch(i + 1);
}

void play_to_next_clog(Inspector& insp, PanelState& ps) {
  ps.play_until = -1;
  for (const auto& c : insp.clogs())
    if (c.first > insp.frame_index()) {
      ps.play_until = c.first;
      break;
    }
  ps.playing = ps.play_until >= 0;
  ps.message = ps.playing ? "playing to the next clog" : "there is no later clog";
}

void advance_playback(Inspector& insp, PanelState& ps, long frames) {
  const long target = insp.frame_index() + frames;
  if (ps.play_until >= 0 && target >= ps.play_until) {
    // Arrived: the same place `goto clog K` lands, written down as that.
    const long k = insp.clog_at(ps.play_until);
    ps.play_until = -1;
    ps.playing = false;
    if (k >= 0) return act(insp, ps, [&] { insp.goto_clog(k + 1); });
  }
  insp.set_frame(target);
  if (insp.frame_index() == insp.trajectory().size() - 1) ps.playing = false;
}

namespace {
void draw_transport(Inspector& insp, PanelState& ps, long n, const core::Frame& f) {
  // Transport.
  int frame = static_cast<int>(insp.frame_index());
  ImGui::SetNextItemWidth(-1);
  if (ImGui::SliderInt("##frame", &frame, 0, static_cast<int>(n - 1), "frame %d")) insp.set_frame(frame);
  remember(ps, "frame");
  ImGui::Text("t = %.3f s   clog timer %.2f s", f.t, f.since_last_exit);
  if (ImGui::Button("|<")) act(insp, ps, [&] { insp.goto_start(); });
  ImGui::SameLine();
  if (ImGui::Button("< clog")) act(insp, ps, [&] { insp.next_clog(false); }), ps.playing = false;
  remember(ps, "prev clog");
  ImGui::SameLine();
  if (ImGui::Button("<")) insp.set_frame(insp.frame_index() - 1);
  remember(ps, "step back");
  ImGui::SameLine();
  if (ImGui::Button(ps.playing ? "pause" : "play")) ps.playing = !ps.playing;
  remember(ps, "play");
  ImGui::SameLine();
  if (ImGui::Button(">")) insp.set_frame(insp.frame_index() + 1);
  remember(ps, "step forward");
  ImGui::SameLine();
  if (ImGui::Button("clog >")) act(insp, ps, [&] { insp.next_clog(true); }), ps.playing = false;
  remember(ps, "next clog");
  ImGui::SameLine();
  if (ImGui::Button(">|")) act(insp, ps, [&] { insp.goto_end(); });
  // Navigation by the run's events: the final arch of this clog, the changes of arch, play to the next clog.
  if (ImGui::Button("final arch (a)")) act(insp, ps, [&] { final_arch(insp); });
  remember(ps, "final arch");
  ImGui::SameLine();
  if (ImGui::Button("< arch")) act(insp, ps, [&] { insp.next_arch_change(false); });
  remember(ps, "prev arch");
  ImGui::SameLine();
  if (ImGui::Button("arch >")) act(insp, ps, [&] { insp.next_arch_change(true); });
  remember(ps, "next arch");
  ImGui::SameLine();
  if (ImGui::Button("play to clog (c)")) play_to_next_clog(insp, ps);
  remember(ps, "play to clog");
  ImGui::SetNextItemWidth(10 * ImGui::GetFontSize());
  if (ImGui::InputTextWithHint("##goto", "go to: 120, 4.5 s, +30", ps.go_to, sizeof ps.go_to,
                               ImGuiInputTextFlags_EnterReturnsTrue))
    act(insp, ps, [&] { go_to(insp, ps.go_to); });
  remember(ps, "go to");
  const long here = insp.clog_at(insp.frame_index());
  if (here >= 0)
    ImGui::TextWrapped("%s", insp.clog_caption(static_cast<size_t>(here)).c_str());
  else
    ImGui::TextUnformatted("flowing (no clog at this frame)");
  ImGui::SetNextItemWidth(-1);
  ImGui::SliderFloat("##speed", &ps.speed, 0.05f, 10.0f, "playback %.2fx", ImGuiSliderFlags_Logarithmic);
}

void draw_view(Inspector& insp, PanelState& ps) {
  // View.
  ImGui::Separator();
  const char* cams[] = {"split", "outlet", "hopper"};
  for (const char* c : cams) {
    if (ImGui::RadioButton(c, insp.camera.text == c))
      act(insp, ps, [&] { insp.set_camera(render::parse_camera(c)); });
    ImGui::SameLine();
  }
  ImGui::NewLine();
  float zoom = static_cast<float>(insp.zoom);
  ImGui::SetNextItemWidth(-1);
  if (ImGui::SliderFloat("##zoom", &zoom, 0.5f, 10.0f, "zoom %.2fx", ImGuiSliderFlags_Logarithmic))
    insp.zoom = zoom;
  remember(ps, "zoom");
  // Each choice calls the action it stands for (the script line `color MODE`).
  const std::pair<const char*, render::ColorMode> colors[] = {
      {"species", render::ColorMode::Species},
      {"speed", render::ColorMode::Speed},
      {"force", render::ColorMode::Force},
      {"displacement", render::ColorMode::Displacement},
      {"coordination", render::ColorMode::Coordination},
      {"id", render::ColorMode::Id}};
  for (size_t k = 0; k < std::size(colors); ++k) {
    if (k > 0 && k != 3) ImGui::SameLine();
    if (ImGui::RadioButton(colors[k].first, insp.style.color == colors[k].second))
      act(insp, ps, [&] { insp.set_color(colors[k].second, colors[k].first); });
  }
  if (insp.style.color != render::ColorMode::Species && insp.style.color != render::ColorMode::Id) {
    // The colour map of the scale (the script line `colormap NAME`).
    for (auto m : {render::Colormap::Viridis, render::Colormap::Magma, render::Colormap::Inferno,
                   render::Colormap::Cividis}) {
      if (m != render::Colormap::Viridis) ImGui::SameLine();
      if (ImGui::RadioButton(render::colormap_name(m), insp.style.colormap == m))
        act(insp, ps, [&] { insp.execute(std::string("colormap ") + render::colormap_name(m)); });
    }
  }
  bool cb = insp.style.palette == render::Palette::ColorBlind;
  if (ImGui::Checkbox("colour-blind palette", &cb))
    insp.style.palette = cb ? render::Palette::ColorBlind : render::Palette::Paper;
  ImGui::SameLine();
  ImGui::Checkbox("arch", &insp.style.show_arch);
  if (insp.has_contacts()) {  // the run kept its contacts: force chains as record draws them
    ImGui::SameLine();
    ImGui::Checkbox("force chains", &insp.style.chains);
  }
  auto& o = insp.overlay;
  ImGui::Checkbox("time", &o.time);
  ImGui::SameLine();
  ImGui::Checkbox("counts", &o.counts);
  ImGui::SameLine();
  ImGui::Checkbox("Q~", &o.rate);
  ImGui::SameLine();
  ImGui::Checkbox("timer", &o.timer);
  ImGui::Checkbox("legend", &o.legend);
  ImGui::SameLine();
  ImGui::Checkbox("scale", &o.scale);
  ImGui::SameLine();
  ImGui::Checkbox("arch info", &o.arch);
}

void draw_arch(Inspector& insp, Painter* painter, const core::Frame& f) {
  // The arch of this frame.
  ImGui::Separator();
  if (f.arch.empty()) {
    ImGui::TextUnformatted("no arch spans the hopper in this frame");
  } else {
    std::vector<core::Vec2> pos;
    std::vector<double> rad;
    for (const auto& p : f.particles) pos.push_back({p.x, p.y}), rad.push_back(p.radius);
    const auto g = core::arch_geometry(f.arch, pos, rad);
    const auto& names = insp.overlay_data.species_names;
    const bool shorthand = names.size() == 2 && names[0] == "original";
    int added = 0;
    for (int id : f.arch) added += f.particles[id].species != core::Species::Original;
    const char* clogging = f.clog_arrested ? ", arrested" : ", clogging";
    if (shorthand)
      ImGui::Text("arch: %zu disks, %d added%s", f.arch.size(), added, clogging);
    else
      ImGui::Text("arch: %zu grains%s", f.arch.size(), clogging);
    ImGui::Text("span %.3f m, height %.3f m, largest angle %.0f deg", g.span, g.height, g.max_angle_deg);
    const auto d = core::arch_descriptors(f.arch, pos, rad);
    ImGui::TextWrapped(
        "rise %.3f m, aspect rise/(span/2) %.2f, theta_max %.0f deg, %d defect%s, bead angles sd %.0f deg",
        d.rise, d.aspect, d.theta_max_deg, d.defects, d.defects == 1 ? "" : "s", d.angle_sd_deg);
    std::string members;
    for (int id : f.arch) {
      const size_t sp = static_cast<size_t>(core::species_index(f.particles[id].species));
      members += std::to_string(id) +
                 (shorthand ? (sp == 1 ? "a " : "o ") : " (" + (sp < names.size() ? names[sp] : "?") + ") ");
    }
    ImGui::TextWrapped(
        shorthand ? "members (left to right, o/a = original/added): %s" : "members (left to right): %s",
        members.c_str());
  }
  ImGui::Text("%zu clogs in this trajectory", insp.clogs().size());
  // No corner of the picture is clear of the container (zoomed in): the information box is shown here.
  if (painter && painter->info_left()) {
    ImGui::Separator();
    render::info_contents(f, insp.overlay_data, insp.overlay, insp.style, ImGui::GetFontSize());
  }
}

void draw_outputs(Inspector& insp, PanelState& ps, Painter* painter, float w) {
  // Outputs.
  ImGui::Separator();
  ImGui::SetNextItemWidth(0.55f * w);
  ImGui::InputText("##snap", ps.snapshot_path, sizeof ps.snapshot_path);
  ImGui::SameLine();
  ImGui::SetNextItemWidth(-1);
  ImGui::Combo("##size", &ps.snapshot_size, kSizes, IM_ARRAYSIZE(kSizes));
  if (ImGui::Button("snapshot this frame"))
    act(
        insp, ps,
        [&] {
          int sw = 0, sh = 0;
          render::parse_size(kSizes[ps.snapshot_size], "snapshot size", sw, sh);
          insp.snapshot(ps.snapshot_path, sw, sh, painter);
        },
        true);
  remember(ps, "snapshot");
  ImGui::SetNextItemWidth(0.3f * w);
  ImGui::InputInt("from", &ps.export_from, 0);
  ImGui::SameLine();
  ImGui::SetNextItemWidth(0.3f * w);
  ImGui::InputInt("to", &ps.export_to, 0);
  ImGui::SetNextItemWidth(-1);
  ImGui::InputText("##clip", ps.export_path, sizeof ps.export_path);
  const int clip_fps = std::max(1, static_cast<int>(std::lround(1.0 / insp.trajectory().frame_interval())));
  if (ImGui::Button("export from..to"))
    act(
        insp, ps,
        [&] {
          insp.export_frames(ps.export_path, ps.export_from, ps.export_to, 1280, 720, clip_fps, painter);
        },
        true);
  ImGui::SameLine();
  if (ImGui::Button("export this clog"))
    act(
        insp, ps, [&] { insp.export_clog(ps.export_path, 1280, 720, clip_fps, painter); }, true);
  remember(ps, "export clog");
  ImGui::Separator();
  ImGui::TextWrapped("%s", ps.message.c_str());
  ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(0.25f, 0.25f, 0.25f, 1.0f));
  ImGui::TextWrapped(
      "keys: left/right step, space play, n/p next/previous clog, Home/End, q close; "
      "wheel zooms, drag pans");
  ImGui::PopStyleColor();
  if (ps.last_redraw_ms > 0) ImGui::TextDisabled("last redraw %.1f ms", ps.last_redraw_ms);
  ImGui::End();
}

void draw_timeline(Inspector& insp, PanelState& ps, long n, float timeline_y, float timeline_w,
                   float timeline_h) {
  // Timeline: clogs in orange (red when the rule removed the arch), the current frame as a line; click to
  // seek.
  ImGui::SetNextWindowPos(ImVec2(0, timeline_y));
  ImGui::SetNextWindowSize(ImVec2(timeline_w, timeline_h));
  ImGui::Begin("timeline", nullptr, ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove);
  ImVec2 p0 = ImGui::GetCursorScreenPos();
  const float bw = ImGui::GetContentRegionAvail().x, bh = ImGui::GetContentRegionAvail().y;
  ImGui::InvisibleButton("##timeline", ImVec2(bw, std::max(4.0f, bh)));
  remember(ps, "timeline");
  if (ImGui::IsItemActive()) insp.set_frame(std::lround((ImGui::GetIO().MousePos.x - p0.x) / bw * (n - 1)));
  ImDrawList* dl = ImGui::GetWindowDrawList();
  // The bar over the top 55%, a time axis (seconds) under it.
  const float bar_h = std::max(4.0f, 0.55f * bh);
  dl->AddRectFilled(p0, ImVec2(p0.x + bw, p0.y + bar_h), IM_COL32(235, 235, 235, 255));
  auto xof = [&](long k) { return p0.x + bw * static_cast<float>(k) / std::max(1L, n - 1); };
  for (const auto& c : insp.clogs())
    dl->AddRectFilled(ImVec2(xof(c.first), p0.y + 0.25f * bar_h),
                      ImVec2(std::max(xof(c.last), xof(c.first) + 1), p0.y + bar_h),
                      c.removed ? IM_COL32(200, 40, 30, 255) : IM_COL32(240, 150, 30, 255));
  dl->AddLine(ImVec2(xof(insp.frame_index()), p0.y), ImVec2(xof(insp.frame_index()), p0.y + bar_h),
              IM_COL32(0, 0, 0, 255), 2);
  const double t0 = insp.trajectory().time(0), t1 = insp.trajectory().time(n - 1);
  if (t1 > t0 && bw > 0) {
    // A tick every 1, 2 or 5 x 10^k s, at least 70 px apart.
    const double min_step = (t1 - t0) * 70.0 / bw;
    double step = std::pow(10.0, std::floor(std::log10(min_step)));
    for (double m : {1.0, 2.0, 5.0, 10.0})
      if (m * step >= min_step) {
        step *= m;
        break;
      }
    const ImU32 ink = IM_COL32(60, 60, 60, 255);
    for (double t = std::ceil(t0 / step) * step; t <= t1 + 1e-9; t += step) {
      const float x = p0.x + bw * static_cast<float>((t - t0) / (t1 - t0));
      dl->AddLine(ImVec2(x, p0.y + bar_h), ImVec2(x, p0.y + bar_h + 4), ink);
      char label[32];
      std::snprintf(label, sizeof label, step < 1 ? "%.1f s" : "%.0f s", t);
      const ImVec2 size = ImGui::CalcTextSize(label);
      const float lx = std::clamp(x - 0.5f * size.x, p0.x, p0.x + bw - size.x);
      dl->AddText(ImVec2(lx, p0.y + bar_h + 4), ink, label);
    }
  }
  ImGui::End();
}
}  // namespace

void draw_panels(Inspector& insp, PanelState& ps, Painter* painter, float x, float w, float h,
                 float timeline_y, float timeline_w, float timeline_h) {
  const long n = insp.trajectory().size();
  ImGui::SetNextWindowPos(ImVec2(x, 0));
  ImGui::SetNextWindowSize(ImVec2(w, h));
  ImGui::Begin("siloscope inspect", nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse);
  const core::Frame f = insp.current();

  draw_transport(insp, ps, n, f);
  draw_view(insp, ps);
  draw_arch(insp, painter, f);
  draw_outputs(insp, ps, painter, w);
  draw_timeline(insp, ps, n, timeline_y, timeline_w, timeline_h);
}

}  // namespace ui
