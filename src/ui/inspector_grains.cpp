// Grains and arches the inspector can be asked about: the grain under a click, its details, and the arch of
// the current frame member by member (ui/inspector.h).
#include <cmath>
#include <cstdio>
#include <limits>

#include "core/arch.h"
#include "core/error.h"
#include "core/forces.h"
#include "core/physics.h"
#include "ui/inspector.h"

namespace ui {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Two grains touch "by distance" when their centres are closer than the sum of their radii (of the circle
// around a polygon) plus this fraction of the smaller radius: what a run without its contacts can offer.
constexpr double kTouchTolerance = 0.05;

double outer_radius(const core::Particle& p) {
  return p.radius * core::polygon_extent(p.sides);
}

std::string species_of(const core::Particle& p, const render::OverlayData& d) {
  const size_t k = static_cast<size_t>(core::species_index(p.species));
  return k < d.species_names.size() ? d.species_names[k] : core::species_name(p.species);
}

// The walls (and obstacle) grain p touches, by distance, in the container's own frame.
std::string walls_touched(const core::Particle& p, const core::Frame& f, const core::Geometry& geo) {
  const core::Vec2 c{p.x - f.container_x, p.y - f.container_y};
  const double reach = outer_radius(p) * (1 + kTouchTolerance);
  const bool flat = geo.kind == core::ContainerKind::Flat;
  const std::pair<core::Wall, const char*> named[] = {
      {core::Wall::HopperLeft, flat ? "floor (left)" : "left hopper wall"},
      {core::Wall::HopperRight, flat ? "floor (right)" : "right hopper wall"},
      {core::Wall::SiloLeft, "left wall"},
      {core::Wall::SiloRight, "right wall"}};
  std::string out;
  for (const auto& [w, name] : named) {
    const core::Segment& s = geo.walls[static_cast<int>(w)];
    if (core::distance_to_segment(c, s) <= reach) out += (out.empty() ? "" : ", ") + std::string(name);
  }
  if (geo.obstacle.present() && geo.obstacle.gap(c) <= outer_radius(p) * kTouchTolerance)
    out += (out.empty() ? "" : ", ") + std::string("obstacle");
  return out;
}

// The normal force between grains a and b from the frame's contacts, NaN when the frame has none.
double contact_force(const core::Frame& f, int a, int b) {
  if (f.contacts.empty()) return kNaN;
  for (const auto& c : f.contacts)
    if ((c.a == a && c.b == b) || (c.a == b && c.b == a)) return c.force;
  return 0.0;
}
}  // namespace

long Inspector::grain_at(core::Vec2 p) const {
  const core::Frame f = current();
  long best = -1;
  double best_d = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < f.particles.size(); ++i) {
    const auto& g = f.particles[i];
    const double d = std::hypot(g.x - p.x, g.y - p.y);
    if (d <= outer_radius(g) && d < best_d) best = static_cast<long>(i), best_d = d;
  }
  return best;
}

void Inspector::select_grain(long id) {
  const long n = static_cast<long>(current().particles.size());
  if (id < -1 || id >= n)
    throw core::InputError("select: grain " + std::to_string(id) + " does not exist; ids run from 0 to " +
                           std::to_string(n - 1) + " (or 'off')");
  selected = id;
  log(id < 0 ? "select off" : "select " + std::to_string(id));
}

std::vector<std::string> Inspector::grain_details() const {
  const core::Frame f = current();
  if (selected < 0 || selected >= static_cast<long>(f.particles.size())) return {};
  const int id = static_cast<int>(selected);
  const core::Particle& g = f.particles[static_cast<size_t>(id)];
  std::vector<std::string> lines;
  char buf[200];
  const char* shape = g.sides == 0 ? "disk" : "polygon";
  std::snprintf(buf, sizeof buf, "grain %d: %s, %s of radius %.4f m%s", id,
                species_of(g, overlay_data).c_str(), shape, static_cast<double>(g.radius),
                g.sides ? " (equal area)" : "");
  lines.push_back(buf);
  std::snprintf(buf, sizeof buf, "at (%.4f, %.4f) m, speed %.3f m/s, angle %.0f deg",
                static_cast<double>(g.x), static_cast<double>(g.y),
                std::hypot(static_cast<double>(g.vx), static_cast<double>(g.vy)),
                static_cast<double>(g.angle) * 180.0 / M_PI);
  lines.push_back(buf);
  // Its contacts: the solver's, with forces, when the run kept them; otherwise by distance.
  std::string contacts;
  int z = 0;
  if (!f.contacts.empty()) {
    for (const auto& c : f.contacts)
      if (c.a == id || c.b == id) {
        std::snprintf(buf, sizeof buf, "%s%d (%.2f N)", z ? ", " : "", c.a == id ? c.b : c.a,
                      static_cast<double>(c.force));
        contacts += buf, ++z;
      }
  } else {
    for (size_t j = 0; j < f.particles.size(); ++j) {
      const auto& o = f.particles[j];
      const double reach =
          outer_radius(g) + outer_radius(o) +
          kTouchTolerance * std::min(static_cast<double>(g.radius), static_cast<double>(o.radius));
      if (static_cast<int>(j) != id && std::hypot(g.x - o.x, g.y - o.y) <= reach)
        contacts += (z++ ? ", " : "") + std::to_string(j);
    }
  }
  const std::string walls = walls_touched(g, f, geo_);
  std::snprintf(buf, sizeof buf, "summed contact force %.2f N, %d grain contact%s%s",
                static_cast<double>(g.force), z, z == 1 ? "" : "s",
                f.contacts.empty() ? " (by distance: the run kept no contacts)" : "");
  lines.push_back(buf);
  if (z) lines.push_back("touches " + contacts);
  if (!walls.empty()) lines.push_back("and " + walls);
  for (size_t k = 0; k < f.arch.size(); ++k)
    if (f.arch[k] == id)
      lines.push_back("member " + std::to_string(k + 1) + " of " + std::to_string(f.arch.size()) +
                      " of this frame's arch");
  return lines;
}

std::vector<ArchMember> Inspector::arch_table() const {
  const core::Frame f = current();
  std::vector<core::Vec2> pos;
  for (const auto& p : f.particles) pos.push_back({p.x, p.y});
  const std::vector<double> bead = core::bead_angles_deg(f.arch, pos);
  std::vector<ArchMember> rows;
  for (size_t k = 0; k < f.arch.size(); ++k) {
    const int id = f.arch[k];
    const core::Particle& g = f.particles[static_cast<size_t>(id)];
    ArchMember m{id, species_of(g, overlay_data), g.x, g.y, kNaN, kNaN, kNaN, walls_touched(g, f, geo_)};
    if (k > 0 && k + 1 < f.arch.size()) m.bead_deg = bead[k - 1];
    if (k > 0) m.force_left = contact_force(f, id, f.arch[k - 1]);
    if (k + 1 < f.arch.size()) m.force_right = contact_force(f, id, f.arch[k + 1]);
    rows.push_back(m);
  }
  // Each member's load from grains outside the arch and the walls' force on it.
  const std::vector<core::ContactForce> forces = core::contact_forces(f);
  const core::Vec2 g = model_.setup.gravity;
  const double gn = std::hypot(g.x, g.y);
  if (!forces.empty() && gn > 0) {
    const core::Vec2 down{g.x / gn, g.y / gn};
    const std::vector<core::ArchBalance> members = core::member_balances(forces, f.arch);
    for (size_t k = 0; k < rows.size(); ++k) {
      rows[k].load = members[k].load(down);
      rows[k].wall_force = std::hypot(members[k].from_walls.x, members[k].from_walls.y);
    }
  }
  return rows;
}

std::optional<ArchLoads> Inspector::arch_loads() const {
  const core::Frame f = current();
  const std::vector<core::ContactForce> forces = core::contact_forces(f);
  const core::Vec2 g = model_.setup.gravity;
  const double gn = std::hypot(g.x, g.y);
  if (f.arch.empty() || forces.empty() || !(gn > 0)) return std::nullopt;
  // Each grain's weight from its species' areal density and its equal-area radius.
  std::vector<core::Vec2> weights(f.particles.size());
  for (size_t i = 0; i < f.particles.size(); ++i) {
    const auto s = static_cast<size_t>(core::species_index(f.particles[i].species));
    const double density = s < model_.setup.species.size() ? model_.setup.species[s].density : 0;
    const double m = core::mass_of(f.particles[i].radius, density);
    weights[i] = {m * g.x, m * g.y};
  }
  const core::ArchBalance b = core::arch_balance(forces, f.arch, weights);
  const core::Vec2 down{g.x / gn, g.y / gn};
  const core::Vec2 r = b.residual();
  return ArchLoads{b.load(down), b.held(down), std::hypot(b.weight.x, b.weight.y), std::hypot(r.x, r.y)};
}

std::string Inspector::print_grain() {
  if (selected < 0) throw core::InputError("print grain: no grain is selected (select ID first)");
  std::string all;
  for (const auto& l : grain_details()) all += l + "\n";
  std::printf("%s", all.c_str());
  last_output = all;
  return all;
}

std::string Inspector::print_arch() {
  std::string all = "id,species,x_m,y_m,bead_angle_deg,force_left_N,force_right_N,load_N,wall_N,walls\n";
  for (const auto& m : arch_table()) {
    char buf[240];
    std::snprintf(buf, sizeof buf, "%d,%s,%.6f,%.6f,%.2f,%.4g,%.4g,%.4g,%.4g,\"%s\"\n", m.id,
                  m.species.c_str(), m.x, m.y, m.bead_deg, m.force_left, m.force_right, m.load, m.wall_force,
                  m.walls.c_str());
    all += buf;
  }
  if (const auto b = arch_loads()) {
    char buf[200];
    std::snprintf(buf, sizeof buf, "# balance: load_N=%.4g held_N=%.4g weight_N=%.4g residual_N=%.4g\n",
                  b->load, b->held, b->weight, b->residual);
    all += buf;
  }
  std::printf("%s", all.c_str());
  last_output = all;
  return all;
}

}  // namespace ui
