// The overlay's marks on the picture itself: the discharge plot, the zoom box, the ids, the scale bar, and
// the shared helpers of overlay_detail.h (the texts over the scene: overlay_texts.cpp).
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

#include "render/overlay.h"
#include "render/overlay_detail.h"

namespace render {

namespace overlay_detail {

namespace {
void scale_bar(const char* label, double lo, double hi, const Style& style, float em, bool chains = false) {
  ImGui::Text("%s %.3g", label, lo);
  ImGui::SameLine();
  ImVec2 p = ImGui::GetCursorScreenPos();
  const int steps = 32;
  const float bw = 8 * em, bh = ImGui::GetTextLineHeight();
  for (int k = 0; k < steps; ++k)
    ImGui::GetWindowDrawList()->AddRectFilled(
        ImVec2(p.x + bw * k / steps, p.y), ImVec2(p.x + bw * (k + 1) / steps, p.y + bh),
        to_u32(chains ? chain_color(style, (k + 0.5) / steps) : colormap(style, (k + 0.5) / steps)));
  ImGui::Dummy(ImVec2(bw, bh));
  ImGui::SameLine();
  if (hi > lo)
    ImGui::Text("%.3g", hi);
  else
    ImGui::TextUnformatted("each frame's largest");  // displacement "auto", not yet settled on a frame
}
}  // namespace

void colour_bar(const Style& style, float em) {
  // The grains' colour scale, then the force chains' (each on its own line).
  const std::string label = color_scale_label(style);
  if (!label.empty()) scale_bar(label.c_str(), style.color_min, color_scale_max(style), style, em);
  if (style.chains) scale_bar("force chains [N]", style.chain_min, style.chain_max, style, em, true);
}

const View& most_zoomed(const std::vector<View>& views) {
  const View* v = &views.front();
  for (const auto& c : views)
    if (c.px_per_m() > v->px_per_m()) v = &c;
  return *v;
}

void boxed_text(ImDrawList* dl, float cx, float y, const char* text, ImU32 ink, ImU32 box, float em) {
  const ImVec2 size = ImGui::CalcTextSize(text);
  const ImVec2 a(cx - 0.5f * size.x - 0.4f * em, y),
      b(cx + 0.5f * size.x + 0.4f * em, y + size.y + 0.3f * em);
  dl->AddRectFilled(a, b, box, 0.3f * em);
  dl->AddText(ImVec2(a.x + 0.4f * em, a.y + 0.15f * em), ink, text);
}
}  // namespace overlay_detail

using overlay_detail::boxed_text;
using overlay_detail::most_zoomed;
using overlay_detail::to_u32;

void Overlay::plot(const core::Frame& f, const OverlayData& d, const OverlayOptions& o,
                   const std::vector<View>& views, const Style& style) {
  // The discharge staircase: cumulative exits of each species against time, clogs shaded. Bottom-right of the
  // most zoomed view, below the outlet where there are no disks.
  if (!history_.empty() && f.t < history_.back().t) history_.clear();  // a new run or a jump back (inspector)
  // One sample per picture (each is laid out, then drawn; a window redraws a still frame many times).
  if (history_.empty() || f.t != history_.back().t)
    history_.push_back({f.t, f.exits, f.clog_open, f.clog_start});
  const float em = static_cast<float>(font_px_), pad = 0.6f * em;
  const View& v = most_zoomed(views);
  // The clear spot nearest to the panel's bottom-right (below the outlet where there are no grains): at
  // full size, else as wide as the margin kept beside the container, else smaller.
  const Box region{panel_x0_, 0, panel_x1_, panel_y1_};
  std::optional<Box> spot;
  if (o.plot_at >= 0) {  // the user's corner of the panel, whatever it covers
    const auto [bw, bh] = plot_box_size(static_cast<float>(v.rect.w), static_cast<float>(v.rect.h), em);
    const bool right = o.plot_at % 2 == 0, bottom = o.plot_at >= 2;
    const float x0 = right ? region.x1 - pad - bw : region.x0 + pad;
    const float y0 = bottom ? region.y1 - pad - bh : region.y0 + pad;
    spot = Box{x0, y0, x0 + bw, y0 + bh};
  }
  if (!spot)
    for (const auto& [bw, bh] : plot_box_sizes(
             static_cast<float>(v.rect.w), static_cast<float>(v.rect.h), em, static_cast<float>(d.margin_w),
             d.margin_h > 0 && info_shown_ ? region.x1 - region.x0 - info_w_ : 0.0f))
      if ((spot = this->spot("plot", bw, bh, region, 2, pad))) break;
  if (!spot) {  // nowhere clear: bottom-right of the outlet view, as ever
    boxes_clear_ = false;
    const auto [bw, bh] = plot_box_size(static_cast<float>(v.rect.w), static_cast<float>(v.rect.h), em);
    const float right = v.rect.x + v.rect.w - 0.4f * em, bottom = v.rect.y + v.rect.h - 0.2f * em;
    spot = Box{right - bw, bottom - bh, right, bottom};
  }
  space_->block(*spot, 0.4f * em);
  plot_rect_ = {spot->x0, spot->y0, spot->x1, spot->y1};
  // The axes inside the box: the largest count left of them, the caption below.
  const float x0 = spot->x0 + 2.6f * em, x1 = spot->x1 - 0.4f * em;
  const float y0 = spot->y0 + 1.5f * em, y1 = spot->y1 - 1.4f * em;
  const float pw = x1 - x0, ph = y1 - y0;
  ImDrawList* dl = ImGui::GetForegroundDrawList();
  dl->AddRectFilled(ImVec2(spot->x0, spot->y0), ImVec2(spot->x1, spot->y1),
                    style.dark ? IM_COL32(30, 30, 36, 215) : IM_COL32(255, 255, 255, 215), 0.3f * em);
  const double tmax = std::max(1.0, history_.back().t);
  // One staircase per species, on one scale.
  const size_t n_species = std::max<size_t>(1, d.species_names.size());
  long nmax = 1;
  for (const auto& s : history_)
    for (std::int64_t e : s.exits) nmax = std::max(nmax, static_cast<long>(e));
  auto X = [&](double t) { return x0 + static_cast<float>(t / tmax) * pw; };
  auto Y = [&](double n) { return y1 - static_cast<float>(n / static_cast<double>(nmax)) * ph; };
  // Clogs: shaded from the clog's start (its last exit, as clogs.csv's start_s), not from the moment the
  // timer passed clog_min_gap.
  // Each clog one band (its samples merged): a long movie draws as many bands as clogs, not as samples.
  for (size_t k = 1; k < history_.size(); ++k) {
    if (!history_[k].clogged) continue;
    size_t last = k;
    while (last + 1 < history_.size() && history_[last + 1].clogged &&
           history_[last + 1].clog_start == history_[k].clog_start)
      ++last;
    dl->AddRectFilled(ImVec2(X(std::max(0.0, history_[k].clog_start)), y0),
                      ImVec2(X(history_[last].t) + 0.5f, y1),
                      style.dark ? IM_COL32(80, 80, 92, 255) : IM_COL32(200, 200, 200, 255));  // dim on dark
    k = last;
  }
  auto exits_at = [&](size_t k, size_t sp) {
    const auto& e = history_[k].exits;
    return sp < e.size() ? static_cast<long>(e[sp]) : 0L;
  };
  // Each staircase one polyline through its steps only (samples without an exit add no point).
  std::vector<ImVec2> stairs;
  for (size_t sp = 0; sp < n_species; ++sp) {
    const ImU32 ink = to_u32(species_color(style, static_cast<core::Species>(sp)));
    stairs.assign(1, ImVec2(X(history_.front().t), Y(static_cast<double>(exits_at(0, sp)))));
    for (size_t k = 1; k < history_.size(); ++k) {
      const long a = exits_at(k - 1, sp), b = exits_at(k, sp);
      if (b == a) continue;
      stairs.push_back(ImVec2(X(history_[k].t), Y(static_cast<double>(a))));
      stairs.push_back(ImVec2(X(history_[k].t), Y(static_cast<double>(b))));
    }
    stairs.push_back(ImVec2(X(history_.back().t), Y(static_cast<double>(exits_at(history_.size() - 1, sp)))));
    dl->AddPolyline(stairs.data(), static_cast<int>(stairs.size()), ink, ImDrawFlags_None, 2.0f);
  }
  const ImU32 axis = style.dark ? IM_COL32(220, 220, 220, 255) : IM_COL32(40, 40, 40, 255);
  dl->AddLine(ImVec2(x0, y1), ImVec2(x1, y1), axis);
  dl->AddLine(ImVec2(x0, y0), ImVec2(x0, y1), axis);
  // Ticks at a round step (1, 2 or 5 times a power of ten) giving at most six on each axis.
  auto step_for = [](double span) {
    const double raw = span / 6, p = std::pow(10.0, std::floor(std::log10(raw)));
    for (double m : {1.0, 2.0, 5.0, 10.0})
      if (m * p >= raw) return m * p;
    return 10 * p;
  };
  const float tick = 0.3f * em;
  const double t_step = step_for(tmax), n_step = step_for(static_cast<double>(nmax));
  for (double t = t_step; t <= tmax + 1e-9; t += t_step)
    dl->AddLine(ImVec2(X(t), y1), ImVec2(X(t), y1 + tick), axis);
  for (double c = n_step; c <= static_cast<double>(nmax) + 1e-9; c += n_step)
    dl->AddLine(ImVec2(x0 - tick, Y(c)), ImVec2(x0, Y(c)), axis);
  char text[64];
  std::snprintf(text, sizeof text, "%ld", nmax);
  dl->AddText(ImVec2(x0 - 2.3f * em, y0 - 0.5f * em), axis, text);
  std::snprintf(text, sizeof text, "exits vs t (0-%.0f s, ticks %g s), clogs shaded", tmax, t_step);
  if (ImGui::CalcTextSize(text).x > spot->x1 - x0)
    std::snprintf(text, sizeof text, "exits, 0-%.0f s", tmax);  // a narrow plot (in a margin)
  dl->AddText(ImVec2(x0, y1 + 0.1f * em), axis, text);
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
                  ImVec2(static_cast<float>(b.x), static_cast<float>(b.y)),
                  dark_ ? IM_COL32(220, 220, 225, 230) : IM_COL32(30, 30, 30, 230), 0, 0,
                  std::max(1.5f, h / 500.0f));
      dl->PopClipRect();
    }
  }
}

void Overlay::draw_ids(const core::Frame& f, const std::vector<View>& views, bool arch_ids, int selected,
                       float em) {
  // Arch members' ids in small boxes above each member, and the selected grain ringed in the inspector's
  // highlight colour with its id, in every view (clipped to it).
  ImDrawList* dl = ImGui::GetForegroundDrawList();
  const ImU32 ink = IM_COL32(255, 255, 255, 255), box = IM_COL32(30, 30, 30, 200);
  const ImU32 ring = IM_COL32(0, 170, 255, 255);
  const bool has_selected = selected >= 0 && static_cast<size_t>(selected) < f.particles.size();
  for (const auto& v : views) {
    dl->PushClipRect(
        ImVec2(static_cast<float>(v.rect.x), static_cast<float>(v.rect.y)),
        ImVec2(static_cast<float>(v.rect.x + v.rect.w), static_cast<float>(v.rect.y + v.rect.h)));
    auto label = [&](int id, float above) {
      const core::Particle& p = f.particles[static_cast<size_t>(id)];
      const core::Vec2 c = v.world_to_pixel({p.x, p.y});
      const float r = static_cast<float>(p.radius * v.px_per_m());
      const std::string text = std::to_string(id);
      boxed_text(dl, static_cast<float>(c.x), static_cast<float>(c.y) - r - above - 1.2f * em, text.c_str(),
                 ink, box, em);
      return std::pair<ImVec2, float>(ImVec2(static_cast<float>(c.x), static_cast<float>(c.y)), r);
    };
    // Only where members are drawn big enough to tell apart (at least a text height across).
    const bool legible =
        !f.arch.empty() && f.particles[static_cast<size_t>(f.arch.front())].radius * v.px_per_m() > 0.5 * em;
    if (arch_ids && legible)
      for (int id : f.arch)
        if (id != selected) label(id, 0);
    if (has_selected) {
      const auto [c, r] = label(selected, 0.3f * em);
      dl->AddCircle(c, r + 0.15f * em, ring, 0, std::max(2.0f, 0.18f * em));
    }
    dl->PopClipRect();
  }
}

void Overlay::draw_scale(const OverlayData& d, const OverlayOptions& o, const std::vector<View>& views,
                         float em) {
  ImDrawList* dl = ImGui::GetForegroundDrawList();
  // Scale bar: one original diameter, at the clear spot nearest the bottom-left of the most zoomed view
  // (whose scale it shows); else anywhere clear in the panel, saying which view it measures.
  const View& v = most_zoomed(views);
  const float len = static_cast<float>(d.diameter * v.px_per_m());
  char text[96];
  std::snprintf(text, sizeof text, "1 d = %.0f cm", 100 * d.diameter);
  float tw = std::max(len, ImGui::CalcTextSize(text).x);
  const Box view{static_cast<float>(v.rect.x), static_cast<float>(v.rect.y),
                 static_cast<float>(v.rect.x + v.rect.w), static_cast<float>(v.rect.y + v.rect.h)};
  std::optional<Box> spot;
  if (o.scale_at >= 0) {  // the user's corner of the view, whatever it covers
    const bool right = o.scale_at % 2 == 0, bottom = o.scale_at >= 2;
    const float x0 = right ? view.x1 - em - tw : view.x0 + em;
    const float y0 = bottom ? view.y1 - em - 1.7f * em : view.y0 + em;
    spot = Box{x0, y0, x0 + tw, y0 + 1.7f * em};
  } else {
    spot = this->spot("scale:" + v.name, tw, 1.7f * em, view, 3, em);
  }
  if (!spot && views.size() > 1) {
    std::snprintf(text, sizeof text, "1 d = %.0f cm (%s view)", 100 * d.diameter, v.name.c_str());
    tw = std::max(len, ImGui::CalcTextSize(text).x);
  }
  if (!spot) spot = space_->place_at_corner(tw, 1.7f * em, {panel_x0_, 0, panel_x1_, panel_y1_}, 3, em);
  if (!spot) boxes_clear_ = false;
  if (!spot)
    spot = Box{view.x0 + em, view.y1 - 1.2f * em - 1.7f * em, view.x0 + em + tw, view.y1 - 1.2f * em};
  space_->block(*spot, 0.4f * em);
  scale_rect_ = {spot->x0, spot->y0, spot->x1, spot->y1};
  const float x0 = spot->x0, y0 = spot->y1 - 0.25f * em;
  const ImU32 ink = dark_ ? IM_COL32(235, 235, 235, 255) : IM_COL32(20, 20, 20, 255);
  dl->AddRectFilled(ImVec2(x0, y0 - 0.25f * em), ImVec2(x0 + len, y0), ink);
  dl->AddText(ImVec2(x0, y0 - 1.45f * em), ink, text);
}

}  // namespace render
