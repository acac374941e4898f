// core::resolve: from a validated Scene to the Setup every layer below uses (species, sizes, geometry,
// obstacle, drive, safe time steps). Over 400 lines because the cross-field checks (obstacle in the
// container, species that fit the aperture, dipole time steps) need the whole resolved setup at once and
// must say FILE:LINE of the field at fault; split, they would pass half-built setups around.
#include "core/setup.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "core/error.h"
#include "core/format.h"
#include "core/physics.h"
#include "core/portable_math.h"

namespace core {

namespace {

std::string num(double v) {
  return format_g(v, 4);
}

[[noreturn]] void refuse(const Scene& s, const std::string& key, const std::string& value,
                         const std::string& why) {
  throw InputError(s.where(key) + ": " + key + " = " + value + " is not allowed; " + why);
}

bool parse_color(const std::string& text, std::array<float, 3>& rgb) {
  if (text.size() != 7 || text[0] != '#') return false;
  for (int k = 0; k < 3; ++k) {
    int v = 0;
    for (int j = 1 + 2 * k; j < 3 + 2 * k; ++j) {
      const char c = text[static_cast<size_t>(j)];
      int d = c >= '0' && c <= '9'   ? c - '0'
              : c >= 'a' && c <= 'f' ? c - 'a' + 10
              : c >= 'A' && c <= 'F' ? c - 'A' + 10
                                     : -1;
      if (d < 0) return false;
      v = 16 * v + d;
    }
    rgb[static_cast<size_t>(k)] = static_cast<float>(v) / 255.0f;
  }
  return true;
}

// The two species of the paper's shorthand, ids in the order originals then added.
std::vector<SpeciesDef> shorthand_species(const Scene& s) {
  SpeciesDef o, a;
  o.name = "original";
  o.count = static_cast<int>(s.n_original());
  o.radius = o.radius_min = o.radius_max = s.radius_original;
  a.name = "added";
  a.count = static_cast<int>(s.n_added());
  a.radius = a.radius_min = a.radius_max = s.radius_added();
  a.dipole = s.mu;
  for (SpeciesDef* d : {&o, &a})
    d->density = s.density, d->friction = s.friction, d->restitution = s.restitution;
  a.first_id = o.count;
  return {o, a};
}

std::vector<SpeciesDef> listed_species(const Scene& s) {
  std::vector<SpeciesDef> out;
  const bool by_count = s.species.front().count > 0;
  double fraction_sum = 0;
  for (const auto& sp : s.species) {
    const std::string key = "species." + sp.name;
    if (sp.count > 0 && sp.fraction > 0)
      refuse(s, key + ".fraction", format_shortest(sp.fraction),
             "species " + sp.name + " gives both a count and a fraction; give one of them");
    if (sp.count == 0 && sp.fraction == 0)
      throw InputError(s.where(key + ".name") + ": species " + sp.name +
                       " gives neither count nor fraction; give one of them (every species the same way)");
    if ((sp.count > 0) != by_count)
      throw InputError(s.where(key + (by_count ? ".fraction" : ".count")) + ": species " + sp.name +
                       (by_count ? " gives a fraction" : " gives a count") + " but species " +
                       s.species.front().name + (by_count ? " a count" : " a fraction") +
                       "; every species gives a count, or every species a fraction");
    fraction_sum += sp.fraction;
  }
  std::vector<int> counts;
  if (by_count) {
    for (const auto& sp : s.species) counts.push_back(static_cast<int>(sp.count));
  } else {
    if (std::abs(fraction_sum - 1.0) > 1e-9) {
      std::string parts;
      for (const auto& sp : s.species) parts += (parts.empty() ? "" : " + ") + format_shortest(sp.fraction);
      throw InputError(s.where("species." + s.species.front().name + ".fraction") +
                       ": the species' fractions sum to " + parts + " = " + format_g(fraction_sum, 10) +
                       ", not 1");
    }
    // Largest remainders: the counts sum to n_total exactly.
    int assigned = 0;
    std::vector<std::pair<double, size_t>> rest;
    for (size_t k = 0; k < s.species.size(); ++k) {
      const double exact = s.species[k].fraction * static_cast<double>(s.n_total);
      counts.push_back(static_cast<int>(std::floor(exact)));
      assigned += counts.back();
      rest.push_back({exact - std::floor(exact), k});
    }
    std::stable_sort(rest.begin(), rest.end(), [](auto a, auto b) { return a.first > b.first; });
    for (size_t k = 0; assigned < s.n_total && k < rest.size(); ++k, ++assigned) ++counts[rest[k].second];
  }
  int first = 0;
  for (size_t k = 0; k < s.species.size(); ++k) {
    const SpeciesSpec& sp = s.species[k];
    const std::string key = "species." + sp.name;
    SpeciesDef d;
    d.name = sp.name;
    d.count = counts[k];
    d.first_id = first;
    first += d.count;
    if (!sp.color.empty() && !parse_color(sp.color, d.color))
      refuse(s, key + ".color", toml_string(sp.color), "expected #rrggbb (hex), e.g. \"#2a9d8f\"");
    d.has_color = !sp.color.empty();
    if (sp.sides != 0 && (sp.sides < 3 || sp.sides > 8))
      refuse(s, key + ".sides", std::to_string(sp.sides), "0 (a disk) or 3 to 8 (a regular polygon)");
    d.sides = static_cast<int>(sp.sides);
    d.density = sp.density.value_or(s.density);
    d.friction = sp.friction.value_or(s.friction);
    d.restitution = sp.restitution.value_or(s.restitution);
    d.dipole = sp.dipole;
    if (sp.size == "fixed") {
      d.law = SizeLaw::Fixed;
      if (!(sp.radius > 0))
        refuse(s, key + ".radius", format_shortest(sp.radius), "a fixed size needs a radius > 0 m");
      d.radius = d.radius_min = d.radius_max = sp.radius;
    } else if (sp.size == "uniform") {
      d.law = SizeLaw::Uniform;
      if (!(sp.radius_min > 0))
        refuse(s, key + ".radius_min", format_shortest(sp.radius_min),
               "the size distribution would reach non-positive radii; a uniform size needs 0 < radius_min < "
               "radius_max");
      if (!(sp.radius_max > sp.radius_min))
        refuse(s, key + ".radius_max", format_shortest(sp.radius_max),
               "a uniform size needs radius_max > radius_min = " + format_shortest(sp.radius_min));
      d.radius_min = sp.radius_min;
      d.radius_max = sp.radius_max;
      d.radius = 0.5 * (d.radius_min + d.radius_max);
    } else {  // lognormal
      d.law = SizeLaw::Lognormal;
      if (!(sp.radius > 0))
        refuse(s, key + ".radius", format_shortest(sp.radius), "a lognormal size needs a mean radius > 0 m");
      if (!(sp.spread > 0))
        refuse(
            s, key + ".spread", format_shortest(sp.spread),
            "a lognormal size needs a spread > 0 (standard deviation over the mean; 0 is size = \"fixed\")");
      d.radius = sp.radius;
      d.spread = sp.spread;
      const double sigma = std::sqrt(portable::log(1.0 + sp.spread * sp.spread));
      const double median = sp.radius / std::sqrt(1.0 + sp.spread * sp.spread);
      d.radius_min = sp.radius_min != 0 ? sp.radius_min : median * portable::exp(-3.0 * sigma);
      d.radius_max = sp.radius_max != 0 ? sp.radius_max : median * portable::exp(3.0 * sigma);
      if (!(d.radius_min > 0))
        refuse(s, key + ".radius_min", format_shortest(sp.radius_min),
               "the size distribution would reach non-positive radii; the truncation must be > 0 m");
      if (!(d.radius_min < d.radius && d.radius < d.radius_max))
        refuse(s, key + ".radius_max", format_shortest(d.radius_max),
               "the truncation [" + num(d.radius_min) + ", " + num(d.radius_max) +
                   "] m must hold the mean radius " + num(d.radius));
    }
    out.push_back(d);
  }
  return out;
}

// The obstacle must sit inside the container, leave a grain through between itself and each wall, and not
// rest on the outlet.
void check_obstacle(const Scene& s, const Setup& st) {
  const Obstacle& ob = st.geo.obstacle;
  if (!ob.present()) return;
  const Geometry& g = st.geo;
  const double grain = 2 * st.largest_extent();
  if (!(s.obstacle_size > 0))
    refuse(s, "obstacle_size", format_shortest(s.obstacle_size),
           "an obstacle needs a size > 0 m (the disk's diameter or the bar's width)");
  if (ob.kind == Obstacle::Kind::Bar && !(s.obstacle_thickness > 0))
    refuse(s, "obstacle_thickness", format_shortest(s.obstacle_thickness), "a bar needs a thickness > 0 m");
  const double bottom = ob.centre.y - 0.5 * ob.height, top = ob.centre.y + 0.5 * ob.height;
  if (bottom < grain)
    refuse(s, "obstacle_height", format_shortest(s.obstacle_height),
           "the obstacle's lower edge would be " + num(bottom) +
               " m above the outlet, closing it to grains of " + num(grain) +
               " m; the lowest height that lets one through is " + num(grain + 0.5 * ob.height) + " m");
  if (top > g.total_height - grain)
    refuse(s, "obstacle_height", format_shortest(s.obstacle_height),
           "the obstacle would reach the top of the container (" + num(g.total_height) +
               " m); the highest is " + num(g.total_height - grain - 0.5 * ob.height) + " m");
  // The gap to each side wall, at the obstacle's heights: sampled along the obstacle's outline.
  double left = INFINITY, right = INFINITY;
  for (int k = 0; k <= 64; ++k) {
    const double y = bottom + (top - bottom) * k / 64.0;
    const double dy = y - ob.centre.y;
    double half = 0.5 * ob.width;
    if (ob.kind == Obstacle::Kind::Disk)
      half = std::sqrt(std::max(0.0, 0.25 * ob.width * ob.width - dy * dy));
    left = std::min(left, (ob.centre.x - half) - g.left_at(y));
    right = std::min(right, g.right_at(y) - (ob.centre.x + half));
  }
  if (std::min(left, right) < grain) {
    const double room = g.width_at(ob.centre.y) - 2 * grain - 2 * std::abs(ob.centre.x);
    refuse(s, "obstacle_size", format_shortest(s.obstacle_size),
           "the obstacle leaves " + num(std::max(0.0, std::min(left, right))) + " m to the " +
               (left < right ? "left" : "right") + " wall, less than the largest grain (" + num(grain) +
               " m); at this height and obstacle_x at most " + num(std::max(0.0, room)) + " m fits");
  }
}

}  // namespace

bool parse_hex_color(const std::string& text, std::array<float, 3>& rgb) {
  return parse_color(text, rgb);
}

double SpeciesDef::extent_factor() const {
  // A regular n-gon of circumradius R has area (n/2) R^2 sin(2 pi / n); equal to pi r^2.
  return polygon_extent(sides);
}

double SpeciesDef::mean_square_radius() const {
  switch (law) {
    case SizeLaw::Fixed:
      return radius * radius;
    case SizeLaw::Uniform:
      return (radius_min * radius_min + radius_min * radius_max + radius_max * radius_max) / 3.0;
    case SizeLaw::Lognormal:
      return radius * radius * (1.0 + spread * spread);  // truncation ignored (a small correction)
  }
  return radius * radius;
}

int Setup::species_of(int id) const {
  for (size_t k = species.size(); k-- > 0;)
    if (id >= species[k].first_id) return static_cast<int>(k);
  return 0;
}
bool Setup::any_dipole() const {
  for (const auto& d : species)
    if (d.dipole > 0 && d.count > 0) return true;
  return false;
}
bool Setup::any_polygon() const {
  for (const auto& d : species)
    if (d.polygon() && d.count > 0) return true;
  return false;
}
double Setup::smallest_radius() const {
  double r = INFINITY;
  for (const auto& d : species)
    if (d.count > 0) r = std::min(r, d.radius_min);
  return r;
}
double Setup::largest_extent() const {
  double r = 0;
  for (const auto& d : species)
    if (d.count > 0) r = std::max(r, d.radius_max * d.extent_factor());
  return r;
}
std::vector<std::string> Setup::species_names() const {
  std::vector<std::string> out;
  for (const auto& d : species) out.push_back(d.name);
  return out;
}

double hopper_height_of(const Scene& s) {
  if (s.hopper_angle > 0) {
    double sn = 0, cs = 0;
    portable::sincos(s.hopper_angle * kPi / 180.0, sn, cs);
    return (0.5 * s.silo_width - 0.5 * s.aperture) * cs / sn;
  }
  return s.hopper_height;
}

double reference_radius(const Scene& s) {
  if (s.shorthand()) return s.radius_original;
  double r = 0;
  for (const auto& sp : s.species) {
    double mean = sp.radius;
    if (sp.size == "uniform") mean = 0.5 * (sp.radius_min + sp.radius_max);
    r = std::max(r, mean);
  }
  return r > 0 ? r : s.radius_original;
}

Vec2 container_offset(const Setup& setup, double t) {
  if (!setup.drive.vibrating() || t <= 0) return {};
  double sn = 0, cs = 0;
  portable::sincos(setup.drive.omega * t, sn, cs);
  const double u = setup.drive.amplitude * sn;
  return setup.drive.axis == VibrationAxis::Vertical ? Vec2{0, u} : Vec2{u, 0};
}

namespace {
// The container and what must fit through and into it: the outlet wider than every grain, inside the floor.
void resolve_container(const Scene& s, Setup& st) {
  if (s.container == "flat" && s.hopper_angle != 0)
    refuse(s, "hopper_angle", format_shortest(s.hopper_angle),
           "a flat silo has no hopper walls; hopper_angle applies to container = \"hopper\"");
  st.geo = make_geometry(s);
  const Geometry& g = st.geo;
  if (s.container == "hopper" && !(g.hopper_height > 0.01))
    refuse(s, "hopper_angle", format_shortest(s.hopper_angle),
           "the hopper would be " + num(g.hopper_height) +
               " m tall; use a smaller angle or container = \"flat\"");
  for (const auto& d : st.species) {
    if (d.count == 0) continue;
    const double diameter = 2.0 * d.radius_max;
    if (s.aperture <= diameter)
      refuse(s, "aperture", format_shortest(s.aperture),
             "it must be wider than every grain (species " + d.name + ": diameter up to " +
                 format_shortest(diameter) + " m)");
  }
  if (0.5 * s.aperture + std::abs(s.outlet_x) >= 0.5 * s.silo_width) {
    if (s.outlet_x == 0)
      refuse(s, "aperture", format_shortest(s.aperture),
             "it must be narrower than silo_width = " + format_shortest(s.silo_width));
    refuse(s, "outlet_x", format_shortest(s.outlet_x),
           "the outlet must lie within the silo's bottom: |outlet_x| + aperture/2 < silo_width/2 = " +
               format_shortest(0.5 * s.silo_width) + " m");
  }
  if (2.0 * st.largest_extent() >= s.silo_width)
    refuse(s, "silo_width", format_shortest(s.silo_width),
           "every grain must fit in the silo (the largest is " + num(2 * st.largest_extent()) + " m across)");
}

// Gravity (tilted with the container) and the drive: kicks and a harmonic vibration.
void resolve_drive(const Scene& s, Setup& st) {
  st.tilt = s.tilt * kPi / 180.0;
  if (s.tilt == 0) {
    st.gravity = {0, -s.gravity};
  } else {
    double sn = 0, cs = 0;
    portable::sincos(st.tilt, sn, cs);
    st.gravity = {-s.gravity * sn, -s.gravity * cs};
  }
  st.drive.kick_period = s.kick_period;
  st.drive.kick_impulse_max = s.kick_impulse_max;
  st.drive.global_kick = s.global_kick;
  st.drive.settle_kicks = s.settle_kicks;
  st.drive.axis = s.vibration_direction == "horizontal" ? VibrationAxis::Horizontal : VibrationAxis::Vertical;
  if (s.vibration_amplitude > 0 && s.vibration_gamma > 0)
    refuse(s, "vibration_gamma", format_shortest(s.vibration_gamma),
           "give the vibration's amplitude or its Gamma, not both (vibration_amplitude = " +
               format_shortest(s.vibration_amplitude) + " m)");
  if (s.vibration_amplitude > 0 || s.vibration_gamma > 0) {
    if (!(s.vibration_frequency > 0))
      refuse(s, "vibration_frequency", format_shortest(s.vibration_frequency),
             "a vibration needs a frequency > 0 Hz");
    if (s.vibration_frequency * s.dt > 0.05)
      refuse(s, "vibration_frequency", format_shortest(s.vibration_frequency),
             "a period must span at least 20 time steps; at dt = " + format_shortest(s.dt) + " s at most " +
                 num(0.05 / s.dt) + " Hz");
    st.drive.omega = 2 * kPi * s.vibration_frequency;
    st.drive.amplitude = s.vibration_amplitude > 0
                             ? s.vibration_amplitude
                             : s.vibration_gamma * s.gravity / (st.drive.omega * st.drive.omega);
    if (s.vibration_gamma > 0 && !(s.gravity > 0))
      refuse(s, "vibration_gamma", format_shortest(s.vibration_gamma), "Gamma needs gravity > 0");
    if (st.drive.amplitude * st.drive.omega * s.dt > 0.5 * st.smallest_radius())
      refuse(s, s.vibration_amplitude > 0 ? "vibration_amplitude" : "vibration_gamma",
             format_shortest(s.vibration_amplitude > 0 ? s.vibration_amplitude : s.vibration_gamma),
             "the container would move " + num(st.drive.amplitude * st.drive.omega * s.dt) +
                 " m per time step, more than half the smallest grain's radius (" +
                 num(0.5 * st.smallest_radius()) + " m); lower it or dt");
  }
}

// The protocol: kicks and arrest checks on whole steps, the shortcut and the clog rule consistent.
void check_protocol(const Scene& s, const Setup& st) {
  // Kicks and arrest checks land on steps: the period must be a whole number of steps (to 1e-6 of a step).
  double steps_per_kick = s.kick_period / s.dt;
  if (steps_per_kick < 1.0 || std::abs(steps_per_kick - std::round(steps_per_kick)) > 1e-6)
    refuse(s, "kick_period", format_shortest(s.kick_period),
           "it must be a whole multiple of dt = " + format_shortest(s.dt) + " s");
  const double hold_steps = std::round(s.arrest_hold / s.dt);
  if (hold_steps < 1.0 || hold_steps >= std::round(steps_per_kick))
    refuse(s, "arrest_hold", format_shortest(s.arrest_hold),
           "it must be at least dt = " + format_shortest(s.dt) +
               " s and shorter than kick_period = " + format_shortest(s.kick_period) + " s");
  if (s.arrest_skip > 0 && !st.clog_rule)
    refuse(s, "arrest_skip", std::to_string(s.arrest_skip),
           "the shortcut jumps to the clog rule, which is off (clog_timeout = 0); use 0 (off)");
  if (s.arrest_skip > 0 && st.drive.vibrating())
    refuse(
        s, "arrest_skip", std::to_string(s.arrest_skip),
        "a vibrating container never holds still; use 0 (off) with vibration_amplitude or vibration_gamma");
  if (st.clog_rule && s.clog_min_gap >= s.clog_timeout)
    refuse(s, "clog_min_gap", format_shortest(s.clog_min_gap),
           "it must be shorter than clog_timeout = " + format_shortest(s.clog_timeout) + " s");
}

// The grains must fit: the settled column (packing fraction at most ~0.8) below the top.
void check_fill(const Scene& s, const Setup& st) {
  const Geometry& g = st.geo;
  double area_grains = 0;
  for (const auto& d : st.species) area_grains += kPi * d.count * d.mean_square_radius();
  double area_box = g.area();
  if (g.obstacle.present())
    area_box -= g.obstacle.kind == Obstacle::Kind::Disk ? 0.25 * kPi * g.obstacle.width * g.obstacle.width
                                                        : g.obstacle.width * g.obstacle.height;
  if (area_grains / 0.8 > 0.9 * area_box) {
    const std::string why = "the container cannot hold the grains: their packed area " +
                            format_g(area_grains / 0.8, 4) + " m^2 does not fit in the container (" +
                            format_g(area_box, 4) + " m^2); raise silo_height or use fewer grains";
    if (st.shorthand) refuse(s, "n_total", std::to_string(s.n_total), why);
    std::string counts;
    for (const auto& d : st.species) counts += (counts.empty() ? "" : " + ") + std::to_string(d.count);
    throw InputError(s.where("species." + st.species.front().name + ".name") + ": " + counts + " = " +
                     std::to_string(st.n_total) + " grains: " + why);
  }
}

}  // namespace

Setup resolve(const Scene& s) {
  Setup st;
  st.shorthand = s.shorthand();
  st.species = st.shorthand ? shorthand_species(s) : listed_species(s);
  for (const auto& d : st.species) st.n_total += d.count;
  if (st.n_total < 1)
    throw InputError(s.where("n_total") + ": the scene has no grains; give a species a count > 0");
  if (st.n_total > 20000)
    throw InputError(s.where("n_total") + ": " + std::to_string(st.n_total) + " grains; at most 20000");
  st.reference_radius = reference_radius(s);
  st.deposit_order = s.deposit_order == "shuffled" ? DepositOrder::Shuffled : DepositOrder::InOrder;
  parse_arch_method(s.arch_method, st.arch_method);
  st.clog_rule = s.clog_timeout > 0;

  resolve_container(s, st);
  resolve_drive(s, st);
  check_protocol(s, st);
  check_fill(s, st);
  check_obstacle(s, st);
  return st;
}

double dipole_safe_dt(const Setup& st) {
  double worst = 0;  // the largest omega of any pair of dipole species
  for (size_t i = 0; i < st.species.size(); ++i) {
    const SpeciesDef& a = st.species[i];
    if (!(a.dipole > 0) || a.count == 0) continue;
    for (size_t j = i; j < st.species.size(); ++j) {
      const SpeciesDef& b = st.species[j];
      if (!(b.dipole > 0) || b.count == 0 || (i == j && a.count < 2)) continue;
      double omega;
      if (i == j) {
        // Two grains of one species (the shorthand's added disks): reduced mass m / 2.
        const double r = a.radius_min, d = 2.0 * r;
        const double force = kDipolePrefactor * a.dipole * a.dipole / (d * d * d * d);
        const double stiffness = 4.0 * force / (2.0 * r);
        omega = std::sqrt(2.0 * stiffness / mass_of(r, a.density));
      } else {
        const double d = a.radius_min + b.radius_min;
        const double force = kDipolePrefactor * a.dipole * b.dipole / (d * d * d * d);
        const double ma = mass_of(a.radius_min, a.density), mb = mass_of(b.radius_min, b.density);
        omega = std::sqrt(4.0 * force / d / (ma * mb / (ma + mb)));
      }
      worst = std::max(worst, omega);
    }
  }
  return worst > 0 ? 1.0 / worst : INFINITY;
}

double kinematic_safe_dt(const Setup& st, double gravity) {
  const double smallest = st.smallest_radius();
  double v = std::sqrt(2.0 * gravity * st.geo.total_height);
  if (st.drive.vibrating()) v += st.drive.amplitude * st.drive.omega;
  return v > 0 ? 2.0 * smallest / v : INFINITY;
}

}  // namespace core
