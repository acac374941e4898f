#include "render/overlay.h"

#include <imgui.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "core/error.h"
#include "core/format.h"
#include "core/setup.h"
#include "render/gl.h"
#include "siloscope_version.h"

// The OpenGL3 backend, compiled from Debian's shipped source with our loader (see CMakeLists.txt).
bool ImGui_ImplOpenGL3_Init(const char* glsl_version);
void ImGui_ImplOpenGL3_Shutdown();
void ImGui_ImplOpenGL3_NewFrame();
void ImGui_ImplOpenGL3_RenderDrawData(ImDrawData* draw_data);
bool ImGui_ImplOpenGL3_CreateFontsTexture();
void ImGui_ImplOpenGL3_DestroyFontsTexture();

namespace render {

namespace {
const char* kFont = SILOSCOPE_FONT;  // found at build time
ImU32 to_u32(Rgba c) {
  return ImGui::ColorConvertFloat4ToU32(ImVec4(c.r, c.g, c.b, c.a));
}
}  // namespace

OverlayOptions parse_overlay(const std::string& spec) {
  if (spec == "all") return {};
  OverlayOptions o = OverlayOptions::none();
  if (spec == "none") return o;
  std::stringstream ss(spec);
  for (std::string item; std::getline(ss, item, ',');) {
    if (item == "all")
      o = OverlayOptions{};
    else if (item == "all+plot")
      o = OverlayOptions{}, o.plot = true;
    else if (item == "events")
      o.events = true;
    else if (item == "zoombox")
      o.zoombox = true;
    else if (item == "plot")
      o.plot = true;
    else if (item == "colorbar")
      o.colorbar = true;
    else if (item == "time")
      o.time = true;
    else if (item == "counts")
      o.counts = true;
    else if (item == "rate")
      o.rate = true;
    else if (item == "timer")
      o.timer = true;
    else if (item == "arch")
      o.arch = true;
    else if (item == "legend")
      o.legend = true;
    else if (item == "scale")
      o.scale = true;
    else
      throw core::InputError(
          "--overlay " + spec + ": '" + item +
          "' is not one of all, all+plot, none, time, counts, rate, timer, arch, legend, scale, "
          "events, zoombox, plot, colorbar");
  }
  return o;
}

OverlayData overlay_data_for(const core::Scene& scene) {
  OverlayData d;
  const core::Setup st = core::resolve(scene);
  d.clog_timeout = scene.clog_timeout;
  d.clog_min_gap = scene.clog_min_gap;
  d.clog_rule = st.clog_rule;
  d.diameter = 2 * st.reference_radius;
  d.species_names = st.species_names();
  for (const auto& sp : st.species)
    d.species_colors.push_back(sp.has_color ? Rgba{sp.color[0], sp.color[1], sp.color[2], 1}
                                            : Rgba{0, 0, 0, 0});
  char title[200];
  if (st.shorthand) {
    std::snprintf(title, sizeof title, "r = %g, chi = %g, mu = %g A m^2, seed %llu", scene.size_ratio,
                  scene.chi, scene.mu, static_cast<unsigned long long>(scene.seed));
  } else {
    std::string what = scene.container == "flat" ? "flat silo" : "hopper";
    if (st.geo.obstacle.present()) what += " + obstacle";
    if (st.drive.vibrating())
      what += ", Gamma " +
              core::format_g(st.drive.amplitude * st.drive.omega * st.drive.omega / scene.gravity, 3);
    if (scene.tilt != 0) what += ", tilt " + core::format_g(scene.tilt, 3) + " deg";
    std::snprintf(title, sizeof title, "%s, D = %g m, %d grains, seed %llu", what.c_str(), scene.aperture,
                  st.n_total, static_cast<unsigned long long>(scene.seed));
  }
  d.title = title;
  return d;
}

Overlay::Overlay() {
  IMGUI_CHECKVERSION();
  ImGuiContext* previous = ImGui::GetCurrentContext();
  ctx_ = ImGui::CreateContext();
  ImGui::SetCurrentContext(static_cast<ImGuiContext*>(ctx_));
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini next to the user's files
  ImGui::StyleColorsLight();
  if (!ImGui_ImplOpenGL3_Init("#version 330 core"))
    throw core::RuntimeFault("ImGui: the OpenGL3 backend failed");
  ImGui::SetCurrentContext(previous ? previous : static_cast<ImGuiContext*>(ctx_));
}

Overlay::~Overlay() {
  ImGui::SetCurrentContext(static_cast<ImGuiContext*>(ctx_));
  ImGui_ImplOpenGL3_Shutdown();
  ImGui::DestroyContext(static_cast<ImGuiContext*>(ctx_));
}

void Overlay::ensure_font(int h) {
  const int px = std::max(13, h / 42);
  if (px == font_px_) return;
  ImGuiIO& io = ImGui::GetIO();
  io.Fonts->Clear();
  if (kFont[0] != '\0' && std::filesystem::exists(kFont)) {
    io.Fonts->AddFontFromFileTTF(kFont, static_cast<float>(px));
  } else {
    ImFontConfig cfg;
    cfg.SizePixels = static_cast<float>(px);
    io.Fonts->AddFontDefault(&cfg);
  }
  ImGui_ImplOpenGL3_DestroyFontsTexture();
  if (!ImGui_ImplOpenGL3_CreateFontsTexture())
    throw core::RuntimeFault("ImGui: cannot create the font texture");
  font_px_ = px;
  laid_out_ = false;  // the panel's size changes with the font
}

void Overlay::draw(const core::Frame& f, const OverlayData& d, const OverlayOptions& o,
                   const std::vector<View>& views, const Style& style, int w, int h,
                   const core::Geometry* geo, const Annotations* notes) {
  static const Annotations none;
  const Annotations& marks = notes ? *notes : none;
  if (!o.any()) return;
  ImGuiContext* previous = ImGui::GetCurrentContext();
  ImGui::SetCurrentContext(static_cast<ImGuiContext*>(ctx_));
  ensure_font(h);
  ImGuiIO& io = ImGui::GetIO();
  io.DisplaySize = ImVec2(static_cast<float>(w), static_cast<float>(h));
  io.DeltaTime = 1.0f / 30.0f;
  ImGui_ImplOpenGL3_NewFrame();
  // Auto-sized windows learn their size in their first frame: lay the first one out once without drawing it.
  if (!laid_out_) {
    ImGui::NewFrame();
    build(f, d, o, views, style, w, h, geo, marks);
    ImGui::EndFrame();
    laid_out_ = true;
  }
  ImGui::NewFrame();
  build(f, d, o, views, style, w, h, geo, marks);
  ImGui::Render();
  glViewport(0, 0, w, h);
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
  check_gl("Overlay::draw");
  ImGui::SetCurrentContext(previous ? previous : static_cast<ImGuiContext*>(ctx_));
}

namespace {
// The colour scale of speed or force colouring, inside the current ImGui window.
void colour_bar(const Style& style, float em) {
  const bool speed = style.color == ColorMode::Speed;
  ImGui::Text("%s 0", speed ? "speed [m/s]" : "contact force [N]");
  ImGui::SameLine();
  ImVec2 p = ImGui::GetCursorScreenPos();
  const int steps = 32;
  const float bw = 8 * em, bh = ImGui::GetTextLineHeight();
  for (int k = 0; k < steps; ++k)
    ImGui::GetWindowDrawList()->AddRectFilled(ImVec2(p.x + bw * k / steps, p.y),
                                              ImVec2(p.x + bw * (k + 1) / steps, p.y + bh),
                                              to_u32(colormap((k + 0.5) / steps)));
  ImGui::Dummy(ImVec2(bw, bh));
  ImGui::SameLine();
  ImGui::Text("%g", speed ? style.speed_max : style.force_max);
}

// The view with the most pixels per metre (the outlet panel of a split camera).
const View& most_zoomed(const std::vector<View>& views) {
  const View* v = &views.front();
  for (const auto& c : views)
    if (c.px_per_m() > v->px_per_m()) v = &c;
  return *v;
}

// A text in a light box, centred at (cx, y) on the draw list.
void boxed_text(ImDrawList* dl, float cx, float y, const char* text, ImU32 ink, ImU32 box, float em) {
  const ImVec2 size = ImGui::CalcTextSize(text);
  const ImVec2 a(cx - 0.5f * size.x - 0.4f * em, y),
      b(cx + 0.5f * size.x + 0.4f * em, y + size.y + 0.3f * em);
  dl->AddRectFilled(a, b, box, 0.3f * em);
  dl->AddText(ImVec2(a.x + 0.4f * em, a.y + 0.15f * em), ink, text);
}
}  // namespace

void Overlay::plot(const core::Frame& f, const OverlayData& d, const std::vector<View>& views,
                   const Style& style) {
  // The discharge staircase: cumulative exits of each species against time, clogs shaded. Bottom-right of the
  // most zoomed view, below the outlet where there are no disks.
  if (!history_.empty() && f.t < history_.back().t) history_.clear();  // a new run or a jump back (inspector)
  history_.push_back({f.t, static_cast<long>(f.exits_original), static_cast<long>(f.exits_added),
                      f.since_last_exit >= d.clog_min_gap});
  const float em = static_cast<float>(font_px_);
  const View& v = most_zoomed(views);
  const float pw = 0.42f * v.rect.w, ph = 0.2f * v.rect.h;
  const float x1 = v.rect.x + v.rect.w - 0.8f * em, y1 = v.rect.y + v.rect.h - 1.6f * em;
  const float x0 = x1 - pw, y0 = y1 - ph;
  ImDrawList* dl = ImGui::GetForegroundDrawList();
  dl->AddRectFilled(ImVec2(x0 - 2.6f * em, y0 - 1.5f * em), ImVec2(x1 + 0.4f * em, y1 + 1.4f * em),
                    IM_COL32(255, 255, 255, 215), 0.3f * em);
  const double tmax = std::max(1.0, history_.back().t);
  long nmax = 1;
  for (const auto& s : history_) nmax = std::max(nmax, std::max(s.original, s.added));
  auto X = [&](double t) { return x0 + static_cast<float>(t / tmax) * pw; };
  auto Y = [&](double n) { return y1 - static_cast<float>(n / static_cast<double>(nmax)) * ph; };
  // Clogs: spans where the clog timer ran past clog_min_gap.
  for (size_t k = 1; k < history_.size(); ++k)
    if (history_[k].clogged)
      dl->AddRectFilled(ImVec2(X(history_[k - 1].t), y0), ImVec2(X(history_[k].t) + 0.5f, y1),
                        IM_COL32(200, 200, 200, 255));
  for (int sp = 0; sp < 2; ++sp) {
    const ImU32 ink =
        to_u32(sp == 0 ? species_color(style, core::Species::Original)
                       : (d.species_names.size() == 2 ? species_color(style, core::Species::Added)
                                                      : Rgba{0.35f, 0.35f, 0.35f, 1}));
    for (size_t k = 1; k < history_.size(); ++k) {
      const long a = sp == 0 ? history_[k - 1].original : history_[k - 1].added;
      const long b = sp == 0 ? history_[k].original : history_[k].added;
      dl->AddLine(ImVec2(X(history_[k - 1].t), Y(static_cast<double>(a))),
                  ImVec2(X(history_[k].t), Y(static_cast<double>(a))), ink, 2.0f);
      if (b != a)
        dl->AddLine(ImVec2(X(history_[k].t), Y(static_cast<double>(a))),
                    ImVec2(X(history_[k].t), Y(static_cast<double>(b))), ink, 2.0f);
    }
  }
  const ImU32 axis = IM_COL32(40, 40, 40, 255);
  dl->AddLine(ImVec2(x0, y1), ImVec2(x1, y1), axis);
  dl->AddLine(ImVec2(x0, y0), ImVec2(x0, y1), axis);
  char text[64];
  std::snprintf(text, sizeof text, "%ld", nmax);
  dl->AddText(ImVec2(x0 - 2.3f * em, y0 - 0.5f * em), axis, text);
  std::snprintf(text, sizeof text, "exits vs t (0-%.0f s), clogs grey", tmax);
  dl->AddText(ImVec2(x0, y1 + 0.1f * em), axis, text);
}

namespace {
// A world point on the container as the information box must not cover it: inside the walls (and a tenth of
// a diameter beyond, for the walls' lines) or in the column below the aperture that exiting disks fall
// through (four diameters deep).
bool in_container(const core::Geometry& g, core::Vec2 p) {
  const double m = 0.1 * g.grain_diameter;
  if (p.y < 0) return p.y > -4 * g.grain_diameter && std::abs(p.x) < g.half_aperture + m;
  if (p.y > g.total_height + m) return false;
  return p.x > g.left_at(p.y) - m && p.x < g.right_at(p.y) + m;
}
}  // namespace

// The information box's lines, into the current ImGui window.
void info_contents(const core::Frame& f, const OverlayData& d, const OverlayOptions& o, const Style& given,
                   float em) {
  Style style = given;  // the scene's own species colours, wherever the box is drawn (a window's side panel)
  if (!d.species_colors.empty()) style.species_colors = d.species_colors;
  if (!d.title.empty()) ImGui::TextUnformatted(d.title.c_str());
  if (o.time) ImGui::Text("t = %.2f s", f.t);
  const bool shorthand = d.species_names.size() == 2 && d.species_names[0] == "original";
  auto colored = [&](core::Species sp, const std::string& text) {
    const Rgba c = species_color(style, sp);
    ImGui::TextColored(ImVec4(c.r, c.g, c.b, 1), "%s", text.c_str());
  };
  if (o.counts) {
    if (shorthand) {
      colored(core::Species::Original, std::to_string(f.exits_original) + " original");
      ImGui::SameLine();
      colored(core::Species::Added, std::to_string(f.exits_added) + " added");
      ImGui::SameLine();
      ImGui::TextUnformatted("exits");
    } else {
      ImGui::Text("%lld exits", static_cast<long long>(f.exits_original + f.exits_added));
      if (d.species_names.size() > 1) {
        ImGui::SameLine();
        colored(core::Species::Original,
                "(" + std::to_string(f.exits_original) + " " + d.species_names.front() + ")");
      }
    }
  }
  if (o.rate)
    ImGui::Text("%s = %.2f /s (%s, so far)", shorthand || d.species_names.size() > 1 ? "Q~" : "Q",
                f.t > 0 ? f.exits_original / f.t : 0.0,
                shorthand ? "originals" : d.species_names.front().c_str());
  if (o.timer) {
    const bool clogged = f.since_last_exit >= d.clog_min_gap;
    const double frac = d.clog_rule ? std::min(1.0, f.since_last_exit / d.clog_timeout) : clogged ? 1.0 : 0.0;
    ImGui::PushStyleColor(ImGuiCol_PlotHistogram,
                          clogged ? ImVec4(0.85f, 0.25f, 0.15f, 1) : ImVec4(0.3f, 0.6f, 0.3f, 1));
    char label[64];
    if (!clogged)
      std::snprintf(label, sizeof label, "flowing");
    else if (d.clog_rule)
      std::snprintf(label, sizeof label, "clogged %.1f s / %.0f s", f.since_last_exit, d.clog_timeout);
    else
      std::snprintf(label, sizeof label, "clogged %.1f s (no rule)", f.since_last_exit);
    ImGui::ProgressBar(static_cast<float>(frac), ImVec2(14 * em, 0), label);
    ImGui::PopStyleColor();
  }
  if (o.arch && !f.arch.empty()) {
    int added = 0;
    for (int id : f.arch) added += f.particles[id].species != core::Species::Original;
    if (shorthand)
      ImGui::Text("arch: %zu disks (%d added)", f.arch.size(), added);
    else
      ImGui::Text("arch: %zu grains", f.arch.size());
  }
  if (o.legend) {
    ImGui::Separator();
    const float r = 0.4f * em;
    auto swatch = [&](Rgba fill, Rgba ring, const char* text) {
      ImVec2 p = ImGui::GetCursorScreenPos();
      ImVec2 c(p.x + r + 2, p.y + 0.5f * ImGui::GetTextLineHeight());
      if (ring.a > 0) ImGui::GetWindowDrawList()->AddCircle(c, r + 0.15f * em, to_u32(ring), 0, 0.25f * em);
      ImGui::GetWindowDrawList()->AddCircleFilled(c, r, to_u32(fill));
      ImGui::Dummy(ImVec2(2 * r + 0.5f * em, ImGui::GetTextLineHeight()));
      ImGui::SameLine();
      ImGui::TextUnformatted(text);
    };
    if (style.color == ColorMode::Species) {
      for (size_t k = 0; k < d.species_names.size(); ++k) {
        swatch(species_color(style, static_cast<core::Species>(k)), {0, 0, 0, 0}, d.species_names[k].c_str());
        ImGui::SameLine();
      }
    } else {
      colour_bar(style, em);
    }
    swatch({0.85f, 0.85f, 0.85f, 1}, arch_color(style.palette), "arch");
  }
}

void Overlay::draw_zoombox(const std::vector<View>& views, int h) {
  ImDrawList* dl = ImGui::GetForegroundDrawList();
  {
    // The outlet panel's world window, outlined on the whole-hopper panel.
    const View& zoom = most_zoomed(views);
    for (const auto& v : views) {
      if (&v == &zoom) continue;
      const double half_w = 0.5 * zoom.rect.w / zoom.px_per_m(), half_h = 0.5 * zoom.cam.height;
      const core::Vec2 a = v.world_to_pixel({zoom.cam.cx - half_w, zoom.cam.cy + half_h});
      const core::Vec2 b = v.world_to_pixel({zoom.cam.cx + half_w, zoom.cam.cy - half_h});
      dl->PushClipRect(
          ImVec2(static_cast<float>(v.rect.x), static_cast<float>(v.rect.y)),
          ImVec2(static_cast<float>(v.rect.x + v.rect.w), static_cast<float>(v.rect.y + v.rect.h)));
      dl->AddRect(ImVec2(static_cast<float>(a.x), static_cast<float>(a.y)),
                  ImVec2(static_cast<float>(b.x), static_cast<float>(b.y)), IM_COL32(30, 30, 30, 230), 0, 0,
                  std::max(1.5f, h / 500.0f));
      dl->PopClipRect();
    }
  }
}

void Overlay::draw_events(const Annotations& notes, const std::vector<View>& views, float em) {
  ImDrawList* dl = ImGui::GetForegroundDrawList();
  {
    // Disks the rule removed, ringed where they stood, in every view; the caption over the most zoomed view.
    const ImU32 ring = IM_COL32(200, 0, 160, 255);
    for (const auto& v : views) {
      dl->PushClipRect(
          ImVec2(static_cast<float>(v.rect.x), static_cast<float>(v.rect.y)),
          ImVec2(static_cast<float>(v.rect.x + v.rect.w), static_cast<float>(v.rect.y + v.rect.h)));
      for (const auto& g : notes.removed) {
        const core::Vec2 c = v.world_to_pixel({g.x, g.y});
        const float r = static_cast<float>(g.radius * v.px_per_m());
        dl->AddCircle(ImVec2(static_cast<float>(c.x), static_cast<float>(c.y)), r, ring, 0,
                      std::max(2.0f, 0.12f * r));
      }
      dl->PopClipRect();
    }
    const View& zoom = most_zoomed(views);
    if (!notes.caption.empty())
      boxed_text(dl, zoom.rect.x + 0.5f * zoom.rect.w, zoom.rect.y + 0.8f * em, notes.caption.c_str(),
                 IM_COL32(255, 255, 255, 255), IM_COL32(200, 0, 160, 235), em);
    if (notes.slowdown > 1.0 + 1e-9) {
      char badge[48];
      std::snprintf(badge, sizeof badge, "slow motion %.3gx", notes.slowdown);
      const ImVec2 size = ImGui::CalcTextSize(badge);
      const float x = zoom.rect.x + 0.8f * em, y = zoom.rect.y + 0.8f * em;
      dl->AddRectFilled(ImVec2(x, y), ImVec2(x + size.x + 0.8f * em, y + size.y + 0.3f * em),
                        IM_COL32(20, 20, 20, 220), 0.3f * em);
      dl->AddText(ImVec2(x + 0.4f * em, y + 0.15f * em), IM_COL32(255, 220, 0, 255), badge);
    }
  }
}

void Overlay::draw_colorbar(const OverlayOptions& o, const std::vector<View>& views, const Style& style,
                            float em) {
  if (o.colorbar && !o.legend && style.color != ColorMode::Species) {
    const View& zoom = most_zoomed(views);
    ImGui::SetNextWindowPos(ImVec2(zoom.rect.x + zoom.rect.w - 0.6f * em, zoom.rect.y + 0.6f * em), 0,
                            ImVec2(1.0f, 0.0f));
    ImGui::SetNextWindowBgAlpha(0.82f);
    ImGui::Begin("colorbar", nullptr,
                 ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize |
                     ImGuiWindowFlags_NoInputs | ImGuiWindowFlags_NoSavedSettings |
                     ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoNav);
    colour_bar(style, em);
    ImGui::End();
  }
}

void Overlay::draw_info(const core::Frame& f, const OverlayData& d, const OverlayOptions& o,
                        const std::vector<View>& views, const Style& style, int w, int h,
                        const core::Geometry* geo, float em) {
  // The information panel, top-left of the first view.
  const bool panel = o.time || o.counts || o.rate || o.timer || o.arch || o.legend;
  if (panel) {
    // Top-right corner: the outlet view leaves room there beside the hopper wall; the silo's top stays
    // visible.
    const float right = d.panel_w > 0 ? static_cast<float>(d.panel_x + d.panel_w) : static_cast<float>(w);
    const float left = static_cast<float>(d.panel_x), pad = 0.6f * em;
    // Corner k: its anchor and pivot. In a window, move to the corner covering the fewest disk centres
    // (within a radius); stay where the box is unless another corner is strictly better, so it does not jump.
    float bottom = 0;  // of the lowest view: a window's timeline may lie below
    for (const auto& v : views) bottom = std::max(bottom, static_cast<float>(v.rect.y + v.rect.h));
    if (bottom <= 0) bottom = static_cast<float>(h);
    auto anchor = [&](int k) {
      return ImVec2(k % 2 == 0 ? right - pad : left + pad, k < 2 ? pad : bottom - pad);
    };
    auto pivot = [](int k) { return ImVec2(k % 2 == 0 ? 1.0f : 0.0f, k < 2 ? 0.0f : 1.0f); };
    if (o.place_clear && info_w_ > 0) {
      // Cost of corner k: the container under the box first (sampled every few pixels), then arch members,
      // then other disks.
      constexpr long kContainer = 1000000;
      auto covered = [&](int k) {
        const ImVec2 a = anchor(k), pv = pivot(k);
        const float x0 = a.x - pv.x * info_w_, y0 = a.y - pv.y * info_h_;
        long n = 0;
        if (geo) {
          const float step = std::max(3.0f, 0.25f * em);
          for (float py = y0; py <= y0 + info_h_; py += step)
            for (float px = x0; px <= x0 + info_w_; px += step)
              for (const auto& v : views)
                if (px >= v.rect.x && px < v.rect.x + v.rect.w && py >= v.rect.y &&
                    py < v.rect.y + v.rect.h && in_container(*geo, v.pixel_to_world({px, py}))) {
                  n += kContainer;
                  break;
                }
        }
        std::vector<char> in_arch(f.particles.size(), 0);
        for (int id : f.arch) in_arch[static_cast<size_t>(id)] = 1;
        for (const auto& v : views) {
          for (size_t i = 0; i < f.particles.size(); ++i) {
            const auto& p = f.particles[i];
            const core::Vec2 c = v.world_to_pixel({p.x, p.y});
            const double r = 1.3 * p.radius * v.px_per_m();  // with the arch's ring
            if (c.x < v.rect.x || c.x > v.rect.x + v.rect.w || c.y < v.rect.y || c.y > v.rect.y + v.rect.h)
              continue;
            // Covering an arch member is worst: it is what the inspector is for.
            if (c.x + r > x0 && c.x - r < x0 + info_w_ && c.y + r > y0 && c.y - r < y0 + info_h_)
              n += in_arch[i] ? 100 : 1;
          }
        }
        return n;
      };
      long best = covered(info_corner_);
      for (int k = 0; k < 4 && best > 0; ++k) {
        const long n = covered(k);
        if (n < best) best = n, info_corner_ = k;
      }
      info_left_ = o.may_leave && best >= kContainer;
    } else if (!o.place_clear) {
      info_corner_ = 0;
    }
    // Left out of the picture, the box is still laid out (off-screen) so its size follows the options.
    if (info_left_)
      ImGui::SetNextWindowPos(ImVec2(static_cast<float>(w) + 100 * em, 0));
    else
      ImGui::SetNextWindowPos(anchor(info_corner_), 0, pivot(info_corner_));
    ImGui::SetNextWindowBgAlpha(0.82f);
    ImGui::Begin("info", nullptr,
                 ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize |
                     ImGuiWindowFlags_NoInputs | ImGuiWindowFlags_NoSavedSettings |
                     ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoNav);
    info_contents(f, d, o, style, em);
    info_w_ = ImGui::GetWindowSize().x;
    info_h_ = ImGui::GetWindowSize().y;
    ImGui::End();
  }
}

void Overlay::draw_scale(const OverlayData& d, const std::vector<View>& views, float em) {
  ImDrawList* dl = ImGui::GetForegroundDrawList();
  // Scale bar: one original diameter, bottom-left of the most zoomed view.
  {
    const View* v = &views.front();
    for (const auto& c : views)
      if (c.px_per_m() > v->px_per_m()) v = &c;
    const float len = static_cast<float>(d.diameter * v->px_per_m());
    const float x0 = v->rect.x + em, y0 = v->rect.y + v->rect.h - 1.2f * em;
    const ImU32 ink = IM_COL32(20, 20, 20, 255);
    dl->AddRectFilled(ImVec2(x0, y0 - 0.25f * em), ImVec2(x0 + len, y0), ink);
    char text[64];
    std::snprintf(text, sizeof text, "1 d = %.0f cm", 100 * d.diameter);
    dl->AddText(ImVec2(x0, y0 - 1.45f * em), ink, text);
  }
}

void Overlay::build(const core::Frame& f, const OverlayData& d, const OverlayOptions& o,
                    const std::vector<View>& views, const Style& style, int w, int h,
                    const core::Geometry* geo, const Annotations& notes) {
  const float em = static_cast<float>(font_px_);
  info_left_ = false;
  ImDrawList* dl = ImGui::GetForegroundDrawList();

  if (o.zoombox && views.size() > 1) draw_zoombox(views, h);
  if (o.events) draw_events(notes, views, em);
  if (o.plot) plot(f, d, views, style);
  draw_colorbar(o, views, style, em);
  draw_info(f, d, o, views, style, w, h, geo, em);
  if (o.scale) draw_scale(d, views, em);
  // A bold line between panels of a comparison, thin separators between views.
  if (d.panel_x > 0)
    dl->AddLine(ImVec2(static_cast<float>(d.panel_x), 0),
                ImVec2(static_cast<float>(d.panel_x), static_cast<float>(h)), IM_COL32(20, 20, 20, 255),
                std::max(3.0f, h / 300.0f));
  // Thin separators between views.
  for (size_t k = 1; k < views.size(); ++k)
    dl->AddLine(ImVec2(static_cast<float>(views[k].rect.x), 0),
                ImVec2(static_cast<float>(views[k].rect.x), static_cast<float>(h)),
                IM_COL32(120, 120, 120, 255), std::max(1.0f, h / 720.0f));
}

}  // namespace render
