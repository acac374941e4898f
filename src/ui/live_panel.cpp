#include "ui/live_panel.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "core/arch.h"
#include "core/format.h"
#include "core/physics.h"

namespace ui {

namespace {
void remember(LiveState& st, const char* name) {
  const ImVec2 a = ImGui::GetItemRectMin(), b = ImGui::GetItemRectMax();
  st.rects[name] = {a.x, a.y, b.x, b.y};
}
}  // namespace

std::vector<render::View> live_views(const LiveState& st, const core::Geometry& geo, int w, int h) {
  // As the inspector does: zoom and pan apply to the most magnified view (the outlet in split).
  auto views = render::layout_views(st.camera, geo, w, h);
  render::View* main = &views.front();
  for (auto& v : views)
    if (v.px_per_m() > main->px_per_m()) main = &v;
  main->cam.height /= st.zoom;
  main->cam.cx += st.pan.x;
  main->cam.cy += st.pan.y;
  return views;
}

double drag_step(const std::string& key, double value) {
  if (value != 0) return 0.005 * std::abs(value);
  // From 0: steps of 0.5% of the key's default (kick_impulse_max: 2.5e-7 N s a pixel, not 1 N s from its
  // range), else a millionth of a finite range, else 1e-3.
  static const auto defaults = core::scene_values(core::Scene{});
  const auto d = defaults.find(key);
  const double dv = d == defaults.end() ? 0 : std::strtod(d->second.c_str(), nullptr);
  if (std::isfinite(dv) && dv != 0) return 0.005 * std::abs(dv);
  if (const core::Field* f = core::find_field(key))
    if (std::isfinite(f->max - f->min) && f->max > f->min) return 1e-6 * (f->max - f->min);
  return 1e-3;
}

bool key_drag(core::Scene& s, const std::string& key) {
  double lo = 0, hi = 1;
  const char* unit = "";
  if (const core::Field* f = core::find_field(key)) {
    lo = f->min, hi = f->max, unit = f->unit;
  } else if (key.rfind("species.", 0) == 0) {
    if (const core::SpeciesField* sf = core::find_species_field(key.substr(key.rfind('.') + 1)))
      lo = sf->min, hi = sf->max, unit = sf->unit;
  }
  const auto values = core::scene_values(s);
  const auto it = values.find(key);
  if (it == values.end()) return false;
  double v = std::strtod(it->second.c_str(), nullptr);
  const float speed = static_cast<float>(drag_step(key, v));
  const std::string label =
      key + (unit && *unit && std::string(unit) != "1" ? " [" + std::string(unit) + "]" : "");
  ImGui::SetNextItemWidth(0.45f * ImGui::GetContentRegionAvail().x);
  double lo_c = std::isfinite(lo) ? lo : -1e300, hi_c = std::isfinite(hi) ? hi : 1e300;
  if (!ImGui::DragScalar(label.c_str(), ImGuiDataType_Double, &v, speed, &lo_c, &hi_c, "%.4g",
                         ImGuiSliderFlags_AlwaysClamp))
    return false;
  try {
    core::set_field(s, key, core::format_shortest(v), "the live panel");
  } catch (const std::exception&) {
    // a whole-number field: set_field keeps it whole on the next edit
  }
  return true;
}

std::string edits_between(const core::Scene& before, const core::Scene& after) {
  const auto a = core::scene_values(before), b = core::scene_values(after);
  std::string out;
  for (const auto& [key, value] : b) {
    const auto it = a.find(key);
    if (it != a.end() && it->second != value)
      out += (out.empty() ? "" : ", ") + key + " " + it->second + " -> " + value;
  }
  return out;
}

std::string blame_edits(const LiveState& st, const std::string& what) {
  if (st.restart_edits.empty()) return what;
  return "the restart with " + st.restart_edits + " failed: " + what +
         " (\"scene file\" returns to the file's values)";
}

void draw_arch_summary(const core::Frame& f, const render::OverlayData& od) {
  if (f.arch.empty()) {
    ImGui::TextUnformatted(f.clog_open ? "clogged, no arch found yet" : "flowing: no clog, no arch");
    return;
  }
  std::vector<core::Vec2> pos;
  std::vector<double> rad;
  for (const auto& p : f.particles) pos.push_back({p.x, p.y}), rad.push_back(p.radius);
  const auto d = core::arch_descriptors(f.arch, pos, rad);
  const auto& names = od.species_names;
  const bool shorthand = names.size() == 2 && names[0] == "original";
  int added = 0;
  for (int id : f.arch) added += f.particles[static_cast<size_t>(id)].species != core::Species::Original;
  // Forming: it stands, its clog not yet confirmed (no exit for clog_min_gap); then clogging, then arrested.
  const char* state = f.arch_forming
                          ? ", forming (the clog is confirmed once no grain has left for clog_min_gap)"
                      : f.clog_arrested ? ", arrested"
                                        : ", clogging";
  if (shorthand)
    ImGui::Text("arch of clog %d: %zu disks, %d added%s", f.clog_number, f.arch.size(), added, state);
  else
    ImGui::Text("arch of clog %d: %zu grains%s", f.clog_number, f.arch.size(), state);
  // The descriptors of arches.csv: span edge to edge; rise of the highest centre above the end members'
  // chord; the bead angles (180 deg: flat, above: a defect pointing at the outlet).
  ImGui::TextWrapped(
      "span %.3f m (edge to edge), rise %.3f m above the ends' chord, aspect rise/(span/2) %.2f; bead "
      "angles: "
      "largest %.0f deg, sd %.0f deg, %d defect%s (> 180 deg)",
      d.span, d.rise, d.aspect, d.theta_max_deg, d.angle_sd_deg, d.defects, d.defects == 1 ? "" : "s");
}

void draw_live_panel(LiveSource& source, LiveState& st, const core::Frame& f, const render::OverlayData& od,
                     const render::Painter* painter) {
  ImGui::Text("t = %.2f s, %lld exits", f.t, static_cast<long long>(f.exits_total()));
  if (ImGui::Button(st.paused ? "resume (space)" : "pause (space)")) st.paused = !st.paused;
  remember(st, "pause");
  ImGui::SameLine();
  ImGui::BeginDisabled(!st.paused);
  if (ImGui::Button("step 1/30 s (right)")) st.step_pending += kLiveStep;
  remember(st, "step");
  ImGui::EndDisabled();
  ImGui::SameLine();
  if (ImGui::Button("snapshot (s)")) st.snapshot = true;
  ImGui::PushID("run");
  // The speed asked for, and the speed the simulation keeps up with (the window's loop measures it).
  char speed_format[64] = "%.2fx real time";
  if (st.achieved > 0 && !st.paused)
    std::snprintf(speed_format, sizeof speed_format, "%%.2fx asked, %.2fx achieved", st.achieved);
  ImGui::SliderFloat("speed", &st.speed, 0.05f, 4.0f, speed_format, ImGuiSliderFlags_Logarithmic);
  remember(st, "speed");
  ImGui::PopID();
  ImGui::Separator();
  ImGui::TextUnformatted("scene (applies on restart; drag or ctrl+click to type)");
  for (const auto& key : source.live_keys()) key_drag(st.edit, key);
  if (st.edit.shorthand()) {
    const double weight = core::mass_of(st.edit.radius_added(), st.edit.density) * st.edit.gravity;
    ImGui::Text("dipole contact force / weight = %.3g",
                weight > 0 ? core::dipole_contact_force(st.edit) / weight : 0.0);
  }
  if (ImGui::Button("restart (settles first)")) {
    const std::string edits = edits_between(source.scene(), st.edit);
    try {
      st.restart_edits = edits;
      source.restart(st.edit);
      st.message = edits.empty() ? "restarted" : "restarted with " + edits;
    } catch (const std::exception& e) {
      st.message = blame_edits(st, e.what());
    }
  }
  ImGui::SameLine();
  if (!st.file_scene) st.file_scene = source.scene();  // as the window opened: the scene file's
  if (ImGui::Button("undo edits")) st.edit = source.scene();
  ImGui::SameLine();
  if (ImGui::Button("scene file")) st.edit = *st.file_scene;  // back from a restart that went wrong
  remember(st, "scene file");
  ImGui::Separator();
  ImGui::PushID("camera");
  for (const char* c : {"split", "outlet", "hopper"}) {
    if (ImGui::RadioButton(c, st.camera.text == c))
      st.camera = render::parse_camera(c), st.zoom = 1, st.pan = {0, 0};
    ImGui::SameLine();
  }
  ImGui::PopID();
  ImGui::NewLine();
  float zoom = static_cast<float>(st.zoom);
  ImGui::SetNextItemWidth(0.6f * ImGui::GetContentRegionAvail().x);
  if (ImGui::SliderFloat("zoom", &zoom, 0.5f, 10.0f, "%.2fx", ImGuiSliderFlags_Logarithmic)) st.zoom = zoom;
  ImGui::SameLine();
  if (ImGui::Button("reset view")) st.zoom = 1, st.pan = {0, 0};
  const std::pair<const char*, render::ColorMode> colors[] = {
      {"species", render::ColorMode::Species},
      {"speed", render::ColorMode::Speed},
      {"force", render::ColorMode::Force},
      {"displacement", render::ColorMode::Displacement},
      {"coordination", render::ColorMode::Coordination},
      {"stress", render::ColorMode::Stress},
      {"id", render::ColorMode::Id}};
  // The colourings in an ID scope of their own: "speed" is also the simulation speed's slider in this window
  // (one ImGui ID for both aborted the window on the first click).
  ImGui::PushID("color");
  for (const auto& [label, mode] : colors) {
    if (mode == render::ColorMode::Displacement || mode == render::ColorMode::Stress) ImGui::NewLine();
    if (ImGui::RadioButton(label, st.style.color == mode)) st.style.color = mode;
    ImGui::SameLine();
  }
  ImGui::PopID();
  ImGui::NewLine();
  const bool scaled = st.style.color != render::ColorMode::Species && st.style.color != render::ColorMode::Id;
  ImGui::BeginDisabled(!scaled);  // shown always: the panel does not jump when the colouring changes
  for (auto m : {render::Colormap::Viridis, render::Colormap::Magma, render::Colormap::Inferno,
                 render::Colormap::Cividis}) {
    if (ImGui::RadioButton(render::colormap_name(m), st.style.colormap == m)) st.style.colormap = m;
    ImGui::SameLine();
  }
  ImGui::EndDisabled();
  ImGui::NewLine();
  ImGui::Checkbox("arch", &st.style.show_arch);
  ImGui::SameLine();
  ImGui::Checkbox("force chains", &st.style.chains);
  ImGui::SameLine();
  ImGui::Checkbox("arch ids", &st.overlay.ids);
  ImGui::Separator();
  draw_arch_summary(f, od);
  if (painter && painter->info_left()) {  // no corner of the picture is clear of the container
    ImGui::Separator();
    render::info_contents(f, od, st.overlay, st.style, ImGui::GetFontSize());
  }
  ImGui::TextWrapped("%s", st.message.c_str());
  ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(0.25f, 0.25f, 0.25f, 1.0f));
  ImGui::TextWrapped("keys: space pause, right step (paused), s snapshot, q close; wheel zooms, drag pans");
  ImGui::PopStyleColor();
  // The panel's text size (it starts at the window's height over 720 pixels); the panel widens with it.
  ImGui::SetNextItemWidth(0.45f * ImGui::GetContentRegionAvail().x);
  ImGui::SliderFloat("text size", &st.font_scale, 0.8f, 2.0f, "%.2fx");
  remember(st, "text size");
}

void draw_live_window(LiveSource& source, LiveState& st, const core::Frame& f, const render::OverlayData& od,
                      const render::Painter* painter, float x, float w, float h) {
  ImGui::SetNextWindowPos(ImVec2(x, 0));
  ImGui::SetNextWindowSize(ImVec2(w, h));
  ImGui::Begin("siloscope live", nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse);
  draw_live_panel(source, st, f, od, painter);
  ImGui::End();
}

}  // namespace ui
