#include "render/painter.h"

#include <algorithm>
#include <chrono>

#include "render/draw_list.h"
#include "render/grain_values.h"
#include "render/renderer.h"
#include "render/target.h"

namespace render {

namespace {
double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}
}  // namespace

Painter::Painter() : renderer_(std::make_unique<Renderer>()) {}
Painter::~Painter() = default;

void Painter::draw(const std::vector<PanelInput>& panels, const Style& style, const OverlayOptions& overlay,
                   int w, int h, int overlay_w) {
  info_left_ = false;
  for (size_t k = 0; k < panels.size(); ++k) {
    const PanelInput& p = panels[k];
    Style panel_style = style;
    panel_style.clear = style.clear && k == 0;
    if (p.data) panel_style.species_colors = p.data->species_colors;
    const bool valued = per_grain_values(panel_style.color);
    if (panel_style.tracked.empty() && !valued) {
      renderer_->draw(*p.frame, *p.geometry, *p.views, panel_style, w, h);
    } else {
      const std::vector<float>* values = nullptr;
      if (valued) {
        while (values_.size() <= k) values_.emplace_back();
        values = &values_[k].update(*p.frame, panel_style, p.reference);
        values_[k].settle_scale(panel_style);  // the colour bar shows the same scale
      }
      DrawList list =
          build_draw_list(*p.frame, *p.geometry, panel_style, {}, values, color_scale_max(panel_style));
      if (!panel_style.tracked.empty()) {
        while (trails_.size() <= k) trails_.emplace_back();
        trails_[k].update(*p.frame, panel_style.tracked, panel_style.trail_s);
        trails_[k].append(list, *p.frame, tracked_color(panel_style));
      }
      renderer_->paint(list, *p.views, panel_style, w, h);
    }
    // No overlay object (and no ImGui context) for clean frames: nothing to show and no note of the user's.
    if (!overlay.any() && !(p.notes && !p.notes->texts.empty())) continue;
    while (overlays_.size() <= k) overlays_.push_back(std::make_unique<Overlay>());
    overlays_[k]->draw(*p.frame, *p.data, overlay, *p.views, panel_style, overlay_w < 0 ? w : overlay_w, h,
                       p.geometry, p.notes);
    if (k == 0) info_left_ = overlays_[k]->info_left();
  }
}

core::Image Painter::paint(const std::vector<PanelInput>& panels, const Style& style,
                           const OverlayOptions& overlay, int w, int h) {
  core::Image img;
  paint(img, panels, style, overlay, w, h);
  return img;
}

void Painter::start_afresh() {
  for (auto& o : overlays_) o->reset();
  for (auto& t : trails_) t = Trails{};
  laid_out_w_ = laid_out_h_ = 0;
}

void Painter::paint(core::Image& img, const std::vector<PanelInput>& panels, const Style& style,
                    const OverlayOptions& overlay, int w, int h) {
  if (!target_ || target_->width() != w || target_->height() != h) target_ = std::make_unique<Target>(w, h);
  const auto t0 = std::chrono::steady_clock::now();
  target_->bind();
  const bool window_info_left = info_left_;  // info_left() is about the window's picture, not this image
  // An information box placed by free space needs its size, known once drawn at this image size: the first
  // picture of a size is laid out once before it is drawn (a snapshot, a movie's first frame).
  if (overlay.place_clear && overlay.any() && (w != laid_out_w_ || h != laid_out_h_))
    draw(panels, style, overlay, w, h);
  laid_out_w_ = w, laid_out_h_ = h;
  draw(panels, style, overlay, w, h);
  info_left_ = window_info_left;
  const auto t1 = std::chrono::steady_clock::now();
  timing_.draw_s += std::chrono::duration<double>(t1 - t0).count();
  target_->read(img, style.transparent);
  timing_.readback_s += seconds_since(t1);
  img.t = panels.empty() ? 0 : panels.front().frame->t;
}

}  // namespace render
