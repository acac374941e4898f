// Disks found frame by frame (vision/detect.h) linked into tracks: the id each disk of a frame takes.
#pragma once

#include <array>
#include <vector>

#include "vision/detect.h"

namespace vision {

// Frame-to-frame linking: each disk of the next frame takes the id of the nearest disk of the last frame
// seen (its position predicted from its last velocity) within `max_step` times the largest radius plus half
// the predicted move (twice as far for the disks and tracks left over), and found in the same size band as
// the disk it was last or of a radius within `size_band` of the median of its last five fitted to their rims
// (a fraction: 0.25 links 10 px to 8 to 12.5 px), nearest pairs first; a disk unmatched for more than
// `memory` frames is forgotten; a new disk gets a new id. The band keeps a blurred disk, whose rim fit wavers
// by a third, in its track; the size keeps a grain whose size lies between two species' (a lognormal's tail,
// found in either band from frame to frame) in its.
class Linker {
 public:
  Linker(double max_step, int memory, double size_band = 0.25)
      : max_step_(max_step), memory_(memory), size_band_(size_band) {}
  // The ids of `found`, in its order.
  std::vector<long> link(const std::vector<Circle>& found);
  long tracks() const { return next_id_; }

 private:
  struct Live {
    long id;
    double x, y, vx, vy, r;
    int band;
    int missed;
    // Its last radii fitted to its rim (a disk's radius wavers by a pixel or two from frame to frame where it
    // touches others): the guard compares with their median; with none, with its last band's radius.
    static constexpr int kSizes = 5;
    std::array<float, kSizes> sizes{};
    int seen = 0;
    void add_size(double radius) { sizes[static_cast<size_t>(seen++ % kSizes)] = static_cast<float>(radius); }
    double size() const;
  };
  // Whether disk `c` can be the grain of a track of this size: within a factor 1 + size_band of it when both
  // are measured, within size_band of the band's radius when either is a band's radius (Circle::fitted).
  bool same_size(const Circle& c, double size, bool size_measured) const;
  double max_step_;
  int memory_;
  double size_band_;
  long next_id_ = 0;
  std::vector<Live> live_;
};

}  // namespace vision
