// The inspector window's ImGui panels (ui/panels.h): the frame controls, the timeline with the clog bars, the
// camera, the look, the arch table, the grain details and the exports. Over 400 lines because they are one
// side panel, drawn top to bottom in one pass over one PanelState; each section is a function of its own.
#include "ui/panels.h"

#include <cmath>
#include <functional>

#include <imgui.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <utility>

#include "core/arch.h"
#include "core/error.h"
#include "ui/live_panel.h"

namespace ui {

void remember(PanelState& ps, const char* name) {
  ImVec2 a = ImGui::GetItemRectMin(), b = ImGui::GetItemRectMax();
  ps.rects[name] = {a.x, a.y, b.x, b.y};
}

namespace {
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

void snapshot_from_panel(Inspector& insp, PanelState& ps, Painter* painter) {
  int sw = 0, sh = 0;
  render::parse_size(kSizes[ps.snapshot_size], "snapshot size", sw, sh);
  insp.snapshot(ps.snapshot_path, sw, sh, painter);
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
  if (insp.branch() && !insp.branch()->saved() && frames > 0) {
    // "What if" plays on one clock: the branch is simulated on as far, and the recording follows it.
    bool went_on = false;
    act(insp, ps, [&] {
      insp.branch_continue(static_cast<double>(frames) * insp.trajectory().frame_interval());
      went_on = true;
    });
    if (!went_on) ps.playing = false;  // refused (the message says why): playback stops
    return;
  }
  insp.set_frame(target);
  if (insp.frame_index() == insp.trajectory().size() - 1) ps.playing = false;
}

const std::vector<std::pair<const char*, const char*>>& inspector_keys() {
  static const std::vector<std::pair<const char*, const char*>> keys = {
      {"right / left", "one frame forward / back (held: repeats)"},
      {"space", "play / pause"},
      {"n / p", "the start of the next / previous clog (playback stops)"},
      {"a", "the frame where this clog's final arch first stands (or the next clog's)"},
      {". / ,", "the next / previous change of arch"},
      {"c", "play until the next clog starts"},
      {"s", "snapshot this frame (the outputs tab's name and size)"},
      {"w", "save the session as a script (the outputs tab's name)"},
      {"Home / End", "the first / last frame"},
      {"?", "this list (again, Escape or a click closes it)"},
      {"q / Escape", "close the window"},
      {"wheel", "zoom the main view"},
      {"drag", "pan the main view"},
      {"click a grain", "its details in the panel, ringed in the picture (empty space: none)"},
      {"ctrl + click a field", "type a value"},
  };
  return keys;
}

void draw_keys_overlay(PanelState& ps, float w, float h) {
  ImGui::SetNextWindowPos(ImVec2(0.5f * w, 0.5f * h), ImGuiCond_Always, ImVec2(0.5f, 0.5f));
  ImGui::SetNextWindowBgAlpha(0.95f);
  ImGui::Begin("keys", nullptr,
               ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoCollapse |
                   ImGuiWindowFlags_NoSavedSettings);
  if (ImGui::BeginTable("keys", 2, ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingFixedFit)) {
    for (const auto& [key, what] : inspector_keys()) {
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(key);
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(what);
    }
    ImGui::EndTable();
  }
  if (ImGui::Button("close")) ps.show_keys = false;
  remember(ps, "close keys");
  if (ImGui::IsMouseClicked(ImGuiMouseButton_Left) && !ImGui::IsWindowHovered())
    ps.show_keys = false, ps.swallow_release = true;
  ImGui::End();
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
  // Two lines kept for the clog's caption whatever the frame, so the panel below does not jump by a line
  // between flowing and clogged frames.
  const float caption_y = ImGui::GetCursorPosY();
  if (here >= 0)
    ImGui::TextWrapped("%s", insp.clog_caption(static_cast<size_t>(here)).c_str());
  else
    ImGui::TextUnformatted("flowing (no clog at this frame)");
  const float spacing = ImGui::GetStyle().ItemSpacing.y;
  const float short_by = 2 * ImGui::GetTextLineHeight() + spacing - (ImGui::GetCursorPosY() - caption_y);
  if (short_by > spacing) ImGui::Dummy(ImVec2(0, short_by - spacing));
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
      {"stress", render::ColorMode::Stress},
      {"id", render::ColorMode::Id}};
  for (size_t k = 0; k < std::size(colors); ++k) {
    if (k > 0 && k != 3 && k != 5) ImGui::SameLine();
    if (ImGui::RadioButton(colors[k].first, insp.style.color == colors[k].second))
      act(insp, ps, [&] { insp.set_color(colors[k].second, colors[k].first); });
  }
  // The colour map and range of the scale (the script lines `colormap NAME`, `color MODE MIN:MAX`), shown for
  // every colouring so the panel does not jump; disabled where there is no scale.
  const bool scaled =
      insp.style.color != render::ColorMode::Species && insp.style.color != render::ColorMode::Id;
  ImGui::BeginDisabled(!scaled);
  ImGui::PushID("colormap");
  for (auto m : {render::Colormap::Viridis, render::Colormap::Magma, render::Colormap::Inferno,
                 render::Colormap::Cividis}) {
    if (m != render::Colormap::Viridis) ImGui::SameLine();
    if (ImGui::RadioButton(render::colormap_name(m), insp.style.colormap == m))
      act(insp, ps, [&] { insp.execute(std::string("colormap ") + render::colormap_name(m)); });
  }
  ImGui::PopID();
  double* top = render::color_scale_top(insp.style);
  double none = 0, lo_min = 0, hi_max = 1e6;
  ImGui::SetNextItemWidth(0.6f * ImGui::GetContentRegionAvail().x);
  // Drag in steps of 0.5% of the top; the top stays above the bottom (displacement: 0 is each frame's own).
  const float step = static_cast<float>(std::max(1e-4, 0.005 * (top ? *top : 1.0)));
  ImGui::DragScalar("##colour_min", ImGuiDataType_Double, &insp.style.color_min, step, &lo_min,
                    top ? top : &none, "from %.3g", ImGuiSliderFlags_AlwaysClamp);
  remember(ps, "colour min");
  ImGui::SameLine();
  ImGui::SetNextItemWidth(-1);
  ImGui::DragScalar("##colour_max", ImGuiDataType_Double, top ? top : &none, step, &insp.style.color_min,
                    &hi_max, "to %.3g", ImGuiSliderFlags_AlwaysClamp);
  remember(ps, "colour max");
  ImGui::EndDisabled();
  bool cb = insp.style.palette == render::Palette::ColorBlind;
  if (ImGui::Checkbox("colour-blind palette", &cb))
    insp.style.palette = cb ? render::Palette::ColorBlind : render::Palette::Paper;
  ImGui::SameLine();
  ImGui::Checkbox("arch", &insp.style.show_arch);
  ImGui::SameLine();
  ImGui::Checkbox("member ids", &insp.overlay.ids);
  if (insp.has_contact_forces()) {  // the forces on the arch from outside it, as arrows
    ImGui::SameLine();
    bool arrows = insp.style.arch_forces;
    if (ImGui::Checkbox("forces", &arrows))
      act(insp, ps, [&] { insp.execute(arrows ? "arch forces on" : "arch forces off"); });
  }
  if (insp.has_contacts()) {  // the run kept its contacts: force chains as record draws them
    ImGui::Checkbox("force chains", &insp.style.chains);
    ImGui::SameLine();
    ImGui::BeginDisabled(!insp.style.chains);
    double chain_lo = 0, chain_hi = 1e6;
    ImGui::SetNextItemWidth(-1);
    double range[2] = {insp.style.chain_min, insp.style.chain_max};
    if (ImGui::DragScalarN("##chains", ImGuiDataType_Double, range, 2,
                           static_cast<float>(std::max(0.01, 0.005 * range[1])), &chain_lo, &chain_hi,
                           "%.3g N", ImGuiSliderFlags_AlwaysClamp)) {
      insp.style.chain_min = range[0];
      insp.style.chain_max = std::max(range[1], range[0] + 1e-3);
    }
    ImGui::EndDisabled();
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

void draw_grain(Inspector& insp, PanelState& ps) {
  // The grain asked about: a click on it, its id typed (the script line `select ID`), or `select ID`.
  ImGui::SetNextItemWidth(8 * ImGui::GetFontSize());
  if (ImGui::InputTextWithHint("##grain_id", "grain id", ps.grain_id, sizeof ps.grain_id,
                               ImGuiInputTextFlags_EnterReturnsTrue | ImGuiInputTextFlags_CharsDecimal))
    act(insp, ps, [&] { insp.execute(std::string("select ") + ps.grain_id); });
  remember(ps, "grain id");
  if (!insp.style.tracked.empty()) {
    ImGui::SameLine();
    if (ImGui::Button("track off")) act(insp, ps, [&] { insp.execute("track off"); });
    remember(ps, "track off");
  }
  if (insp.selected < 0) {
    ImGui::TextDisabled("click a grain, or type its id, for its details");
    return;
  }
  for (const auto& line : insp.grain_details()) ImGui::TextWrapped("%s", line.c_str());
  if (ImGui::Button("track this grain"))
    act(insp, ps, [&] { insp.execute("track " + std::to_string(insp.selected)); });
  remember(ps, "track grain");
  ImGui::SameLine();
  if (ImGui::Button("clear selection")) act(insp, ps, [&] { insp.select_grain(-1); });
  remember(ps, "clear selection");
}

void draw_arch(Inspector& insp, PanelState& ps, const core::Frame& f) {
  // The arch of this frame: its summary, then member by member (left to right).
  draw_arch_summary(f, insp.overlay_data);
  const std::vector<ArchMember> rows = insp.arch_table();
  if (!rows.empty()) {
    const bool forces = !f.contacts.empty();
    const std::optional<ArchLoads> loads = insp.arch_loads();  // with the contacts' geometry (version 2)
    const int cols = loads ? 9 : forces ? 7 : 5;
    if (ImGui::BeginTable("arch members", cols,
                          ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingFixedFit)) {
      const char* heads[] = {"id",         "species",     "x [m]",    "y [m]",    "bead",
                             "F left [N]", "F right [N]", "load [N]", "walls [N]"};
      for (int c = 0; c < cols; ++c) ImGui::TableSetupColumn(heads[c]);
      ImGui::TableHeadersRow();
      for (const auto& m : rows) {
        ImGui::TableNextRow();
        ImGui::TableNextColumn();
        ImGui::PushID(m.id);
        if (ImGui::Selectable(std::to_string(m.id).c_str(), insp.selected == m.id,
                              ImGuiSelectableFlags_SpanAllColumns))
          act(insp, ps, [&] { insp.select_grain(m.id); });
        ImGui::PopID();
        if (!m.walls.empty() && ImGui::IsItemHovered()) ImGui::SetTooltip("touches %s", m.walls.c_str());
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(m.species.c_str());
        ImGui::TableNextColumn();
        ImGui::Text("%.3f", m.x);
        ImGui::TableNextColumn();
        ImGui::Text("%.3f", m.y);
        ImGui::TableNextColumn();
        if (std::isnan(m.bead_deg))
          ImGui::TextDisabled("%s", m.walls.empty() ? "end" : "wall");
        else
          ImGui::Text("%.0f", m.bead_deg);
        if (forces) {
          const double values[] = {m.force_left, m.force_right, m.load, m.wall_force};
          for (int c = 0; c < cols - 5; ++c) {
            const double F = values[c];
            ImGui::TableNextColumn();
            if (std::isnan(F))
              ImGui::TextDisabled("-");
            else
              ImGui::Text("%.2f", F);
          }
        }
      }
      ImGui::EndTable();
    }
    if (ImGui::Button("track the arch's members")) {
      std::string ids;
      for (const auto& m : rows) ids += (ids.empty() ? "" : ",") + std::to_string(m.id);
      act(insp, ps, [&] { insp.execute("track " + ids); });
    }
    remember(ps, "track arch");
    if (loads)
      ImGui::TextWrapped(
          "as a body: load from above %.2f N, walls hold %.2f N, its weight %.2f N (left over: %.2f N)",
          loads->load, loads->held, loads->weight, loads->residual);
    else if (forces)
      ImGui::TextDisabled("loads: the run's contacts hold normal forces only (recorded before version 2)");
    if (!forces) ImGui::TextDisabled("forces: the run kept no contacts (record keeps them)");
  }
}

void draw_outputs(Inspector& insp, PanelState& ps, Painter* painter, float w) {
  // Outputs.
  ImGui::SetNextItemWidth(0.55f * w);
  ImGui::Combo("size", &ps.snapshot_size, kSizes, IM_ARRAYSIZE(kSizes));  // of snapshots and clips
  ImGui::SetNextItemWidth(-1);
  ImGui::InputText("##snap", ps.snapshot_path, sizeof ps.snapshot_path);
  if (ImGui::Button("snapshot this frame (s)"))
    act(
        insp, ps, [&] { snapshot_from_panel(insp, ps, painter); }, true);
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
          int cw = 0, ch = 0;
          render::parse_size(kSizes[ps.snapshot_size], "export size", cw, ch);
          insp.export_frames(ps.export_path, ps.export_from, ps.export_to, cw, ch, clip_fps, painter);
        },
        true);
  ImGui::SameLine();
  if (ImGui::Button("export this clog"))
    act(
        insp, ps,
        [&] {
          int cw = 0, ch = 0;
          render::parse_size(kSizes[ps.snapshot_size], "export size", cw, ch);
          insp.export_clog(ps.export_path, cw, ch, clip_fps, painter);
        },
        true);
  remember(ps, "export clog");
  // The session so far as a script: replayed with --script it makes the same pictures.
  ImGui::SetNextItemWidth(0.55f * w);
  ImGui::InputText("##session", ps.session_path, sizeof ps.session_path);
  ImGui::SameLine();
  if (ImGui::Button("save session (w)"))
    act(
        insp, ps, [&] { insp.save_session(ps.session_path, ps.trajectory_name); }, true);
  remember(ps, "save session");
  ImGui::SetNextItemWidth(0.55f * w);
  ImGui::SliderFloat("text size", &ps.font_scale, 0.8f, 2.0f, "%.2fx");
  remember(ps, "text size");
  if (ps.last_redraw_ms > 0) ImGui::TextDisabled("last redraw %.1f ms", ps.last_redraw_ms);
}

void draw_timeline(Inspector& insp, PanelState& ps, long n, float timeline_y, float timeline_w,
                   float timeline_h) {
  // Timeline: clogs in orange (red when the rule removed the arch), the current frame as a line; click to
  // seek.
  ImGui::SetNextWindowPos(ImVec2(0, timeline_y));
  ImGui::SetNextWindowSize(ImVec2(timeline_w, timeline_h));
  ImGui::Begin("timeline", nullptr, ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove);
  ImVec2 p0 = ImGui::GetCursorScreenPos();
  const float x_seek = p0.x;
  const float bw = ImGui::GetContentRegionAvail().x, bh = ImGui::GetContentRegionAvail().y;
  ImGui::InvisibleButton("##timeline", ImVec2(bw, std::max(4.0f, bh)));
  remember(ps, "timeline");
  if (ImGui::IsItemActive()) insp.set_frame(std::lround((ImGui::GetIO().MousePos.x - x_seek) / bw * (n - 1)));
  ImDrawList* dl = ImGui::GetWindowDrawList();
  // A legend row, the bar, a time axis (seconds) under it.
  const float line = ImGui::GetTextLineHeight();
  const ImU32 clog_ink = IM_COL32(240, 150, 30, 255), rule_ink = IM_COL32(200, 40, 30, 255);
  const ImU32 text_ink = IM_COL32(60, 60, 60, 255);
  {
    float lx = p0.x;
    auto key = [&](ImU32 colour, const char* label) {
      dl->AddRectFilled(ImVec2(lx, p0.y + 0.2f * line), ImVec2(lx + 0.8f * line, p0.y + 0.9f * line), colour);
      dl->AddText(ImVec2(lx + 1.1f * line, p0.y), text_ink, label);
      lx += 1.1f * line + ImGui::CalcTextSize(label).x + 1.2f * line;
    };
    key(clog_ink, "clog");
    key(rule_ink, "clog ended by the rule (long-lasting arch)");
    key(IM_COL32(0, 0, 0, 255), "this frame; click or drag to seek");
  }
  const ImVec2 b0(p0.x, p0.y + line + 2);
  const float bar_h = std::max(4.0f, bh - 2 * line - 8);
  dl->AddRectFilled(b0, ImVec2(b0.x + bw, b0.y + bar_h), IM_COL32(235, 235, 235, 255));
  auto xof = [&](long k) { return p0.x + bw * static_cast<float>(k) / std::max(1L, n - 1); };
  // Each clog from its first frame to the frame after its last, one pixel short of the next clog when they
  // touch, so back-to-back clogs read as two bars.
  const auto& clogs = insp.clogs();
  for (size_t i = 0; i < clogs.size(); ++i) {
    const auto& c = clogs[i];
    float x1 = std::max(xof(c.last + 1), xof(c.first) + 2);
    if (i + 1 < clogs.size()) x1 = std::min(x1, xof(clogs[i + 1].first) - 1);
    dl->AddRectFilled(ImVec2(xof(c.first), b0.y), ImVec2(std::max(x1, xof(c.first) + 1), b0.y + bar_h),
                      c.removed ? rule_ink : clog_ink);
  }
  p0.y = b0.y;  // the frame line and the axis below measure from the bar
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
    const ImU32 ink = text_ink;
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
  // The arch and the grain, or the outputs, in a region of fixed height above the message: nothing jumps
  // while stepping (the region scrolls when a long arch and a grain's contacts need more).
  ImGui::Separator();
  const float bottom_h = 3.2f * ImGui::GetTextLineHeightWithSpacing();
  const float details_h =
      std::max(4 * ImGui::GetTextLineHeightWithSpacing(), ImGui::GetContentRegionAvail().y - bottom_h);
  ImGui::BeginChild("details", ImVec2(0, details_h));
  if (ImGui::BeginTabBar("tabs")) {
    const bool arch_tab = ImGui::BeginTabItem("arch and grain");
    remember(ps, "arch tab");  // the tab itself (its contents follow)
    if (arch_tab) {
      draw_arch(insp, ps, f);
      ImGui::Separator();
      draw_grain(insp, ps);
      // No corner of the picture is clear of the container (zoomed in): the information box is shown here.
      if (painter && painter->info_left()) {
        ImGui::Separator();
        render::info_contents(f, insp.overlay_data, insp.overlay, insp.style, ImGui::GetFontSize());
      }
      ImGui::EndTabItem();
    }
    const bool branch_tab = ImGui::BeginTabItem("what if");
    remember(ps, "what if tab");  // the tab itself (its contents follow)
    if (branch_tab) {
      draw_branch(insp, ps);
      ImGui::EndTabItem();
    }
    const bool outputs_tab = ImGui::BeginTabItem("outputs");
    remember(ps, "outputs tab");  // the tab itself (its contents follow)
    if (outputs_tab) {
      draw_outputs(insp, ps, painter, w);
      ImGui::EndTabItem();
    }
    ImGui::EndTabBar();
  }
  ImGui::EndChild();
  ImGui::Separator();
  ImGui::TextWrapped("%s", ps.message.c_str());
  ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(0.25f, 0.25f, 0.25f, 1.0f));
  ImGui::TextWrapped("? lists every key; wheel zooms, drag pans, click a grain");
  ImGui::PopStyleColor();
  ImGui::End();
  draw_timeline(insp, ps, n, timeline_y, timeline_w, timeline_h);
  if (ps.show_keys) draw_keys_overlay(ps, x + w, h);
}

}  // namespace ui
