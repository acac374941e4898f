#include "render/overlay.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "core/error.h"
#include "core/format.h"
#include "core/setup.h"
#include "render/gl.h"
#include "render/overlay_detail.h"
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
}  // namespace

int parse_corner(const std::string& text, const std::string& option) {
  const char* names[] = {"top-right", "top-left", "bottom-right", "bottom-left"};
  if (text == "auto") return -1;
  for (int k = 0; k < 4; ++k)
    if (text == names[k]) return k;
  throw core::InputError(option + " " + text +
                         ": expected auto, top-right, top-left, bottom-right or bottom-left");
}

void parse_placement(const std::string& text, const std::string& option, OverlayOptions& o) {
  if (text.find('=') == std::string::npos) {
    o.info_at = parse_corner(text, option);
    return;
  }
  std::stringstream ss(text);
  for (std::string item; std::getline(ss, item, ',');) {
    const size_t eq = item.find('=');
    const std::string what = item.substr(0, eq == std::string::npos ? item.size() : eq);
    int* slot = what == "info"       ? &o.info_at
                : what == "plot"     ? &o.plot_at
                : what == "colorbar" ? &o.colorbar_at
                : what == "scale"    ? &o.scale_at
                                     : nullptr;
    if (eq == std::string::npos || !slot)
      throw core::InputError(option + " " + text + ": '" + item +
                             "': expected ELEMENT=CORNER with ELEMENT info, plot, colorbar or scale (or one "
                             "corner, for the information box)");
    *slot = parse_corner(item.substr(eq + 1), option + " " + what + "=");
  }
}

TimedNote parse_note(const std::string& spec, const std::string& option) {
  // T0:T1:X,Y:TEXT (the text may hold colons)
  auto fail = [&](const std::string& why) -> TimedNote {
    throw core::InputError(
        option + " '" + spec + "': " + why +
        " (expected T0:T1:X,Y:TEXT: from T0 to T1 s, an arrow to X,Y m, e.g. 2:6:0,0.3:the arch)");
  };
  std::vector<std::string> parts;
  size_t start = 0;
  for (int k = 0; k < 3; ++k) {
    const size_t colon = spec.find(':', start);
    if (colon == std::string::npos) return fail("missing a field");
    parts.push_back(spec.substr(start, colon - start));
    start = colon + 1;
  }
  TimedNote n;
  n.text = spec.substr(start);
  if (n.text.empty()) return fail("the text is empty");
  auto number = [&](const std::string& s, double& out) {
    char* end = nullptr;
    out = std::strtod(s.c_str(), &end);
    return !s.empty() && *end == '\0' && std::isfinite(out);
  };
  const size_t comma = parts[2].find(',');
  if (!number(parts[0], n.t0) || !number(parts[1], n.t1)) return fail("T0 and T1 must be numbers");
  if (!(n.t0 >= 0) || !(n.t1 > n.t0)) return fail("expected 0 <= T0 < T1");
  if (comma == std::string::npos || !number(parts[2].substr(0, comma), n.x) ||
      !number(parts[2].substr(comma + 1), n.y))
    return fail("X,Y must be two numbers (m)");
  return n;
}

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
    else if (item == "ids")
      o.ids = true;
    else
      throw core::InputError(
          "overlay '" + spec + "': '" + item +
          "' is not one of all, all+plot, none, time, counts, rate, timer, arch, legend, scale, "
          "events, zoombox, plot, colorbar, ids");
  }
  return o;
}

OverlayData overlay_data_for(const core::Model& model) {
  OverlayData d;
  const core::Scene& scene = model.scene;
  const core::Setup& st = model.setup;
  d.clog_timeout = scene.clog_timeout;
  d.clog_min_gap = scene.clog_min_gap;
  d.clog_rule = st.clog_rule;
  d.drain = scene.drain;
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

void Overlay::ensure_font(int h, double scale) {
  const int px = static_cast<int>(overlay_em(h, scale));
  if (px == font_px_) return;
  ImGuiIO& io = ImGui::GetIO();
  io.Fonts->Clear();
  // The text, then a comparison's headings in large type (drawn from its own glyphs: a scaled-up bitmap of
  // the text's would be blurred).
  auto add = [&](float size) {
    if (kFont[0] != '\0' && std::filesystem::exists(kFont)) return io.Fonts->AddFontFromFileTTF(kFont, size);
    ImFontConfig cfg;
    cfg.SizePixels = size;
    return io.Fonts->AddFontDefault(&cfg);
  };
  add(static_cast<float>(px));  // the first font added is ImGui's default
  heading_font_ = add(std::round(kHeadingScale * px));
  ImGui_ImplOpenGL3_DestroyFontsTexture();
  if (!ImGui_ImplOpenGL3_CreateFontsTexture())
    throw core::RuntimeFault("ImGui: cannot create the font texture");
  font_px_ = px;
  laid_out_ = false;  // the panel's size changes with the font
  // The gaps between words and swatches on one row in proportion to the text (ImGui's defaults are for its 13
  // px font): at 4K "27 added exits" and the legend's swatches keep the room they have at 720p. Paddings and
  // row spacing stay: the boxes keep the size the layout plans for.
  ImGuiStyle style;
  if (dark_)
    ImGui::StyleColorsDark(&style);
  else
    ImGui::StyleColorsLight(&style);
  const float k = overlay_style_scale(static_cast<float>(px));
  style.ItemSpacing.x *= k;
  style.ItemInnerSpacing.x *= k;
  ImGui::GetStyle() = style;
}

void Overlay::reset() {
  history_.clear();
  laid_out_ = false;
  info_w_ = info_h_ = info_x_ = info_y_ = 0;
  info_shown_ = false;
  bar_w_ = bar_h_ = 0;
  bar_rect_ = {};
  info_corner_ = 0;
  info_left_ = false;
  spots_.clear();
  text_spots_.clear();
}

void Overlay::draw(const core::Frame& f, const OverlayData& d, const OverlayOptions& o,
                   const std::vector<View>& views, const Style& style, int w, int h,
                   const core::Geometry* geo, const Annotations* notes) {
  static const Annotations none;
  const Annotations& marks = notes ? *notes : none;
  if (!o.any() && marks.selected < 0 && marks.texts.empty()) return;
  ImGuiContext* previous = ImGui::GetCurrentContext();
  ImGui::SetCurrentContext(static_cast<ImGuiContext*>(ctx_));
  ensure_font(h, o.font_scale);
  if (style.dark != dark_) {
    dark_ = style.dark;
    if (dark_)
      ImGui::StyleColorsDark();
    else
      ImGui::StyleColorsLight();
  }
  ImGuiIO& io = ImGui::GetIO();
  io.DisplaySize = ImVec2(static_cast<float>(w), static_cast<float>(h));
  io.DeltaTime = 1.0f / 30.0f;
  ImGui_ImplOpenGL3_NewFrame();
  // Auto-sized windows learn their size from what they held in the previous ImGui frame: lay every picture
  // out once without drawing it, so the boxes are sized and placed for this picture's own contents (sized
  // from the previous picture, a legend that grew by a row lost it, and a snapshot after a shorter one lost
  // its colour bar).
  // A window ImGui has not drawn before learns its size only at the end of its first frame: a fresh overlay
  // lays the picture out twice (the boxes are placed by their true sizes, not ImGui's 32-pixel start).
  // The free space of this picture, once: the container (kept between pictures while it stands still in
  // the views) and the grains.
  {
    const float em = static_cast<float>(font_px_);
    float y1 = 0;  // of the lowest view: a window's timeline may lie below
    for (const auto& v : views) y1 = std::max(y1, static_cast<float>(v.rect.y + v.rect.h));
    if (y1 <= 0) y1 = static_cast<float>(h);
    y1 = std::min(static_cast<float>(h), y1 + d.margin_h);  // and the band for the boxes below them
    const Box region{static_cast<float>(d.panel_x), 0,
                     d.panel_w > 0 ? static_cast<float>(d.panel_x + d.panel_w) : static_cast<float>(w), y1};
    const float cell = std::max(2.0f, 0.25f * em);
    picture_space_ = std::make_unique<FreeSpace>(
        container_space(views, geo, geo ? f.container_x : 0, geo ? f.container_y : 0, region, cell));
    picture_space_->block_grains(f, views);
    picture_space_->freeze();  // its summed-area table made once: each pass takes a copy
  }
  for (int pass = 0; pass < (laid_out_ ? 1 : 2); ++pass) {
    ImGui::NewFrame();
    build(f, d, o, views, style, w, h, geo, marks);
    ImGui::EndFrame();
  }
  laid_out_ = true;
  ImGui::NewFrame();
  build(f, d, o, views, style, w, h, geo, marks);
  ImGui::Render();
  glViewport(0, 0, w, h);
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
  check_gl("Overlay::draw");
  ImGui::SetCurrentContext(previous ? previous : static_cast<ImGuiContext*>(ctx_));
}

namespace {
bool same_views(const std::vector<View>& a, const std::vector<View>& b) {
  if (a.size() != b.size()) return false;
  for (size_t k = 0; k < a.size(); ++k) {
    const Camera &p = a[k].cam, &q = b[k].cam;
    const Rect &r = a[k].rect, &s = b[k].rect;
    if (p.cx != q.cx || p.cy != q.cy || p.height != q.height || p.angle != q.angle || r.x != s.x ||
        r.y != s.y || r.w != s.w || r.h != s.h)
      return false;
  }
  return true;
}
}  // namespace

const FreeSpace& Overlay::container_space(const std::vector<View>& views, const core::Geometry* geo,
                                          double dx, double dy, const Box& region, float cell) {
  const Box& r = container_region_;
  const bool same = container_space_ && geo == container_geo_ && dx == container_dx_ && dy == container_dy_ &&
                    cell == container_cell_ && region.x0 == r.x0 && region.y0 == r.y0 && region.x1 == r.x1 &&
                    region.y1 == r.y1 && same_views(views, container_views_);
  if (!same) {
    container_space_ = std::make_unique<FreeSpace>(region, cell);
    if (geo) container_space_->block_container(views, *geo, dx, dy);
    container_views_ = views;
    container_geo_ = geo;
    container_dx_ = dx, container_dy_ = dy;
    container_cell_ = cell;
    container_region_ = region;
  }
  return *container_space_;
}

std::optional<Box> Overlay::spot(const std::string& key, float w, float h, const Box& within, int corner,
                                 float pad) {
  const auto it = spots_.find(key);
  if (it != spots_.end()) {
    Spot& s = it->second;
    const Box& o = s.box;
    const Box& in = s.within;
    if (s.age < kRecheck && s.corner == corner && in.x0 == within.x0 && in.y0 == within.y0 &&
        in.x1 == within.x1 && in.y1 == within.y1) {
      // The same corner of the box where it was, at its new size.
      const float ax = corner % 2 == 0 ? o.x1 - w : o.x0, ay = corner < 2 ? o.y0 : o.y1 - h;
      const Box b{ax, ay, ax + w, ay + h};
      const Box lim{within.x0 + pad, within.y0 + pad, within.x1 - pad, within.y1 - pad};
      if (b.inside(lim) && space_->covered(b) == 0) {
        ++s.age;
        s.box = b;
        return b;
      }
    }
  }
  const std::optional<Box> b = space_->place_at_corner(w, h, within, corner, pad);
  if (b)
    spots_[key] = {*b, within, corner, 0};
  else
    spots_.erase(key);
  return b;
}

void Overlay::build(const core::Frame& f, const OverlayData& d, const OverlayOptions& o,
                    const std::vector<View>& views, const Style& style, int w, int h,
                    const core::Geometry* geo, const Annotations& notes) {
  const float em = static_cast<float>(font_px_);
  info_left_ = false;
  ImDrawList* dl = ImGui::GetForegroundDrawList();

  if (o.zoombox && views.size() > 1) draw_zoombox(views, h);
  if (o.ids || notes.selected >= 0) draw_ids(f, views, o.ids, notes.selected, em);
  // What the boxes keep off: the container as this picture shows it (where a vibrating one is now), the
  // grains, and each box placed before the next. The information box first: the plot, the colour bar and
  // the scale bar are placed clear of it.
  panel_x0_ = static_cast<float>(d.panel_x);
  panel_x1_ = d.panel_w > 0 ? static_cast<float>(d.panel_x + d.panel_w) : static_cast<float>(w);
  panel_y1_ = 0;  // of the lowest view: a window's timeline may lie below
  for (const auto& v : views) panel_y1_ = std::max(panel_y1_, static_cast<float>(v.rect.y + v.rect.h));
  if (panel_y1_ <= 0) panel_y1_ = static_cast<float>(h);
  panel_y1_ = std::min(static_cast<float>(h), panel_y1_ + d.margin_h);
  space_ = std::make_unique<FreeSpace>(*picture_space_);
  info_shown_ = false;
  plot_rect_ = scale_rect_ = {};
  boxes_clear_ = true;
  heading_rect_ = {};
  if (!d.heading.empty() && d.heading_h > 0) draw_heading(d, em);
  draw_info(f, d, o, views, style, w, h, geo, em);
  if (o.plot) plot(f, d, o, views, style);
  draw_colorbar(o, views, style, em);
  if (o.scale) draw_scale(d, o, views, em);
  // The texts over the scene after the boxes, in the space they left: none over a box or another text.
  texts_.clear();
  if (heading_rect_[2] > heading_rect_[0]) texts_.push_back({"heading", heading_rect_, true});
  place_texts(notes, views, em, o.events);  // widest first, then drawn where each was placed
  if (o.events) draw_events(notes, views, em);
  if (!notes.texts.empty()) draw_texts(notes, views, em);  // the user's own: shown whatever the overlay
  // A bold line between panels of a comparison, thin separators between views.
  if (d.panel_x > 0)
    dl->AddLine(ImVec2(static_cast<float>(d.panel_x), 0),
                ImVec2(static_cast<float>(d.panel_x), static_cast<float>(h)), IM_COL32(20, 20, 20, 255),
                std::max(3.0f, h / 300.0f));
  // Thin separators between views.
  for (size_t k = 1; k < views.size(); ++k)
    dl->AddLine(
        ImVec2(static_cast<float>(views[k].rect.x), static_cast<float>(views[k].rect.y)),
        ImVec2(static_cast<float>(views[k].rect.x), static_cast<float>(views[k].rect.y + views[k].rect.h)),
        IM_COL32(120, 120, 120, 255), std::max(1.0f, h / 720.0f));
}

}  // namespace render
