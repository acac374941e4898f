// The inspector and the live simulation in a window (GLFW + Dear ImGui), drawn by the same painter as the
// movies. Without a display these throw core::InputError pointing to the scripted mode.
#pragma once

#include <string>

#include "core/frame.h"
#include "core/geometry.h"
#include "core/scene.h"
#include "render/overlay.h"
#include "ui/inspector.h"

namespace ui {

struct WindowOptions {
  int width = 1280, height = 720;
  std::string screenshot;  // save the window's own pixels to this PNG after `frames` frames, then close
  int frames = 0;          // > 0: close after this many frames (tests, screenshots)
  const ImageFiles* files = nullptr;  // where screenshots and snapshots go (none: they are refused)
  std::string source_name;            // the run or trajectory shown (a saved session names it)
  // The live window's look (the inspector's is set on the Inspector): style and overlay elements.
  render::Style style;
  render::OverlayOptions overlay;
};

// Returns the median redraw time (ms) of frames where the shown frame changed, 0 if none.
double run_inspector_window(Inspector& insp, const WindowOptions& o);

// What the live window needs of a running simulation. The app owns the simulation and implements this; the
// window sees frames, the container and the scene's values, never the simulation itself. The panel edits the
// scene keys `live_keys()` names (scene keys or species.NAME.KEY), each as its field in the scene's field
// table says (range, unit, meaning); they apply on restart.
class LiveSource {
 public:
  virtual ~LiveSource() = default;
  virtual void advance(double seconds) = 0;  // simulated seconds; throws with the health monitor's message
  virtual core::Frame frame(bool forces) const = 0;
  virtual const core::Geometry& geometry() const = 0;
  virtual render::OverlayData overlay_data() const = 0;
  virtual const core::Scene& scene() const = 0;
  virtual std::vector<std::string> live_keys() const = 0;
  virtual void restart(const core::Scene& s) = 0;  // validates; throws core::InputError naming the value
};

// Space pauses and resumes, the right arrow steps one frame (1/30 s) while paused, S saves a snapshot
// live-tSSS.SSSs.png (1920x1080, re-rendered; never over an existing file), Q or Escape closes.
void run_live_window(LiveSource& source, const WindowOptions& o);

}  // namespace ui
