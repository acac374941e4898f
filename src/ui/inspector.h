// The inspector's state and its command language. The scripted mode runs commands from a file; the window's
// buttons and keys run the same commands, so a figure made by clicking can be written down and made again.
//
//   goto frame N | goto time T | goto clog K | goto arch K | goto start | goto end
//   step N                       one or more frames forward (N > 0) or back (N < 0)
//   next clog | prev clog        the last frame of the next / previous clog (the arch fully formed)
//   zoom hopper|outlet|split|window:X0,Y0,X1,Y1     the camera;  zoom by F   magnify about the view centre
//   pan DX DY                    move the view, metres
//   color species|speed|force    palette paper|colorblind    overlay all|none|time,counts,...    arch on|off
//   snapshot FILE.png [WxH]      re-render the current view off-screen at any resolution (default 1920x1080)
//   export FILE.mp4 FROM TO [WxH] [FPS]    frames FROM..TO as a movie
//   export clog FILE.mp4 [WxH] [FPS]       the clog at or after this frame, 1 s before to 0.5 s after
//   (FILE may hold {frame} and {t}, e.g. snapshot arch-{frame}.png; an existing file is never written over)
//   print                        frame, time, clog timer and arch members on standard output
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/geometry.h"
#include "core/image.h"
#include "render/camera.h"
#include "render/overlay.h"
#include "render/painter.h"
#include "render/palette.h"
#include "ui/sources.h"

namespace ui {

// A stretch of frames during which nothing left for at least clog_min_gap.
struct ClogSpan {
  long first, last;  // frames
  double duration;   // s, the clog timer at its last frame
  bool removed;      // ended by the clog_timeout rule (a long-lasting arch)
};

using render::Painter;  // Frame -> Image, shared with record (render/painter.h)

class Inspector {
 public:
  // `files` (may be null: snapshot and export then refuse) is where snapshots and clips go.
  Inspector(const FrameSource& frames, const core::Scene& scene, const ImageFiles* files = nullptr);

  // Run one command; throws core::InputError naming the problem (unknown command, frame out of range...).
  // `painter` is needed by snapshot and export only.
  void execute(const std::string& line, Painter* painter = nullptr);

  long frame_index() const { return frame_; }
  void set_frame(long k);  // clamps to the trajectory
  core::Frame current() const { return traj_.frame(frame_); }
  const std::vector<ClogSpan>& clogs() const { return clogs_; }
  const FrameSource& trajectory() const { return traj_; }
  const ImageFiles* files() const { return files_; }
  const core::Geometry& geometry() const { return geo_; }
  const core::Scene& scene() const { return scene_; }

  // The views for an image of w x h: the camera preset, then zoom and pan.
  std::vector<render::View> views(int w, int h) const;
  core::Image render_current(Painter& p, int w, int h) const;

  render::CameraSpec camera;  // split
  double zoom = 1.0;          // magnification on top of the preset
  core::Vec2 pan{0, 0};       // m
  render::Style style;
  render::OverlayOptions overlay;
  render::OverlayData overlay_data;
  std::string last_output;  // what `print` printed last, or the file that snapshot/export wrote

 private:
  // FILE with {frame} and {t} filled in; throws core::InputError if it exists.
  std::string output_name(const std::string& pattern, const std::string& line) const;
  const FrameSource& traj_;
  const ImageFiles* files_;
  core::Scene scene_;
  core::Geometry geo_;
  long frame_ = 0;
  std::vector<ClogSpan> clogs_;
};

// Run a script file; errors carry the file name and line number. Returns the number of commands run.
int run_script(Inspector& insp, Painter& painter, const std::string& path);

}  // namespace ui
