// The information drawn over a frame with Dear ImGui: simulated time, exits of each species, running Q~, the
// clog timer, the current arch, a legend (or a colour bar) and a scale bar in particle diameters. Every
// element can be switched off; a clean frame has none.
#pragma once

#include <array>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/frame.h"
#include "core/geometry.h"
#include "core/model.h"
#include "core/scene.h"
#include "render/camera.h"
#include "render/free_space.h"
#include "render/palette.h"

struct ImDrawList;  // ImGui's (the overlay draws with it; this header does not include ImGui)

namespace render {

struct OverlayOptions {
  bool time = true, counts = true, rate = true, timer = true, arch = true, legend = true, scale = true;
  bool events = true;     // rule removals marked and captioned, vibration breaks captioned, slow-motion badge
  bool zoombox = true;    // the outlet panel's region outlined on the whole-hopper panel (split camera)
  bool plot = false;      // cumulative exits of each species against time, clogs shaded (not in "all")
  bool colorbar = false;  // only the colour bar (speed/force colouring), e.g. with nothing else
  bool ids = false;       // each arch member's id beside it (not in "all": the inspector's and talks' choice)
  // Not an element: put the information box in the corner where it covers the fewest disks (the windows,
  // whose views are zoomed and panned at will); off, it stays top-right (movies: the outlet view leaves room
  // there).
  bool place_clear = false;
  // With place_clear: when every corner would cover the container (the hopper, its walls or the column the
  // exiting disks fall through), leave the box out of the picture; Overlay::info_left() then tells the
  // caller, who shows info_contents() beside the picture (the windows' side panels). Off: the least-covering
  // corner.
  bool may_leave = false;
  double font_scale = 1.0;  // text size over the default (1/42 of the image height): 1.5-2 for projectors
  // Where the information box goes: -1 as above (place_clear's choice, or top-right); else the user's corner,
  // 0 top-right, 1 top-left, 2 bottom-right, 3 bottom-left (record --overlay-at).
  int info_at = -1;
  // The other boxes' corners, the same way (-1: the clear spot nearest their own corner): the discharge plot
  // and the colour bar in the panel, the scale bar in the view whose scale it shows.
  int plot_at = -1, colorbar_at = -1, scale_at = -1;
  static OverlayOptions none() {
    OverlayOptions o;
    o.time = o.counts = o.rate = o.timer = o.arch = o.legend = o.scale = o.events = o.zoombox = false;
    return o;
  }
  bool any() const {
    return time || counts || rate || timer || arch || legend || scale || events || zoombox || plot ||
           colorbar || ids;
  }
};
// "auto", "top-right", "top-left", "bottom-right" or "bottom-left" into OverlayOptions::info_at. Throws
// core::InputError naming `option`.
int parse_corner(const std::string& text, const std::string& option);
// Where the user puts the boxes (record --overlay-at): a corner for the information box as above, or a comma
// list of ELEMENT=CORNER with ELEMENT info, plot, colorbar or scale (e.g. "info=top-left,plot=bottom-left").
// Throws core::InputError naming `option`, the item and what is allowed.
void parse_placement(const std::string& text, const std::string& option, OverlayOptions& o);
// Parse "all", "none" or a comma list of
// time,counts,rate,timer,arch,legend,scale,events,zoombox,plot,colorbar,ids
// ("all+plot" is all of the default elements and the plot). Throws core::InputError.
OverlayOptions parse_overlay(const std::string& spec);

// What a frame should point out beyond the state itself, made by whoever knows the run's events (record's
// EventMarks) and drawn by the overlay; never part of the physics frame: grains a rule removal took away,
// ringed where they stood, a caption, and a slow-motion badge.
struct Annotations {
  struct Ring {
    float x, y, radius;  // m
  };
  std::vector<Ring> removed;  // the members the clog rule removed, where they were
  std::string caption;        // e.g. "arch removed (5 s rule)"
  double slowdown = 1;        // > 1: the video runs this many times slower than real time
  int selected = -1;          // a grain asked about in the inspector: ringed and labelled with its id
  // A user's notes (record --annotate): a text in a box with an arrow to a point (m, container frame).
  struct Text {
    float x, y;
    std::string text;
  };
  std::vector<Text> texts;
};

// A note shown from t0 to t1 (s of simulated time) at a point: "T0:T1:X,Y:TEXT" (record --annotate).
struct TimedNote {
  double t0 = 0, t1 = 0, x = 0, y = 0;
  std::string text;
};
// Throws core::InputError naming `option`, the note and what is allowed.
TimedNote parse_note(const std::string& spec, const std::string& option);

struct OverlayData {
  double clog_timeout = 5;       // s
  double clog_min_gap = 0.5;     // s
  double diameter = 0.13;        // m, of an original disk (the scale bar's unit)
  std::string title;             // e.g. "r = 0.4, chi = 0.4, mu = 0 A m^2"
  int panel_x = 0, panel_w = 0;  // the panel this overlay belongs to, pixels (panel_w = 0: the whole image)
  // Pixels at the right of the panel kept free for the overlay's boxes, beside the container (record adds
  // this margin when the container leaves no clear space, render/free_space.h); 0: none.
  int margin_w = 0;
  // ... and a band at the bottom of the panel, below its views (a comparison's narrow panels: a column would
  // halve the outlet view's zoom); 0: none.
  int margin_h = 0;
  // The information box's height the plan reserved in that band (its estimate with every row), pixels: the
  // box stands at the top of that much room, at the same place in every panel of a comparison. 0: its own
  // size.
  int info_h = 0;
  // A comparison panel's heading: its title in large type, centred in a band heading_h pixels tall at the top
  // of the panel, above its views (wrapped between words; smaller type where it would not fit). Empty: none.
  std::string heading;
  int heading_h = 0;
  // The scene's species, by index: names for the legend, and their own colours (alpha 0: the palette's).
  std::vector<std::string> species_names = {"original", "added"};
  std::vector<Rgba> species_colors;
  bool clog_rule = true;  // false: the clog timer has no limit to count towards
  bool drain = false;     // the drain protocol: a clog of clog_timeout is the jam that ends it (no rule)
};

// The information box's lines (title, time, exits, Q~, clog timer, arch, legend or colour bar as `o` asks)
// into the current ImGui window; em is the font's height in pixels.
void info_contents(const core::Frame& f, const OverlayData& d, const OverlayOptions& o, const Style& style,
                   float em);

// The overlay's data for a scene: its clog settings, the original diameter, and a title naming r, chi, mu,
// seed.
OverlayData overlay_data_for(const core::Model& model);

class Overlay {
 public:
  Overlay();  // needs a current GL 3.3 context; creates the ImGui context and its GL objects
  ~Overlay();
  Overlay(const Overlay&) = delete;
  Overlay& operator=(const Overlay&) = delete;
  // Draw into the bound framebuffer of w x h pixels. geo (may be null) is the container, which place_clear
  // keeps the information box off.
  void draw(const core::Frame& f, const OverlayData& d, const OverlayOptions& o,
            const std::vector<View>& views, const Style& style, int w, int h,
            const core::Geometry* geo = nullptr, const Annotations* notes = nullptr);
  // Forget what earlier pictures left: the boxes' sizes and corner, the discharge plot's history. The next
  // picture is laid out from itself alone (a snapshot that a script replays must not depend on what a window
  // showed before it).
  void reset();
  // The last draw left the information box out of the picture (place_clear and may_leave, no clear corner).
  bool info_left() const { return info_left_; }
  // Where the last draw put the information box and the colour bar (pixels: x0, y0, x1, y1; empty if not
  // drawn), so that tests can hold them apart.
  std::array<float, 4> info_rect() const {
    return info_shown_ ? std::array<float, 4>{info_x_, info_y_, info_x_ + info_w_, info_y_ + info_h_}
                       : std::array<float, 4>{};
  }
  std::array<float, 4> colorbar_rect() const { return bar_rect_; }
  // ... and the discharge plot's and the scale bar's boxes (empty if not drawn).
  std::array<float, 4> plot_rect() const { return plot_rect_; }
  // Every box of the last picture found clear space (none had to be put over the container or a grain);
  // a box the user placed (--overlay-at) counts as clear.
  bool boxes_clear() const { return boxes_clear_; }
  std::array<float, 4> scale_rect() const { return scale_rect_; }
  // The texts drawn over the scene in the last picture (an event's caption, the slow-motion badge, each
  // note's label in each view, a comparison panel's heading), by name ("caption", "badge", "note K V",
  // "heading"), with whether each found clear space.
  struct PlacedText {
    std::string name;
    std::array<float, 4> rect;
    bool clear;
  };
  const std::vector<PlacedText>& texts() const { return texts_; }

 private:
  void ensure_font(int h, double scale);
  bool dark_ = false;  // the panels' ImGui colours follow the style's background
  void build(const core::Frame& f, const OverlayData& d, const OverlayOptions& o,
             const std::vector<View>& views, const Style& style, int w, int h, const core::Geometry* geo,
             const Annotations& notes);
  void plot(const core::Frame& f, const OverlayData& d, const OverlayOptions& o,
            const std::vector<View>& views, const Style& style);
  void draw_zoombox(const std::vector<View>& views, int h);
  void draw_events(const Annotations& notes, const std::vector<View>& views, float em);
  void draw_texts(const Annotations& notes, const std::vector<View>& views, float em);
  void draw_colorbar(const OverlayOptions& o, const std::vector<View>& views, const Style& style, float em);
  void draw_info(const core::Frame& f, const OverlayData& d, const OverlayOptions& o,
                 const std::vector<View>& views, const Style& style, int w, int h, const core::Geometry* geo,
                 float em);
  void draw_scale(const OverlayData& d, const OverlayOptions& o, const std::vector<View>& views, float em);
  void draw_ids(const core::Frame& f, const std::vector<View>& views, bool arch_ids, int selected, float em);
  void draw_heading(const OverlayData& d, float em);
  void* ctx_ = nullptr;
  void* heading_font_ = nullptr;         // ImFont at kHeadingScale times the text (a comparison's headings)
  std::array<float, 4> heading_rect_{};  // where this picture's heading went (empty: none)
  // The discharge so far, for the plot: (t, cumulative original exits, cumulative added exits, clogged).
  struct Sample {
    double t;
    std::vector<std::int64_t> exits;  // so far, per species
    bool clogged;
    double clog_start;  // s: when the clog began (its last exit), if clogged
  };
  std::vector<Sample> history_;
  int font_px_ = 0;
  bool laid_out_ = false;
  float info_w_ = 0, info_h_ = 0;  // the information box's size in the last frame, pixels
  float info_x_ = 0, info_y_ = 0;  // ... and its top-left corner
  bool info_shown_ = false;        // drawn in this frame's picture
  float bar_w_ = 0, bar_h_ = 0;    // the colour bar's size in the last frame
  std::array<float, 4> bar_rect_{};
  std::array<float, 4> plot_rect_{}, scale_rect_{};
  bool boxes_clear_ = true;
  // What this picture's boxes must keep off (the container, grains, boxes already placed); a copy of
  // picture_space_ for each pass of build().
  std::unique_ptr<FreeSpace> space_;
  // The container and this picture's grains, made once a picture (both passes of the layout take a copy).
  std::unique_ptr<FreeSpace> picture_space_;
  // The container alone as the views show it: the costliest part of the free space (every cell tested against
  // the walls), kept while the views, the container's place and the cell size stay (a standing camera, a
  // container that does not vibrate: every picture of most movies).
  std::unique_ptr<FreeSpace> container_space_;
  std::vector<View> container_views_;
  const core::Geometry* container_geo_ = nullptr;
  double container_dx_ = 0, container_dy_ = 0;
  float container_cell_ = 0;
  Box container_region_;
  const FreeSpace& container_space(const std::vector<View>& views, const core::Geometry* geo, double dx,
                                   double dy, const Box& region, float cell);
  // Where each box went in the pictures before (by the box's name): kept while it stays clear, anchored at
  // its corner as its size changes, and searched again at least every kRecheck layouts (about half a second
  // of a movie), so a box does not jump between pictures and its search is not paid in every picture.
  struct Spot {
    Box box, within;
    int corner = 0, age = 0;
  };
  static constexpr int kRecheck = 30;
  std::map<std::string, Spot> spots_;
  // A text over the scene (caption, badge, note label) as one more box of the layout, placed after the boxes:
  // where it would stand (`want`, its top-left) if that is clear, else the clear spot nearest to it within
  // `within` (where it stood in the last picture while that stays clear), else `want` (not clear). Blocks it.
  Box place_text(const std::string& name, float w, float h, const Box& within, std::array<float, 2> want,
                 float ax, float ay);
  // The texts of a picture are placed widest first (a short note placed first near its point could leave
  // a long one no clear spot): draw_events and draw_texts run once without drawing (`texts_dry_`: place_text
  // only notes what each text wants), the wants are placed, then the two run again and place_text returns
  // each text's spot (`texts_placed_`).
  void place_texts(const Annotations& notes, const std::vector<View>& views, float em, bool events);
  ImDrawList* text_draw_list();
  struct TextWant {
    std::string name;
    float w, h;
    Box within;
    std::array<float, 2> want;
    float ax, ay;
  };
  bool texts_dry_ = false;
  std::vector<TextWant> text_wants_;
  std::map<std::string, Box> texts_placed_;
  std::shared_ptr<ImDrawList> scratch_;  // what the dry run draws into (shared: its type is ImGui's)
  std::map<std::string, Box> text_spots_;
  std::vector<PlacedText> texts_;
  std::optional<Box> spot(const std::string& key, float w, float h, const Box& within, int corner, float pad);
  float panel_x0_ = 0, panel_x1_ = 0, panel_y1_ = 0;  // the panel's region, pixels
  int info_corner_ = 0;     // 0 top-right, 1 top-left, 2 bottom-right, 3 bottom-left (place_clear)
  bool info_left_ = false;  // see info_left()
};

}  // namespace render
