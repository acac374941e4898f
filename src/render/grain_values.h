// Per-grain quantities a picture can be coloured by that a Particle does not carry on its own: the
// displacement since a reference time (kept from frame to frame, like the trails), the coordination number
// and the pressure of the Love-Weber stress. Pure data, no GL.
#pragma once

#include <vector>

#include "core/frame.h"
#include "render/palette.h"

namespace render {

// Contacts per grain (grain-grain; walls and the obstacle not counted). A frame that carries the solver's
// contacts (a live simulation, a recording) counts those that touch; a stored frame (trajectories keep
// positions only) counts pairs of grains whose equal-area disks are closer than the sum of their radii plus
// kCoordinationGap of it: the same rule for disks, an estimate for polygons.
constexpr double kCoordinationGap = 0.02;
std::vector<float> coordination(const core::Frame& f);

// Whether a colouring needs GrainValues (displacement, coordination, stress), not the particle alone.
inline bool per_grain_values(ColorMode m) {
  return m == ColorMode::Displacement || m == ColorMode::Coordination || m == ColorMode::Stress;
}

class GrainValues {
 public:
  // The values of the style's mode in `f` (empty for species, speed, force and id, which need none).
  // Stress: each grain's pressure, N/m (core::pressures), from the frame's contacts and wall contacts; NaN
  // (grey) where the frame carries no contact geometry (a trajectory without its contacts file, or one of
  // version 1).
  // Displacement: from where each grain stood in the first frame at or after style.displacement_from (0
  // before it); a grain re-injected since then (now more than two of its diameters higher than it was: the
  // grains of a silo fall) has none (NaN). A frame earlier than the reference (a jump back) drops it.
  // `reference`: where each grain stood at the reference time, when the caller knows it (the inspector, from
  // its trajectory: frames drawn out of order); null: the first frame drawn at or after the time.
  const std::vector<float>& update(const core::Frame& f, const Style& style,
                                   const core::Frame* reference = nullptr);
  // The largest finite value of the last update (the top of a scale taken from each frame's data).
  double largest() const { return largest_; }
  // A displacement scale taken from the data (displacement_max 0): set it to this frame's largest, as the
  // colour bar and the grains show it. Any other style is left as it is.
  void settle_scale(Style& style) const;

 private:
  std::vector<float> values_, ref_x_, ref_y_;
  double ref_t_ = 0, largest_ = 0;
  bool have_ref_ = false;
};

}  // namespace render
