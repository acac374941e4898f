// The texts over the scene: an event's caption and the rings of the grains the rule removed, the slow-motion
// badge, the user's notes with their arrows; placed after the boxes, widest first, none over a box or another
// text, off the grains where the panel has room.
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

#include "render/overlay.h"
#include "render/overlay_detail.h"

namespace render {

using overlay_detail::boxed_text;
using overlay_detail::most_zoomed;

void Overlay::draw_events(const Annotations& notes, const std::vector<View>& views, float em) {
  ImDrawList* dl = text_draw_list();
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
    // The caption and the badge stay inside the panel (its views, and the column or band the plan gave the
    // boxes, where the record plan counted them: overlay_margin's texts), clear of the boxes and the grains
    // where the panel has room (the layout's free space), else off the boxes and texts (place_text).
    const Box panel{panel_x0_, 0, panel_x1_, panel_y1_};
    if (!notes.caption.empty()) {
      // Centred over the view, moved in (not cut) where it would pass the panel's edge.
      const ImVec2 size = ImGui::CalcTextSize(notes.caption.c_str());
      const float w = size.x + 0.8f * em, h = size.y + 0.3f * em;
      float cx = static_cast<float>(zoom.rect.x) + 0.5f * static_cast<float>(zoom.rect.w);
      cx = std::max(panel.x0 + 0.5f * w, std::min(cx, panel.x1 - 0.5f * w));
      const Box b = place_text("caption", w, h, panel, {cx - 0.5f * w, zoom.rect.y + 0.8f * em}, 0.5f, 0.0f);
      boxed_text(dl, 0.5f * (b.x0 + b.x1), b.y0, notes.caption.c_str(), IM_COL32(255, 255, 255, 255),
                 IM_COL32(200, 0, 160, 235), em);
    }
    if (notes.slowdown > 1.0 + 1e-9) {
      char badge[48];
      std::snprintf(badge, sizeof badge, "slow motion %.3gx", notes.slowdown);
      const ImVec2 size = ImGui::CalcTextSize(badge);
      const Box b = place_text("badge", size.x + 0.8f * em, size.y + 0.3f * em, panel,
                               {zoom.rect.x + 0.8f * em, zoom.rect.y + 0.8f * em}, 0.0f, 0.0f);
      dl->AddRectFilled(ImVec2(b.x0, b.y0), ImVec2(b.x1, b.y1), IM_COL32(20, 20, 20, 220), 0.3f * em);
      dl->AddText(ImVec2(b.x0 + 0.4f * em, b.y0 + 0.15f * em), IM_COL32(255, 220, 0, 255), badge);
    }
  }
}

ImDrawList* Overlay::text_draw_list() {
  if (!texts_dry_) return ImGui::GetForegroundDrawList();
  if (!scratch_) scratch_ = std::make_shared<ImDrawList>(ImGui::GetDrawListSharedData());
  scratch_->_ResetForNewFrame();
  scratch_->PushTextureID(ImGui::GetIO().Fonts->TexID);
  scratch_->PushClipRectFullScreen();
  return scratch_.get();
}

void Overlay::place_texts(const Annotations& notes, const std::vector<View>& views, float em, bool events) {
  texts_placed_.clear();
  text_wants_.clear();
  texts_dry_ = true;
  if (events) draw_events(notes, views, em);
  if (!notes.texts.empty()) draw_texts(notes, views, em);
  texts_dry_ = false;
  std::stable_sort(text_wants_.begin(), text_wants_.end(),
                   [](const TextWant& a, const TextWant& b) { return a.w > b.w; });
  for (const TextWant& t : text_wants_)
    texts_placed_[t.name] = place_text(t.name, t.w, t.h, t.within, t.want, t.ax, t.ay);
}

Box Overlay::place_text(const std::string& name, float w, float h, const Box& within,
                        std::array<float, 2> want, float ax, float ay) {
  const float em = static_cast<float>(font_px_), pad = 0.25f * em;
  const Box wanted{want[0], want[1], want[0] + w, want[1] + h};
  if (texts_dry_) {
    text_wants_.push_back({name, w, h, within, want, ax, ay});
    return wanted;
  }
  if (const auto it = texts_placed_.find(name); it != texts_placed_.end()) return it->second;
  std::optional<Box> b;
  if (wanted.inside(within) && space_->covered(wanted) == 0) b = wanted;
  const auto it = text_spots_.find(name);
  if (!b && it != text_spots_.end()) {  // where it stood, while that stays clear: no jumping between pictures
    const Box& o = it->second;
    const Box again{o.x0, o.y0, o.x0 + w, o.y0 + h};
    if (again.inside(within) && space_->covered(again) == 0) b = again;
  }
  if (!b) b = space_->place(w, h, within, want[0] + ax * w, want[1] + ay * h, ax, ay);
  const bool clear = b.has_value();
  if (!b) {
    // No spot off the subject: the nearest one off every box and text at least (nothing over anything).
    FreeSpace boxes(space_->region(), std::max(2.0f, 0.25f * em));
    for (const auto& r : {info_rect(), plot_rect(), scale_rect(), colorbar_rect()})
      if (r[2] > r[0]) boxes.block({r[0], r[1], r[2], r[3]}, pad);
    for (const auto& t : texts_) boxes.block({t.rect[0], t.rect[1], t.rect[2], t.rect[3]}, pad);
    b = boxes.place(w, h, within, want[0] + ax * w, want[1] + ay * h, ax, ay);
  }
  const Box placed = b ? *b : wanted;
  text_spots_[name] = placed;
  space_->block(placed, pad);
  texts_.push_back({name, {placed.x0, placed.y0, placed.x1, placed.y1}, clear});
  return placed;
}

void Overlay::draw_texts(const Annotations& notes, const std::vector<View>& views, float em) {
  // Each note once, in the most magnified view that shows its point: a dark box up and to the right of the
  // point (left or down where the view ends), elsewhere in the panel where that spot is taken by a box, a
  // caption, another note or the grains, with an arrow from the box to the point. (Copied into every view, a
  // note was cut at the whole-container thumbnail's edge.)
  ImDrawList* dl = text_draw_list();
  const ImU32 ink = IM_COL32(255, 255, 255, 255), box = IM_COL32(25, 25, 25, 225),
              arrow = IM_COL32(255, 200, 0, 255);
  Box panel{panel_x0_, 0, panel_x1_, panel_y1_};
  dl->PushClipRect(ImVec2(panel.x0, panel.y0), ImVec2(panel.x1, panel.y1));
  for (size_t ti = 0; ti < notes.texts.size(); ++ti) {
    const auto& t = notes.texts[ti];
    const View* shown = nullptr;
    float px = 0, py = 0;
    for (const auto& v : views) {
      const core::Vec2 c = v.world_to_pixel({t.x, t.y});
      const bool in =
          c.x >= v.rect.x && c.x <= v.rect.x + v.rect.w && c.y >= v.rect.y && c.y <= v.rect.y + v.rect.h;
      if (in && (!shown || v.px_per_m() > shown->px_per_m()))
        shown = &v, px = static_cast<float>(c.x), py = static_cast<float>(c.y);
    }
    if (!shown) continue;
    const float x0 = static_cast<float>(shown->rect.x), y0 = static_cast<float>(shown->rect.y);
    const float x1 = x0 + static_cast<float>(shown->rect.w);
    const ImVec2 size = ImGui::CalcTextSize(t.text.c_str());
    const float w = size.x + 0.8f * em, h = size.y + 0.4f * em, gap = 2.5f * em;
    const float dx = px + gap + w <= x1 ? gap : -gap - w;  // right of the point, or left
    const float dy = py - gap - h >= y0 ? -gap - h : gap;  // above it, or below
    const Box b = place_text("note " + std::to_string(ti), w, h, panel, {px + dx, py + dy}, 0.0f, 0.0f);
    const float bx = b.x0, by = b.y0;
    // The arrow from the box's corner nearest the point to the point, with its head at the point.
    const ImVec2 from(std::fabs(bx - px) < std::fabs(bx + w - px) ? bx : bx + w,
                      std::fabs(by - py) < std::fabs(by + h - py) ? by : by + h),
        to(px, py);
    const float len = std::max(1e-3f, std::hypot(to.x - from.x, to.y - from.y)), ux = (to.x - from.x) / len,
                uy = (to.y - from.y) / len, head = 0.6f * em, width = std::max(2.0f, 0.12f * em);
    const ImVec2 base(to.x - ux * head, to.y - uy * head);
    dl->AddLine(from, base, arrow, width);
    dl->AddTriangleFilled(to, ImVec2(base.x - uy * 0.45f * head, base.y + ux * 0.45f * head),
                          ImVec2(base.x + uy * 0.45f * head, base.y - ux * 0.45f * head), arrow);
    dl->AddRectFilled(ImVec2(bx, by), ImVec2(bx + w, by + h), box, 0.25f * em);
    dl->AddText(ImVec2(bx + 0.4f * em, by + 0.2f * em), ink, t.text.c_str());
  }
  dl->PopClipRect();
}

}  // namespace render
