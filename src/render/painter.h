// Frame -> pixels, written once for every caller (record, the inspector and its window, the live window, the
// gallery): the renderer draws the disks of each panel, one overlay per panel draws its HUD (an overlay
// remembers what it drew before: the plot's history, the marks of removed arches), and an off-screen target
// gives the Image.
#pragma once

#include <memory>
#include <vector>

#include "core/frame.h"
#include "core/geometry.h"
#include "core/image.h"
#include "render/camera.h"
#include "render/grain_values.h"
#include "render/overlay.h"
#include "render/palette.h"
#include "render/trails.h"

namespace render {

class Renderer;
class Target;

// One panel of a picture: a frame, its container and where it is shown. Pointers, owned by the caller.
struct PanelInput {
  const core::Frame* frame;
  const core::Geometry* geometry;
  const std::vector<View>* views;
  const OverlayData* data;
  const Annotations* notes = nullptr;  // what to point out (a rule removal, a caption), if anything
  const core::Frame* reference =
      nullptr;  // displacement colouring: the frame at the reference time, if known
};

struct PaintTiming {
  double draw_s = 0, readback_s = 0;  // accumulated over every paint()
};

class Painter {
 public:
  Painter();  // needs a current GL 3.3 context
  ~Painter();
  Painter(const Painter&) = delete;
  Painter& operator=(const Painter&) = delete;

  // Draw the panels into the framebuffer bound now, w x h pixels (the first panel clears it). The overlays
  // draw over the left overlay_w pixels (a window keeps its right-hand side for its own panels); < 0: all of
  // w.
  void draw(const std::vector<PanelInput>& panels, const Style& style, const OverlayOptions& overlay, int w,
            int h, int overlay_w = -1);
  // Draw into an off-screen target of w x h (kept while the size stays) and read it back; img.t is the first
  // panel's time.
  core::Image paint(const std::vector<PanelInput>& panels, const Style& style, const OverlayOptions& overlay,
                    int w, int h);
  // The same into `out`, reusing its pixel buffer (a movie's frames: no fresh 8 MB, zero-filled, per frame).
  void paint(core::Image& out, const std::vector<PanelInput>& panels, const Style& style,
             const OverlayOptions& overlay, int w, int h);
  // One panel.
  core::Image paint(const core::Frame& f, const core::Geometry& geo, const std::vector<View>& views,
                    const Style& style, const OverlayOptions& overlay, const OverlayData& data, int w, int h,
                    const core::Frame* reference = nullptr) {
    return paint({{&f, &geo, &views, &data, nullptr, reference}}, style, overlay, w, h);
  }
  // The next picture depends on its own inputs alone: the overlays forget their layout and history, the
  // tracked grains their trails (Overlay::reset). Snapshots and clips of the inspector start so.
  void start_afresh();
  const PaintTiming& timing() const { return timing_; }
  // Every panel's boxes found clear space in the last picture (Overlay::boxes_clear).
  bool boxes_clear() const {
    for (const auto& o : overlays_)
      if (!o->boxes_clear()) return false;
    return true;
  }
  // Panel k's overlay as last drawn (where its boxes went), or null if it drew none.
  const Overlay* overlay(size_t k) const { return k < overlays_.size() ? overlays_[k].get() : nullptr; }
  // The last draw left the first panel's information box out of the picture (OverlayOptions::may_leave).
  bool info_left() const { return info_left_; }

 private:
  std::unique_ptr<Renderer> renderer_;
  std::vector<std::unique_ptr<Overlay>> overlays_;  // one per panel, made when first needed
  std::vector<Trails> trails_;                      // one per panel: the tracked grains' recent positions
  std::vector<GrainValues> values_;                 // one per panel: displacement reference, coordination
  std::unique_ptr<Target> target_;
  PaintTiming timing_;
  bool info_left_ = false;
  int laid_out_w_ = 0, laid_out_h_ = 0;  // the image size the overlays' boxes were last laid out at
};

}  // namespace render
