// The overlay's information box: its lines (also shown in the windows' side panels) and where it goes on a
// picture, off the container and the arch where a corner allows; the lone colour bar.
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "render/draw_list.h"
#include "render/overlay.h"
#include "render/overlay_detail.h"

namespace render {

using overlay_detail::colour_bar;
using overlay_detail::most_zoomed;
using overlay_detail::to_u32;

// The information box's lines, into the current ImGui window.
void info_contents(const core::Frame& f, const OverlayData& d, const OverlayOptions& o, const Style& given,
                   float em) {
  Style style = given;  // the scene's own species colours, wherever the box is drawn (a window's side panel)
  if (!d.species_colors.empty()) style.species_colors = d.species_colors;
  if (!d.title.empty()) {
    ImGui::PushTextWrapPos(ImGui::GetCursorPosX() + info_title_wrap(em, d.margin_w));
    ImGui::TextUnformatted(d.title.c_str());
    ImGui::PopTextWrapPos();
  }
  if (o.time) ImGui::Text("t = %.2f s", f.t);
  const bool shorthand = d.species_names.size() == 2 && d.species_names[0] == "original";
  auto colored = [&](core::Species sp, const std::string& text) {
    const Rgba c = species_color(style, sp);
    ImGui::TextColored(ImVec4(c.r, c.g, c.b, 1), "%s", text.c_str());
  };
  if (o.counts) {
    // Each species' exits in its own colour: "40 original 12 added exits", "52 exits: 30 a, 22 b".
    const size_t n_species = std::max<size_t>(1, d.species_names.size());
    if (n_species == 1) {
      ImGui::Text("%lld exits", static_cast<long long>(f.exits_total()));
    } else {
      if (!shorthand) {
        ImGui::Text("%lld exits:", static_cast<long long>(f.exits_total()));
        ImGui::SameLine();
      }
      for (size_t k = 0; k < n_species; ++k) {
        if (k > 0) ImGui::SameLine();
        colored(static_cast<core::Species>(k),
                std::to_string(f.exits_of(static_cast<int>(k))) + " " + d.species_names[k]);
      }
      if (shorthand) {
        ImGui::SameLine();
        ImGui::TextUnformatted("exits");
      }
    }
  }
  if (o.rate)
    ImGui::Text("%s = %.2f /s (%s, so far)", shorthand || d.species_names.size() > 1 ? "Q~" : "Q",
                f.t > 0 ? static_cast<double>(f.exits_of(0)) / f.t : 0.0,
                shorthand ? "originals" : d.species_names.front().c_str());
  if (o.timer) {
    const bool clogged = f.clog_open;  // as the simulation's step reported it
    const double frac = d.clog_rule ? std::min(1.0, f.since_last_exit / d.clog_timeout) : clogged ? 1.0 : 0.0;
    ImGui::PushStyleColor(ImGuiCol_PlotHistogram,
                          clogged ? ImVec4(0.85f, 0.25f, 0.15f, 1) : ImVec4(0.3f, 0.6f, 0.3f, 1));
    char label[64];
    if (!clogged && f.arch_forming)  // the clog its arch will cause is not confirmed yet
      std::snprintf(label, sizeof label, "no exit for %.1f s", f.since_last_exit);
    else if (!clogged)
      std::snprintf(label, sizeof label, "flowing");
    else if (d.drain && f.since_last_exit >= d.clog_timeout)  // a drain's jam: what the timeline calls it
      std::snprintf(label, sizeof label, "jammed (clogged %.1f s)", f.since_last_exit);
    else if (d.drain)
      std::snprintf(label, sizeof label, "clogged %.1f s / %.3g s: jam", f.since_last_exit, d.clog_timeout);
    else if (d.clog_rule)
      std::snprintf(label, sizeof label, "clogged %.1f s / %.0f s", f.since_last_exit, d.clog_timeout);
    else
      std::snprintf(label, sizeof label, "clogged %.1f s (no rule)", f.since_last_exit);
    // The label beside the bar, not over it: over it, it begins wherever the fill ends, half on red.
    ImGui::ProgressBar(static_cast<float>(frac), ImVec2(5 * em, 0), "");
    ImGui::PopStyleColor();
    ImGui::SameLine();
    ImGui::TextUnformatted(label);
  }
  if (o.arch && !f.arch.empty()) {
    int added = 0;
    for (int id : f.arch) added += f.particles[id].species != core::Species::Original;
    const char* forming = f.arch_forming ? ", forming" : "";
    if (shorthand)
      ImGui::Text("arch: %zu disks (%d added)%s", f.arch.size(), added, forming);
    else
      ImGui::Text("arch: %zu grains%s", f.arch.size(), forming);
    // The arrows' scale: the longest, a member's diameter, is this force.
    if (given.arch_forces && given.show_arch)
      if (const double top = largest_arch_force(f); top > 0)
        ImGui::Text("arrows: forces on it, longest %.3g N", top);
  }
  if (o.legend) {
    ImGui::Separator();
    const float r = 0.4f * em;
    auto swatch = [&](Rgba fill, Rgba ring, const char* text) {
      // The ring's outer edge (its radius and half its stroke) inside the swatch's own room, on both sides.
      const float outer = r + 0.3f * em;
      ImVec2 p = ImGui::GetCursorScreenPos();
      ImVec2 c(p.x + outer, p.y + 0.5f * ImGui::GetTextLineHeight());
      const Rgba edge = halo_edge_color(style);  // as the picture's halos have it
      if (ring.a > 0 && edge.a > 0)
        ImGui::GetWindowDrawList()->AddCircle(c, r + 0.15f * em, to_u32(edge), 0, 0.4f * em);
      if (ring.a > 0) ImGui::GetWindowDrawList()->AddCircle(c, r + 0.15f * em, to_u32(ring), 0, 0.25f * em);
      ImGui::GetWindowDrawList()->AddCircleFilled(c, r, to_u32(fill));
      ImGui::Dummy(ImVec2(2 * outer, ImGui::GetTextLineHeight()));
      ImGui::SameLine();
      ImGui::TextUnformatted(text);
    };
    if (style.color == ColorMode::Species) {
      for (size_t k = 0; k < d.species_names.size(); ++k) {
        swatch(species_color(style, static_cast<core::Species>(k)), {0, 0, 0, 0}, d.species_names[k].c_str());
        ImGui::SameLine();
      }
      if (style.chains) ImGui::NewLine();
    }
    if (style.color == ColorMode::Id) ImGui::TextUnformatted("colour: grain id");
    colour_bar(style, em);
    // What the picture marks: the arch's halo (unless it is off), the tracked grains' ring.
    if (style.show_arch) swatch({0.85f, 0.85f, 0.85f, 1}, arch_color(style), "arch");
    if (!style.tracked.empty()) {
      if (style.show_arch) ImGui::SameLine();
      swatch({0.85f, 0.85f, 0.85f, 1}, tracked_color(style), "tracked");
    }
  }
}

void Overlay::draw_colorbar(const OverlayOptions& o, const std::vector<View>& views, const Style& style,
                            float em) {
  bar_rect_ = {};
  if (o.colorbar && !o.legend && (!color_scale_label(style).empty() || style.chains)) {
    const View& zoom = most_zoomed(views);
    const float bw = bar_w_ > 0 ? bar_w_ : 16 * em, bh = bar_h_ > 0 ? bar_h_ : 2 * em;
    // Top-right of the outlet view; with the information box drawn, beside it on the side it stands (below
    // a top box, above a bottom one); in either case the clear spot nearest to there.
    float right = zoom.rect.x + zoom.rect.w - 0.6f * em;
    float top = zoom.rect.y + 0.6f * em;
    ImVec2 pivot(1.0f, 0.0f);
    if (info_shown_) {
      const bool left_side = info_corner_ % 2 == 1, bottom = info_corner_ >= 2;
      right = left_side ? info_x_ : info_x_ + info_w_;
      pivot = ImVec2(left_side ? 0.0f : 1.0f, bottom ? 1.0f : 0.0f);
      top = bottom ? info_y_ - 0.4f * em : info_y_ + info_h_ + 0.4f * em;
    }
    const Box region{panel_x0_, 0, panel_x1_, panel_y1_};
    if (o.colorbar_at >= 0) {  // the user's corner of the panel, whatever it covers
      const float pad = 0.6f * em;
      right = o.colorbar_at % 2 == 0 ? region.x1 - pad : region.x0 + pad;
      pivot = ImVec2(o.colorbar_at % 2 == 0 ? 1.0f : 0.0f, 0.0f);
      top = o.colorbar_at >= 2 ? region.y1 - pad - bh : pad;
    } else if (const auto b = space_->place(bw, bh, region, right, top, pivot.x, pivot.y)) {
      right = b->x0, top = b->y0, pivot = ImVec2(0, 0);
    } else {
      boxes_clear_ = false;
      if (pivot.y > 0) top -= bh, pivot.y = 0;
    }
    ImGui::SetNextWindowPos(ImVec2(right, top), 0, ImVec2(pivot.x, 0));
    ImGui::SetNextWindowBgAlpha(0.82f);
    ImGui::Begin("colorbar", nullptr,
                 ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize |
                     ImGuiWindowFlags_NoInputs | ImGuiWindowFlags_NoSavedSettings |
                     ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoNav);
    colour_bar(style, em);
    bar_w_ = ImGui::GetWindowSize().x;
    bar_h_ = ImGui::GetWindowSize().y;
    bar_rect_ = {ImGui::GetWindowPos().x, ImGui::GetWindowPos().y, ImGui::GetWindowPos().x + bar_w_,
                 ImGui::GetWindowPos().y + bar_h_};
    ImGui::End();
    space_->block({bar_rect_[0], bar_rect_[1], bar_rect_[2], bar_rect_[3]}, 0.4f * em);
  }
}

void Overlay::draw_info(const core::Frame& f, const OverlayData& d, const OverlayOptions& o,
                        const std::vector<View>& views, const Style& style, int w, int h,
                        const core::Geometry* geo, float em) {
  const bool panel = o.time || o.counts || o.rate || o.timer || o.arch || o.legend;
  if (!panel) return;
  const float pad = 0.6f * em;
  const Box region{panel_x0_, 0, panel_x1_, panel_y1_};
  // Corner k's anchor and pivot (the user's corner, and the fallback).
  auto anchor = [&](int k) {
    return ImVec2(k % 2 == 0 ? region.x1 - pad : region.x0 + pad, k < 2 ? pad : region.y1 - pad);
  };
  auto pivot = [](int k) { return ImVec2(k % 2 == 0 ? 1.0f : 0.0f, k < 2 ? 0.0f : 1.0f); };
  auto box_at = [&](int k) {
    const ImVec2 a = anchor(k), pv = pivot(k);
    const float x0 = a.x - pv.x * info_w_, y0 = a.y - pv.y * info_h_;
    return Box{x0, y0, x0 + info_w_, y0 + info_h_};
  };
  ImVec2 pos = anchor(0), piv = pivot(0);
  if (o.info_at >= 0 && o.info_at < 4) {
    info_corner_ = o.info_at;  // the user's corner, whatever it covers
    pos = anchor(info_corner_), piv = pivot(info_corner_);
  } else if (info_w_ > 0) {
    // The clear spot nearest to the corner the box is in (a window's box does not jump between corners;
    // a movie's starts top-right): off the container, its grains and its arch, measured on this picture.
    const int preferred = o.place_clear ? info_corner_ : 0;
    // With a band kept below the views for the boxes, the box goes to its top-right (reaching up as high as
    // it needs where the band is lower than it): in every panel of a comparison at the same place.
    std::optional<Box> b;
    bool in_band = false;
    if (d.margin_h > 0) {
      // As tall as the plan reserved (every row: a box that gains a clog's row grows into that room, not
      // off the picture's bottom), at the top-right of that room.
      const float room = std::max(info_h_, static_cast<float>(d.info_h));
      b = spot("info band", info_w_, room, info_band(region, static_cast<float>(d.margin_h), room, pad), 0,
               pad);
      if (b) b->y1 = b->y0 + info_h_, in_band = true;
    }
    if (!b) b = spot("info", info_w_, info_h_, region, preferred, pad);
    if (b) {
      // Held at its top-left, or in the band at its top-right (every panel's box ends at the same edge).
      pos = in_band ? ImVec2(b->x1, b->y0) : ImVec2(b->x0, b->y0), piv = ImVec2(in_band ? 1.0f : 0.0f, 0);
      const float cx = 0.5f * (b->x0 + b->x1), cy = 0.5f * (b->y0 + b->y1);
      info_corner_ = (cx < 0.5f * (region.x0 + region.x1) ? 1 : 0) + (cy > 0.5f * region.y1 ? 2 : 0);
    } else {
      // No clear spot: the corner covering the least (the container counts above any number of grains),
      // or, in a window, beside the picture.
      const FreeSpace& walls = *container_space_;  // the container alone, as this picture's views show it
      constexpr long kContainer = 1000000;
      auto cost = [&](int k) { return kContainer * walls.covered(box_at(k)) + space_->covered(box_at(k)); };
      long best = cost(info_corner_);
      for (int k = 0; k < 4; ++k)
        if (const long c = cost(k); c < best) best = c, info_corner_ = k;
      info_left_ = o.may_leave && best >= kContainer;
      boxes_clear_ = boxes_clear_ && (info_left_ || best == 0);
      pos = anchor(info_corner_), piv = pivot(info_corner_);
    }
  }
  // Left out of the picture, the box is still laid out (off-screen) so its size follows the options.
  if (info_left_)
    ImGui::SetNextWindowPos(ImVec2(static_cast<float>(w) + 100 * em, 0));
  else
    ImGui::SetNextWindowPos(pos, 0, piv);
  (void)h;
  ImGui::SetNextWindowBgAlpha(0.82f);
  ImGui::Begin("info", nullptr,
               ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoInputs |
                   ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing |
                   ImGuiWindowFlags_NoNav);
  info_contents(f, d, o, style, em);
  info_w_ = ImGui::GetWindowSize().x;
  info_h_ = ImGui::GetWindowSize().y;
  info_x_ = ImGui::GetWindowPos().x;
  info_y_ = ImGui::GetWindowPos().y;
  info_shown_ = !info_left_;
  ImGui::End();
  if (info_shown_) space_->block({info_x_, info_y_, info_x_ + info_w_, info_y_ + info_h_}, 0.4f * em);
}

// A comparison panel's heading: centred in the band above its views, in large type (smaller where a word
// would not fit a row or the rows the band), wrapped between words; blocked for the boxes placed after it.
void Overlay::draw_heading(const OverlayData& d, float em) {
  ImFont* font = static_cast<ImFont*>(heading_font_);
  if (!font) return;
  const char* text = d.heading.c_str();
  const char* end = text + d.heading.size();
  const float band = static_cast<float>(d.heading_h), wrap = std::max(4 * em, panel_x1_ - panel_x0_ - 2 * em);
  // Its rows, wrapped between words, at `size` pixels.
  auto rows = [&](float size) {
    std::vector<std::pair<const char*, const char*>> out;
    for (const char* s = text; s < end;) {
      while (s < end && *s == ' ') ++s;
      if (s == end) break;
      const char* eol = font->CalcWordWrapPositionA(size / font->FontSize, s, end, wrap);
      if (eol <= s) eol = s + 1;
      out.push_back({s, eol});
      s = eol;
    }
    return out;
  };
  // The widest word must fit a row whole (else ImGui cuts it), and the rows the band: smaller type until
  // both hold, down to the text's.
  auto fits = [&](float size) {
    for (const char* s = text; s < end;) {
      const char* e = s;
      while (e < end && *e != ' ') ++e;
      if (font->CalcTextSizeA(size, FLT_MAX, 0, s, e).x > wrap) return false;
      s = e < end ? e + 1 : e;
    }
    return rows(size).size() * 1.2f * size <= band - 0.3f * em;
  };
  float size = font->FontSize;
  while (size > em && !fits(size)) size = std::max(em, 0.92f * size);
  const auto lines = rows(size);
  const float line_h = 1.2f * size;
  float y = 0.5f * (band - lines.size() * line_h) + 0.1f * size;
  ImDrawList* dl = ImGui::GetForegroundDrawList();
  const ImU32 colour = ImGui::GetColorU32(ImGuiCol_Text);
  Box r{panel_x1_, y, panel_x0_, y + lines.size() * line_h};
  for (const auto& [s, e] : lines) {
    const float tw = font->CalcTextSizeA(size, FLT_MAX, 0, s, e).x;
    const float x = 0.5f * (panel_x0_ + panel_x1_ - tw);
    dl->AddText(font, size, ImVec2(x, y), colour, s, e);
    r.x0 = std::min(r.x0, x), r.x1 = std::max(r.x1, x + tw);
    y += line_h;
  }
  heading_rect_ = {r.x0, r.y0, r.x1, r.y1};
  space_->block(r, 0.4f * em);
}

}  // namespace render
