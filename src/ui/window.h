// The inspector and the live simulation in a window (GLFW + Dear ImGui), drawn by the same renderer as the
// movies. Without a display these throw core::InputError pointing to the scripted mode.
#pragma once

#include <string>

#include "core/scene.h"
#include "ui/inspector.h"

namespace ui {

struct WindowOptions {
  int width = 1280, height = 720;
  std::string screenshot;  // save the window's own pixels to this PNG after `frames` frames, then close
  int frames = 0;          // > 0: close after this many frames (tests, screenshots)
};

// Returns the median redraw time (ms) of frames where the shown frame changed, 0 if none.
double run_inspector_window(Inspector& insp, const WindowOptions& o);
double run_live_window(const core::Scene& scene, const WindowOptions& o);

}  // namespace ui
