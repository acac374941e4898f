// Tracked grains' trails: the recent positions of chosen grains, kept from frame to frame and drawn as fading
// segments over the grains. Pure data, no GL (the draw list carries the segments to the renderer).
#pragma once

#include <deque>
#include <map>
#include <vector>

#include "core/frame.h"
#include "render/draw_list.h"

namespace render {

class Trails {
 public:
  // Remember where each of `ids` is in `f` and forget positions older than `keep_s`. A frame earlier than the
  // last one (a jump back in the inspector) or more than `keep_s` after it starts the trails afresh.
  void update(const core::Frame& f, const std::vector<int>& ids, double keep_s);
  // The trails as segments, oldest faint and newest solid, each a third of its grain's radius wide; a grain
  // re-injected at the top (a jump of more than a few diameters) breaks its trail there.
  void append(DrawList& list, const core::Frame& f, Rgba color) const;
  size_t points(int id) const;

 private:
  struct Point {
    double t;
    float x, y;
  };
  std::map<int, std::deque<Point>> at_;
  double last_t_ = 0, keep_s_ = 2;
  bool any_ = false;
};

}  // namespace render
