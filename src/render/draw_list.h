// What will be drawn, built from a frame in one stage and painted by the Renderer in the next (as MuJoCo's
// mjv_updateScene fills an mjvScene that mjr_render paints): every grain as a shape instance with its fill
// and halo, the walls and the arch's bonds as segments, all in world units. Pure data, no GL: it can be
// built, tested and extended (force chains, trails) without a context.
#pragma once

#include <string>
#include <vector>

#include "core/frame.h"
#include "core/geometry.h"
#include "render/palette.h"

namespace render {

struct ArchStyle {
  double fade_below = 0.5;  // s; while the outlet has flowed more recently than this, the arch is drawn faint
  double halo_m = 0.012;    // halo width, m (at least 2 px)
  double bond_m = 0.012;    // bond width, m (at least 2 px)
};

// One shape: a disk, a regular polygon or an axis-aligned box (the obstacle). Laid out as the shader reads
// it.
struct ShapeInstance {
  float x, y, r;   // m: centre, bounding radius
  float fill[4];   // straight alpha
  float halo[4];   // alpha 0: no halo
  float shape[4];  // angle (rad), sides (0 disk, 3-8 polygon, 100 box), box half width and height (m)
};

// A segment with round caps; width in metres (drawn at least a few pixels wide).
struct SegmentInstance {
  float ax, ay, bx, by;
  float color[4];
  float width_px;  // set per view by the renderer from `width_m`
};

struct DrawList {
  std::vector<ShapeInstance> shapes;    // grains, then the obstacle
  size_t grains = 0;                    // how many of the shapes are grains
  std::vector<SegmentInstance> walls;   // drawn under the grains
  std::vector<SegmentInstance> trails;  // tracked grains' trails, over the grains
  std::vector<float> trail_width_m;
  std::vector<SegmentInstance> chains;  // force chains, over the grains
  std::vector<float> chain_width_m;     // each chain segment's width, m
  std::vector<SegmentInstance> bonds;   // the arch's bonds, over everything
  float wall_m = 0.012f, bond_m = 0.012f, halo_m = 0.012f;
  // A dark edge outside every halo on a light background (alpha 0: none): the arch's gold has 1.6:1 contrast
  // against white, its edge gives the ring the 3:1 of WCAG's graphics (halo_edge_color).
  Rgba halo_edge{0, 0, 0, 0};
};

// The forces on a frame's arch from outside it (grains that are not members, and walls), each on its member
// at the contact point, N (from contacts with their geometry; none without). largest_arch_force: the
// largest's magnitude (0 without), the length Style::arch_forces gives a member's diameter.
struct ArchForce {
  float x, y, fx, fy;
};
std::vector<ArchForce> arch_external_forces(const core::Frame& f);
double largest_arch_force(const core::Frame& f);

// The draw list of a frame in its container, as the style says. `values`: each grain's value for the
// displacement and coordination colourings (render/grain_values.h), on the scale [color_min, value_top].
DrawList build_draw_list(const core::Frame& frame, const core::Geometry& geo, const Style& style,
                         const ArchStyle& arch = {}, const std::vector<float>* values = nullptr,
                         double value_top = 0);

// The draw list as a table for vector output (the gallery's PDF and SVG, snapshots): one row per shape,
// wall, bond and chain segment, in the view's own frame (metres from the camera's centre, the view's turn
// applied, so that the window shown is [-w/2, w/2] x [-h/2, h/2]), only what reaches into the window.
// Columns: kind (grain, obstacle, wall, bond, chain), x, y, r (bounding radius), angle (rad), sides (0 disk,
// 3-8 polygon, 100 box), half_w, half_h, x2, y2 (a segment's other end), width_m, fill and halo (#rrggbbaa).
// r is a polygon's circumradius; a polygon's first vertex is at `angle` from the x axis.
std::string draw_list_csv(const DrawList& list, double cx, double cy, double angle, double half_w,
                          double half_h);

}  // namespace render
