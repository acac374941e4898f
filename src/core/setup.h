// A scene resolved once into what the simulation builds: the species with their counts and size laws, the
// container with its obstacle, gravity, the drive, and every choice as an enum. resolve() is where the
// relations between keys are checked (an obstacle inside a wall, fractions that do not sum to 1, a container
// that cannot hold the grains, ...): each error names FILE:LINE where the key was set, the key, the value and
// what would be allowed.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/frame.h"
#include "core/geometry.h"
#include "core/scene.h"

namespace core {

enum class SizeLaw { Fixed, Uniform, Lognormal };
enum class DepositOrder { InOrder, Shuffled };
enum class VibrationAxis { Vertical, Horizontal };

struct SpeciesDef {
  std::string name;
  bool has_color = false;
  std::array<float, 3> color{};  // sRGB in [0, 1] when has_color
  int count = 0;
  int first_id = 0;  // grains of this species have ids first_id .. first_id + count - 1
  SizeLaw law = SizeLaw::Fixed;
  double radius = 0;      // m: fixed radius, lognormal mean (equal-area disk radius for polygons)
  double radius_min = 0;  // m: the smallest radius the law gives (fixed: radius)
  double radius_max = 0;  // m: the largest
  double spread = 0;      // lognormal: standard deviation over the mean
  int sides = 0;          // 0 disk, 3-8 regular polygon
  double density = 1, friction = 0.5, restitution = 0.1;
  double dipole = 0;  // A*m^2

  bool polygon() const { return sides >= 3; }
  // Circumradius over equal-area radius: 1 for a disk, 1.555 for a triangle, 1.054 for an octagon.
  double extent_factor() const;
  // Mean of r^2 under the size law (m^2): grain areas are pi times it.
  double mean_square_radius() const;
};

struct Drive {
  double kick_period = 0.1;     // s
  double kick_impulse_max = 0;  // N*s; 0: no kicks
  bool global_kick = true;
  bool settle_kicks = false;
  double amplitude = 0;  // m, of the container's harmonic motion (0: still)
  double omega = 0;      // rad/s
  VibrationAxis axis = VibrationAxis::Vertical;
  bool vibrating() const { return amplitude > 0 && omega > 0; }
};

struct Setup {
  std::vector<SpeciesDef> species;  // in id order
  int n_total = 0;
  bool shorthand = true;  // the paper's "original" and "added" species
  Geometry geo;
  Vec2 gravity;     // m/s^2, in the container's frame
  double tilt = 0;  // rad, the container turned counter-clockwise (the renderer turns the picture back)
  Drive drive;
  DepositOrder deposit_order = DepositOrder::InOrder;
  ArchMethod arch_method = ArchMethod::ContactPath;
  bool clog_rule = true;        // clog_timeout > 0
  double reference_radius = 0;  // m, the largest species' mean radius (the shorthand: r_o)

  int species_of(int id) const;
  bool any_dipole() const;
  bool any_polygon() const;
  double smallest_radius() const;  // m, of any grain
  double largest_extent() const;   // m, the largest circumradius of any grain
  std::vector<std::string> species_names() const;
};

// Resolve and check the relations between keys (field ranges are validate()'s). Throws core::InputError.
Setup resolve(const Scene& s);

// The container's displacement from its rest position at time t (s since the opening), m, in its own frame:
// A sin(omega t) along the vibration's axis; zero before the opening and without vibration.
Vec2 container_offset(const Setup& setup, double t);

// "#rrggbb" into sRGB components in [0, 1]; false when the text is not that.
bool parse_hex_color(const std::string& text, std::array<float, 3>& rgb);

// H_t: hopper_height, or from hopper_angle when that is set.
double hopper_height_of(const Scene& s);
// The largest species' mean radius, m (the shorthand: radius_original): what cameras, slabs and the scale bar
// are sized by.
double reference_radius(const Scene& s);

}  // namespace core
