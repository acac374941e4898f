// The live window's panel (Dear ImGui), apart from the window so that tests can drive it with synthetic
// input: run control, the scene's keys (applied on restart), the view, the colouring and the open clog's
// arch.
#pragma once

#include <array>
#include <map>
#include <optional>
#include <string>

#include "core/frame.h"
#include "core/scene.h"
#include "render/camera.h"
#include "render/overlay.h"
#include "render/painter.h"
#include "ui/window.h"

namespace ui {

struct LiveState {
  float speed = 1.0f;
  float font_scale = 1.0f;  // the panel's text (the window sets it from its height; the panel widens with it)
  double zoom = 1.0;
  core::Vec2 pan{0, 0};  // m, the view's offset from the camera's centre
  bool paused = false, snapshot = false;
  double step_pending = 0;  // s to advance while paused (single steps)
  std::string message = "running";
  render::Style style;
  render::OverlayOptions overlay;
  render::CameraSpec camera;              // split
  core::Scene edit;                       // the panel's values, applied on restart
  std::optional<core::Scene> file_scene;  // the scene the window opened with ("scene file" returns to it)
  double achieved = 0;                    // simulated seconds per wall-clock second, smoothed (0: not known)
  std::string
      restart_edits;  // the keys the last restart changed ("mu 0 -> 0.001, ..."): what a failure blames
  // Screen rectangles of named widgets from the last frame (tests).
  std::map<std::string, std::array<float, 4>> rects;
};
constexpr double kLiveStep = 1.0 / 30.0;  // s: one step while paused

// The views of the live picture, w x h pixels: the camera, zoomed (all but the whole-container view) and
// panned.
std::vector<render::View> live_views(const LiveState& st, const core::Geometry& geo, int w, int h);

// The panel's contents, into the current ImGui window. `painter` (may be null) says whether the picture left
// its information box out (then shown here).
void draw_live_panel(LiveSource& source, LiveState& st, const core::Frame& f, const render::OverlayData& od,
                     const render::Painter* painter);

// The panel as the live window shows it: a fixed ImGui window at (x, 0) of w x h holding draw_live_panel.
void draw_live_window(LiveSource& source, LiveState& st, const core::Frame& f, const render::OverlayData& od,
                      const render::Painter* painter, float x, float w, float h);

// The drag step of a scene key per pixel at `value`: 0.5% of the value, or from 0 of the key's default (a
// millionth of the field's range when the default is 0 too).
double drag_step(const std::string& key, double value);

// A scene key's control: dragged in steps of drag_step, clamped
// to the range of its field in the scene's field table, its unit in the label; edits `s`. Returns whether it
// changed.
bool key_drag(core::Scene& s, const std::string& key);

// The scene keys whose values differ from `before` to `after`, as "KEY OLD -> NEW, ..." ("" when none).
std::string edits_between(const core::Scene& before, const core::Scene& after);

// The message for a simulation that failed (`what`), blaming the last restart's edits when there were any.
std::string blame_edits(const LiveState& st, const std::string& what);

// The arch of a frame (members, species, geometry, descriptors), into the current ImGui window.
void draw_arch_summary(const core::Frame& f, const render::OverlayData& od);

}  // namespace ui
