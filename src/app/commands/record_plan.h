// What `record` is asked for and what it plans from it, checked before any work: the options, the panels (one
// scene, or a comparison of 2 to 4 on one clock, or a run played back beside the simulation) and the plan
// (the video, the frame clock, the style, the overlay, the camera's path, the freezes). cmd_record.cpp runs
// it.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "app/services/cli.h"
#include "app/services/looks.h"
#include "app/services/recording.h"
#include "app/services/replay.h"
#include "app/services/session.h"
#include "core/geometry.h"
#include "core/model.h"
#include "record/mp4.h"
#include "render/camera.h"
#include "render/overlay.h"

namespace app {

struct RecordOptions {
  SceneOptions scene;
  std::string out, size = "1920x1080", camera = "split";
  int fps = 30, crf = 20, png_every = 0;
  double speed = 1.0, slowmo = 1.0;
  std::string camera_path;                          // key frames T:CAMERA,... (render/camera.h)
  std::string freeze;                               // EVENT:SECONDS, EVENT clog or rule
  std::vector<std::string> compare, compare_scene;  // comparison panels: key=value[,...] sets, or scene files
  std::string compare_run;                // a recorded or imported run played back beside the simulation
  std::vector<std::string> panel_titles;  // --panel-title: each panel's title, in order (default: its label)
  std::string preset = "veryfast";
  LookOptions looks;   // how every picture looks (app/services/looks.h)
  TrackOptions track;  // grains followed
  bool no_movie = false, force = false, quiet = false;
};

// One scene of a recording: a single movie has one panel; `--compare` movies have 2 to 4 side by side.
struct Panel {
  core::Model model;  // the panel's scene, compiled once
  std::string label;  // what differs, e.g. "mu=2.2" (empty for a single movie)
  core::Geometry geo;
  std::vector<render::View> views;
  render::OverlayData odata;
  EventMarks marks;
  std::string subdir;              // inside NAME/: "" for one panel, "panelK/" for a comparison
  std::shared_ptr<Replay> replay;  // --compare-run: this panel plays a run back (always the last panel)
};

// The panels: the base scene alone, or one per --compare / --compare-scene (with a single one, the base scene
// is the first panel so that the comparison has two sides).
std::vector<Panel> make_panels(const RecordOptions& o);

// Everything the user typed, checked before any work starts: the video, the clock, the style, the overlay and
// each panel's views.
struct Plan {
  record::VideoSettings video;
  FrameClock clock;
  // The look resolved for the first panel's scene (each panel has its species' colours): its style, overlay
  // options and notes.
  Look look;
  render::Style style;
  render::OverlayOptions overlay;
  render::CameraPath path;               // a camera move (empty: the camera stands)
  render::Freeze freeze;                 // --freeze EVENT:SECONDS (off: none)
  std::vector<render::TimedNote> notes;  // --annotate
  // The overlay's boxes find clear space beside the container (with the margin the plan added, if any);
  // false: the picture is too small for the text size (the plan said so on standard error).
  bool overlay_fits = true;
};

Plan plan_recording(const RecordOptions& o, std::vector<Panel>& panels);

// The k-th of `n` panels' area in a picture w x h: its share of the width less the overlay's column on its
// right, its height less its heading above and the overlay's band below (pixels, top-left origin).
render::Rect panel_area(const Panel& p, size_t k, size_t n, int w, int h);
// The camera path's view at time t laid out in that area.
render::View path_view(const Plan& plan, const Panel& p, size_t k, size_t n, int w, int h, double t);

}  // namespace app
