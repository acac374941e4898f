// Draws a Frame (never the Box2D world) with OpenGL 3.3 core into the bound framebuffer: background, walls
// and the obstacle where the container is now (a vibrating one moves), instanced signed-distance grains
// (disks and regular polygons at their orientation), and the arch highlight (a halo on members, bonds between
// neighbours). A tilted container is drawn as it stands (the views turn the picture, render/camera.h).
#pragma once

#include <vector>

#include "core/frame.h"
#include "core/geometry.h"
#include "render/camera.h"
#include "render/draw_list.h"
#include "render/palette.h"

namespace render {

class Renderer {
 public:
  Renderer();  // needs a current GL 3.3 context
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Clears the w x h framebuffer and draws every view: build_draw_list, then paint.
  void draw(const core::Frame& frame, const core::Geometry& geo, const std::vector<View>& views,
            const Style& style, int w, int h, const ArchStyle& arch = {});
  // Paints a draw list in every view (the second stage; the style gives the background and palette).
  void paint(const DrawList& list, const std::vector<View>& views, const Style& style, int w, int h);

 private:
  void draw_view(const View& v, int image_h);
  unsigned disk_program_ = 0, segment_program_ = 0;
  unsigned quad_vbo_ = 0, disk_vao_ = 0, disk_vbo_ = 0, segment_vao_ = 0, segment_vbo_ = 0;
  std::vector<ShapeInstance> disks_;
  std::vector<SegmentInstance> walls_, bonds_, chains_;
  std::vector<float> chain_width_m_, trail_width_m_;
  std::vector<SegmentInstance> trails_;
  float halo_m_ = 0.012f, bond_m_ = 0.012f, wall_m_ = 0.012f;
  Rgba halo_edge_{0, 0, 0, 0};
};

}  // namespace render
