// The inspector's state and its command language. The scripted mode runs commands from a file; the window's
// buttons and keys run the same commands, so a figure made by clicking can be written down and made again.
//
//   goto frame N | goto time T | goto clog K | goto arch K | goto start | goto end
//   step N                       one or more frames forward (N > 0) or back (N < 0)
//   next clog | prev clog        the last frame of the next / previous clog (the arch fully formed)
//   zoom hopper|outlet|split|window:X0,Y0,X1,Y1     the camera;  zoom by F   magnify about the view centre
//   zoom to F                    the magnification on top of the camera (1: as the camera frames it)
//   pan DX DY | pan to X Y       move the view by / to an offset from the camera's centre, metres
//   color species|speed|force    palette paper|colorblind    overlay all|none|time,counts,...    arch on|off
//   background white|dark        font-scale F (0.5-4)        species-color NAME=#rrggbb[,...]|scene
//   snapshot FILE.png [WxH]      re-render the current view off-screen at any resolution (default 1920x1080)
//   export FILE.mp4 FROM TO [WxH] [FPS]    frames FROM..TO as a movie
//   export clog FILE.mp4 [WxH] [FPS]       the clog at or after this frame, 1 s before to 0.5 s after
//   (FILE may hold {frame} and {t}, e.g. snapshot arch-{frame}.png; an existing file is never written over)
//   select ID|off                ask about a grain (ringed; its details in the panel)
//   annotate T0:T1:X,Y:TEXT|off  a note with an arrow to X,Y (m) in pictures from T0 to T1 s (as record's
//                                --annotate)
//   print [grain|arch]           frame, time, clog timer and arch members (the selected grain's details; the
//                                arch member by member) on standard output
// "What if" (ui/inspector_branch.cpp): the run rebuilt at a frame, changed and continued beside the recording
//   branch at N | branch off     rebuild the run at frame N (checked against it); shown on the right
//   remove grain ID              take a grain out (re-injected on top); an open clog ends there
//   kick DV                      every grain lifted by DV m/s now
//   set kick_impulse_max J | set mu M | set species.NAME.dipole M
//                                the drive's kick (N s), a species' dipole moment (A m^2), from now on
//   continue S                   the branch S seconds on, the recording moved to the same time
//   save branch DIR              the branch as a run of its own (it ends there)
#pragma once

#include <array>
#include <limits>
#include <memory>
#include <optional>
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

// A clog of the run (a row of clogs.csv, as the trajectory's events give it) and the frames it covers: from
// the first frame at or after its start (its last exit) to the last frame before its end.
struct ClogSpan {
  long first, last;       // frames
  double duration;        // s, end - start
  bool removed;           // ended by the clog_timeout rule (a long-lasting arch)
  core::ClogEvent event;  // start, end, how it ended, whether it was arrested
};

using render::Painter;  // Frame -> Image, shared with record (render/painter.h)

// One member of the arch, as the inspector's arch table shows it (members left to right).
struct ArchMember {
  int id;
  std::string species;
  double x, y;                     // m
  double bead_deg;                 // the bead angle (core::bead_angles_deg); NaN at the two ends
  double force_left, force_right;  // N, normal force to the left / right neighbour; NaN when not known
  std::string walls;  // the walls or obstacle it touches ("left hopper wall", "floor", ...), or ""
  // N, from the contact forces (a recording's contacts of version 2; NaN without them): the load it takes
  // from grains that are not members, along gravity (> 0: pressed down), and the walls' force on it (its
  // magnitude).
  double load = std::numeric_limits<double>::quiet_NaN();
  double wall_force = std::numeric_limits<double>::quiet_NaN();
};

// The arch as a body (core::ArchBalance along gravity), N: the load the grains above put on it, what the
// walls hold up, its own weight, and what is left (the residual's magnitude: 0 at rest).
struct ArchLoads {
  double load = 0, held = 0, weight = 0, residual = 0;
};

class Inspector {
 public:
  // `files` (may be null: snapshot and export then refuse) is where snapshots and clips go.
  Inspector(const FrameSource& frames, const core::Model& model, const ImageFiles* files = nullptr);

  // Run one command line of the script language: parsed here, then the typed action below; throws
  // core::InputError naming the line and the problem (unknown command, frame out of range...). `painter` is
  // needed by snapshot and export only.
  void execute(const std::string& line, Painter* painter = nullptr);

  // The actions, typed: what the window's buttons and keys call and what each script command does. Each
  // throws core::InputError naming the problem, and appends the script line that repeats it to history().
  void goto_frame(long k);
  void goto_time(double t);
  // Clogs are numbered from 1 as the rows of clogs.csv. goto_clog lands on the frame where the clog starts
  // (its last exit); goto_clog_arch on the frame where its final arch first stands (the arch of its last
  // frame, the same grains in every frame from there on; the last frame when it ends with none).
  void goto_clog(long k);
  void goto_clog_arch(long k);
  void goto_arch(long k);  // the k-th long-lasting arch, numbered from 1
  void goto_start();
  void goto_end();
  void step_frames(long n);
  void next_clog(bool later);         // the start of the next (later) or previous clog
  void next_arch_change(bool later);  // the next (earlier) frame whose arch is other grains than this one's
  void set_camera(const render::CameraSpec& c);
  void zoom_by(double f);
  void zoom_to(double f);             // 0.1 to 100
  void pan_by(double dx, double dy);  // m
  void pan_to(double x, double y);    // m
  void set_color(render::ColorMode m, const std::string& name);
  void set_palette(render::Palette p, const std::string& name);
  void set_overlay(const std::string& spec);
  void show_arch(bool on);
  // A whole look at once (the command line's, or a recording's own: app/services/looks.h): the style (its
  // tracked grains kept), the overlay's elements, text size and placement, the notes and each species' colour
  // (alpha 0: the scene's or palette's). Written into the session as the lines that make it.
  void set_look(const render::Style& style, const render::OverlayOptions& overlay,
                const std::vector<render::TimedNote>& notes, const std::vector<render::Rgba>& species_colors);
  // Follow the grains whose centres are in the box (m) in this frame, or the members of the arch where
  // `goto clog K` / `goto arch K` lands (found without moving).
  void track_region(double x0, double y0, double x1, double y1);
  void track_arch_of(bool clog, long k);
  // Ask about a grain: select_grain(id) (-1: none) rings it in the window and pictures and lists its details;
  // the script line is `select ID|off`. grain_at: the grain whose outline holds the point (m), or -1.
  void select_grain(long id);
  long grain_at(core::Vec2 p) const;
  // The selected grain's details, one line each: id and species, position, speed, angle, summed force,
  // coordination and its contacts (with normal forces when the run kept its contacts, else by distance).
  std::vector<std::string> grain_details() const;
  // The arch of the current frame, member by member; and its force balance, when the frame has an arch and
  // its contacts carry their forces' geometry.
  std::vector<ArchMember> arch_table() const;
  std::optional<ArchLoads> arch_loads() const;
  std::string print_frame();
  // `print grain`: grain_details(); `print arch`: the arch table as CSV (id,species,x_m,y_m,bead_angle_deg,
  // force_left_N,force_right_N,load_N,wall_N,walls), a header line first, and, when the forces are known, a
  // line "# balance: load_N=... held_N=... weight_N=... residual_N=...".
  std::string print_grain();
  std::string print_arch();
  // Every clog of the run as the inspector holds it (the recording's own events: the rows of clogs.csv), one
  // line each: "clog K START END ENDED_BY arrested|not-arrested frames FIRST-LAST".
  std::string print_clogs();
  // The current frame's main view (the most magnified) for a w x h picture as a vector draw table
  // (render::draw_list_csv), the window's size in metres and a caption (time, clog timer, arch, colour
  // scale).
  std::string vector_table(int w, int h, double& width_m, double& height_m, std::string& caption) const;
  // What a vector snapshot draws beside its picture (ui/sources.h, write_vector): the information box's
  // lines, the legend (species, arch), the colour bar and the scale bar of the current frame, tab-separated.
  std::string vector_key() const;
  // Files are never written over; patterns may hold {frame} and {t}. Return the path written.
  std::string snapshot(const std::string& pattern, int w, int h, Painter* painter);
  std::string export_frames(const std::string& pattern, long from, long to, int w, int h, int fps,
                            Painter* painter);
  std::string export_clog(const std::string& pattern, int w, int h, int fps, Painter* painter);
  // Every action so far as script lines: what the window did, written down to be made again.
  const std::vector<std::string>& history() const { return history_; }
  // The state the pictures depend on, as the script lines that set it, in an order that replays: frame,
  // camera, zoom to, pan to, palette, color, colormap, arch, chains, overlay, track, select (the `zoom to`
  // and `pan to` values printed to round-trip exactly).
  std::vector<std::string> state_lines() const;
  // The window's recorder, called once per redraw after every control ran: each change of state that no
  // action wrote down (an arrow key, the frame slider, the timeline, wheel zoom, a drag, a checkbox) is
  // appended as the line that makes it; a run of frame, zoom or pan changes is one line. The first call
  // starts the session with the whole state (what the command-line flags set).
  void sync_history();
  // The session as a script (a comment naming the trajectory, then history()), to `pattern` ({frame} and {t}
  // as snapshot); never over an existing file. Returns the path.
  std::string save_session(const std::string& pattern, const std::string& trajectory_name);

  // "What if" (see the script lines above). `b` (may be null: branch refuses) rebuilds the run.
  void set_brancher(const Brancher* b) { brancher_ = b; }
  void branch_at(long k);
  void branch_off();
  void branch_remove(long id);
  void branch_kick(double dv);
  void branch_set(const std::string& key, double value);
  void branch_continue(double seconds);
  std::string save_branch(const std::string& dir);
  const Branch* branch() const { return branch_.get(); }
  // A picture of w x h while branched: the recording's views on the left half, the branch's on the right,
  // each panel's overlay data titled.
  void branch_panels(int w, int h, std::vector<render::View>& left, std::vector<render::View>& right,
                     render::OverlayData& od, render::OverlayData& ob) const;
  // Every view on the screen's picture of w x h (both panels while branched): where the mouse is.
  std::vector<render::View> screen_views(int w, int h) const;
  bool can_branch() const { return brancher_ != nullptr; }

  long frame_index() const { return frame_; }
  bool has_contacts() const { return traj_.has_contacts(); }
  bool has_contact_forces() const { return traj_.has_contact_forces(); }
  void set_frame(long k);  // clamps to the trajectory
  core::Frame current() const { return traj_.frame(frame_); }
  const std::vector<ClogSpan>& clogs() const { return clogs_; }
  // The clog (an index into clogs()) whose frames hold frame k, or -1.
  long clog_at(long k) const;
  // The frame where clog i's final arch first stands (see goto_clog_arch).
  long final_arch_frame(size_t i) const;
  // "clog 3 of 12, 4.211-9.211 s, ended by the rule, arches.csv row 2" for clog i.
  std::string clog_caption(size_t i) const;
  const FrameSource& trajectory() const { return traj_; }
  const ImageFiles* files() const { return files_; }
  const core::Geometry& geometry() const { return geo_; }
  const core::Scene& scene() const { return model_.scene; }

  // The views for an image of w x h: the camera preset, then zoom and pan.
  std::vector<render::View> views(int w, int h) const;
  core::Image render_current(Painter& p, int w, int h) const;
  // The frame displacement is measured from (the first at or after style.displacement_from); empty when the
  // colouring is not by displacement.
  core::Frame reference_frame() const;

  render::CameraSpec camera;             // split
  long selected = -1;                    // the grain asked about (select_grain), or -1
  std::vector<render::TimedNote> notes;  // script `annotate`: shown in pictures while their time lasts
  // A camera move (script `camera-path`): while set, pictures follow it by each frame's time (zoom and pan
  // do not apply).
  render::CameraPath path;
  // Clips hold the picture at each clog as it forms or before the clog rule fires (script `freeze`).
  render::Freeze freeze;
  double zoom = 1.0;     // magnification on top of the preset
  core::Vec2 pan{0, 0};  // m
  render::Style style;
  render::OverlayOptions overlay;
  render::OverlayData overlay_data;
  std::string last_output;  // what `print` printed last, or the file that snapshot/export wrote

 private:
  // FILE with {frame} and {t} filled in; throws core::InputError if it exists.
  std::string output_name(const std::string& pattern, const std::string& line) const;
  long in_range(long k) const;
  void log(const std::string& command);
  void export_command(const std::vector<std::string>& words, Painter* painter);
  // The script's `color` and `track` commands (execute() hands them over with the line's words).
  void color_command(const std::vector<std::string>& a, const std::string& line);
  void track_command(const std::vector<std::string>& a);
  void species_color_command(const std::vector<std::string>& a);
  bool branch_command(const std::vector<std::string>& a);
  core::Image render_branch(Painter& p, int w, int h) const;
  Branch& need_branch(const char* what) const;
  bool look_command(const std::vector<std::string>& a, const std::string& line);
  // The "from" each colouring last had (each keeps its own; its "to" is its own in Style already).
  using ColorMins = std::array<double, 7>;  // one per render::ColorMode
  ColorMins color_mins_{};
  // Switches `st` to colouring m, its "from" restored from `mins` and the one it leaves kept there.
  static void switch_color(render::Style& st, render::ColorMode m, ColorMins& mins);
  // Throws core::InputError naming `what` when the frames' contacts carry no forces' geometry (stress,
  // arrows).
  void require_contact_forces(const char* what) const;
  std::vector<std::string> history_;
  std::vector<std::string> recorded_;  // state_lines() as history_ last left it (sync_history)
  bool synced_tail_ = false;           // history_'s last line came from sync_history (it may be merged)
  bool session_started_ = false;
  const FrameSource& traj_;
  const ImageFiles* files_;
  core::Model model_;
  core::Geometry geo_;
  long frame_ = 0;
  std::vector<ClogSpan> clogs_;
  const Brancher* brancher_ = nullptr;
  std::unique_ptr<Branch> branch_;
};

// Run a script file; errors carry the file name and line number. Returns the number of commands run.
int run_script(Inspector& insp, Painter& painter, const std::string& path);

}  // namespace ui
