// Where the overlay's boxes may go: a grid over the picture that marks what they must not cover (the
// container with its walls, the column below the outlet the exiting grains fall through, the obstacle, every
// grain and every box already placed), and the search for the clear spot nearest to where a box would like to
// be. Pure math on the picture's pixels, no GL: the overlay uses it on the picture it draws, and `record`
// uses it before the first frame to decide whether a panel needs a margin beside its container.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/frame.h"
#include "core/geometry.h"
#include "render/camera.h"

namespace render {

struct OverlayOptions;

struct Box {
  float x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // pixels, top-left origin
  float w() const { return x1 - x0; }
  float h() const { return y1 - y0; }
  bool empty() const { return !(x1 > x0 && y1 > y0); }
  bool overlaps(const Box& b) const { return x0 < b.x1 && b.x0 < x1 && y0 < b.y1 && b.y0 < y1; }
  bool inside(const Box& b) const { return x0 >= b.x0 && y0 >= b.y0 && x1 <= b.x1 && y1 <= b.y1; }
};

class FreeSpace {
 public:
  // The region boxes may use (a panel of the picture), in cells of `cell` pixels.
  FreeSpace(Box region, float cell);
  // The container as the views show it, shifted by (dx, dy) m (a vibrating container's displacement): its
  // inside, its walls (with their drawn thickness) and the outlet's column, four grain diameters deep.
  void block_container(const std::vector<View>& views, const core::Geometry& geo, double dx = 0,
                       double dy = 0);
  // Every grain of the frame, with the arch's ring around it, where a view shows it.
  void block_grains(const core::Frame& f, const std::vector<View>& views);
  // A box already placed, with `pad` pixels around it.
  void block(const Box& b, float pad = 0);
  // Cells of b that are blocked (0: b is clear). Parts of b outside the region count as blocked.
  long covered(const Box& b) const;
  // A clear box of w x h pixels inside `within` (and the region), whose point at fractions (ax, ay) of its
  // size lies nearest to `target` (e.g. its top-right corner nearest the panel's top-right corner: ax = 1,
  // ay = 0); none if no clear spot exists.
  std::optional<Box> place(float w, float h, const Box& within, float tx, float ty, float ax, float ay) const;
  // The same towards corner k of `within` (0 top-right, 1 top-left, 2 bottom-right, 3 bottom-left), `pad`
  // pixels in from its edges.
  std::optional<Box> place_at_corner(float w, float h, const Box& within, int k, float pad) const;
  const Box& region() const { return region_; }
  // Make the summed-area table now (copies then share it made).
  void freeze() const { update(); }

 private:
  struct Cells {
    int i0, i1, j0, j1;  // [i0, i1) x [j0, j1), unclamped
  };
  Cells cells_of(const Box& b, float pad) const;
  void mark_cell(int i, int j);
  void mark_box(const Box& b, float pad);
  std::vector<Cells> placed_;  // the boxes placed (block), tested as rectangles
  void update() const;         // the summed-area table after marks
  Box region_;
  float cell_;
  int nx_, ny_;
  std::vector<char> blocked_;
  mutable std::vector<long> sum_;  // (nx+1) x (ny+1) summed-area table of blocked_
  mutable bool dirty_ = true;
};

// Where the information box's title wraps, pixels: at 18 em (a long scene's title would make the box as wide
// as the picture), or inside a margin of margin_w pixels (0: none) with the box's padding.
float info_title_wrap(float em, int margin_w);
// How much wider the gaps within a row of the overlay's boxes are than ImGui's defaults (made for its 13 px
// font): sqrt(em / 13 px), at least 1.
float overlay_style_scale(float em);

// A comparison panel's heading: its type this many times the overlay's text, and the band it takes at the top
// of a panel `panel_w` pixels wide (its rows estimated before ImGui lays it out: the heading shrinks its type
// where they were too few). 0 for no heading.
constexpr float kHeadingScale = 1.6f;
int heading_height(const std::string& text, float em, int panel_w);
// The width of its widest row, estimated the same way (half a heading em a character, at most the wrap).
float heading_width(const std::string& text, float em, int panel_w);

// The text height the overlay uses in a picture h pixels tall at a font scale (the same rule as its font).
float overlay_em(int h, double font_scale);

// What record needs to know before the first frame: the width of a margin, in pixels, to add on the right
// of a panel so that the overlay's boxes, at the sizes they can reach (the information box with a clog's
// rows, the discharge plot, the scale bar), find clear space beside the container; 0 when the views already
// leave it. `views_of(width)` lays the panel's views out in `width` pixels from the panel's left edge (with a
// camera path, one set per key: each must leave the space).
// Where the information box goes in a band of `band` pixels at the bottom of `panel` (a comparison's, below
// its views): the band, or more of the panel above it where the box (`box_h` tall, with `pad` around it)
// needs more; the box at its top-right. The plan (overlay_margin) and the overlay (Overlay::draw_info) both.
Box info_band(const Box& panel, float band, float box_h, float pad);

// `top`: pixels at the top of the panel the boxes may not use (a comparison panel's heading); `band`: a band
// of that many pixels below the views, where the information box goes first (as Overlay draws it).
// `texts`: the sizes of the texts the overlay places after the boxes (an event's caption, the slow-motion
// badge, the user's notes: text_box_estimate), each of which must find clear space in the panel too.
// `column_fits` (if given): whether the column returned holds everything (false: the widest the plan allows,
// half the panel, does not; the overlay then counts the pictures where a box or a text has no clear space).
// `heading_w`: the width of the heading's text, centred in the `top` band (the texts may use the band beside
// it; 0: the whole band is the heading's).
int overlay_margin(const std::function<std::vector<std::vector<View>>(int width)>& views_of,
                   const core::Geometry& geo, const OverlayOptions& o, int panel_x, int panel_w, int h,
                   const std::vector<std::string>& species, const std::string& title, bool colour_rows,
                   int top = 0, int band = 0, const std::vector<std::pair<float, float>>& texts = {},
                   bool* column_fits = nullptr, float heading_w = 0);

// The box of one line of text over the scene (a caption, the badge, a note) estimated before ImGui lays it
// out, in pixels: the text's width and a line, with the box's padding around them.
std::pair<float, float> text_box_estimate(const std::string& text, float em);

// The information box's size estimated from its contents (before ImGui lays it out), in pixels: width and
// height, its title wrapped at `wrap` pixels (as info_contents wraps it). Used by overlay_margin; the box
// itself is measured when drawn.
std::pair<float, float> info_box_estimate(const OverlayOptions& o, float em,
                                          const std::vector<std::string>& species, const std::string& title,
                                          bool colour_rows, float wrap);
// The discharge plot's outer box in a view of `view_w` x `view_h` (pixels), at most `max_w` wide, its axes
// `height` of the view tall.
std::pair<float, float> plot_box_size(float view_w, float view_h, float em, float max_w = 1e9f,
                                      float height = 0.2f);
// The sizes the plot tries, in order, until one finds clear space: whole, as wide as a margin of `margin_w`
// pixels (0: none) allows, then lower.
// `beside`: the width left beside the information box in a band below the views (0: no band), tried before a
// third of the view.
std::vector<std::pair<float, float>> plot_box_sizes(float view_w, float view_h, float em, float margin_w,
                                                    float beside = 0);

}  // namespace render
