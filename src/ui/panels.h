// The inspector's Dear ImGui panels, separate from the window so they can be driven by synthetic input in
// tests. Every control runs an Inspector command (see inspector.h).
#pragma once

#include <functional>

#include <array>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "ui/inspector.h"

namespace ui {

struct PanelState {
  bool playing = false;
  long play_until = -1;    // playback stops at this frame (play to the next clog), or -1
  float speed = 1.0f;      // video frames per display frame, scaled by the trajectory's frame rate
  std::string message;     // the last result or error, shown in the panel
  char grain_id[16] = "";  // the "grain id" field (the script line `select ID`)
  char go_to[32] = "";     // the "go to" field: a frame, a time ("12.5 s") or a step ("+30", "-5")
  char snapshot_path[256] = "snapshot-{frame}.png";
  int snapshot_size = 0;  // index into the size presets
  int export_from = 0, export_to = 0;
  char export_path[256] = "clip-{frame}.mp4";
  char session_path[256] = "session-{frame}.txt";
  char branch_path[256] = "branch-{frame}";  // "what if": where the branch is saved as a run
  float kick_dv = 0.2f;                      // m/s, the branch's "kick now"
  std::string trajectory_name;               // named in a saved session's first line
  float font_scale = 1.0f;       // the window's text size (io.FontGlobalScale); pictures keep their own
  bool show_keys = false;        // the key overlay ('?')
  bool swallow_release = false;  // the press that closed the key overlay: its release selects nothing
  double last_redraw_ms = 0;
  // Screen rectangles (x0, y0, x1, y1) of named widgets from the last frame, for tests and tooltips.
  std::map<std::string, std::array<float, 4>> rects;
};

// Draw the control panel at (x, 0) of width w, and the timeline at (0, y) of size timeline_w x timeline_h.
// Must be called between ImGui::NewFrame() and ImGui::Render().
void draw_panels(Inspector& insp, PanelState& ps, Painter* painter, float x, float w, float h,
                 float timeline_y, float timeline_w, float timeline_h);

// The last widget's screen rectangle under `name` (ps.rects: tests click by name).
void remember(PanelState& ps, const char* name);

// The "what if" tab (ui/branch_panel.cpp): the script's branch lines as buttons.
void draw_branch(Inspector& insp, PanelState& ps);

// Run a command and put its outcome (or error) in ps.message instead of throwing.
// Run a typed inspector action from a button or key; the panel's message says what it did (the script line
// that repeats it, or the file it wrote) or why it could not.
void act(Inspector& insp, PanelState& ps, const std::function<void()>& action, bool writes = false);

// The final arch of the clog at this frame, or of the next clog (Inspector::goto_clog_arch).
void final_arch(Inspector& insp);
// Play until the next clog starts (then `goto clog K` is what the window did); a message when there is none.
void play_to_next_clog(Inspector& insp, PanelState& ps);
// Every key of the inspector window and what it does, as the '?' overlay lists them.
const std::vector<std::pair<const char*, const char*>>& inspector_keys();
// The '?' overlay: every key, centred over the window (w x h); closes on '?', Escape or a click.
void draw_keys_overlay(PanelState& ps, float w, float h);

// Snapshot this frame as the outputs tab names and sizes it.
void snapshot_from_panel(Inspector& insp, PanelState& ps, Painter* painter);
// The "go to" field's text: "N" goes to frame N, "T s" to the frame nearest T seconds, "+N" / "-N" steps N
// frames (the script lines goto frame, goto time, step). Throws core::InputError naming what is allowed.
void go_to(Inspector& insp, const std::string& text);
// Playback's step: advance by `frames`, stopping at the end or where play_to_next_clog asked.
void advance_playback(Inspector& insp, PanelState& ps, long frames);

}  // namespace ui
