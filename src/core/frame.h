// Frame: a snapshot of the simulation, the only thing the renderer, the trajectory writer and the
// inspector see of it. Events: what happened (exits, clogs, long-lasting arches). Plain data, SI units.
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "core/geometry.h"

namespace core {

// A grain's species: its place in the scene's species list (core/setup.h), 0 to 15. The paper's shorthand
// has two: Original (0) and Added (1); the names of any other list come from the scene.
enum class Species : std::uint8_t { Original = 0, Added = 1 };
inline int species_index(Species s) {
  return static_cast<int>(s);
}
// The shorthand's names ("original", "added"); "species K" beyond them (outputs use the scene's names).
std::string species_name(Species s);

struct Particle {
  float x, y;    // m, centre (world frame: a vibrating container's displacement included)
  float angle;   // rad
  float vx, vy;  // m/s
  float radius;  // m, of the disk of equal area (a disk's own radius)
  float force;   // N, sum of contact normal force magnitudes on this grain over the last step
  Species species;
  std::uint8_t sides = 0;  // 0: disk; 3-8: regular polygon of circumradius radius * polygon_extent(sides)
};

// Circumradius over equal-area radius of a regular polygon of `sides` sides (1 for a disk).
double polygon_extent(int sides);
// Whether two grains are close enough to touch: their circumscribed circles, 10% enlarged, overlap.
bool within_reach(const Particle& a, const Particle& b);

// A contact and its force as the solver applied it (impulses over dt: the last step's, or their mean over the
// frame interval in a recording's frames, sim::Silo::average_forces), as recordings keep
// it: `b` is a grain; `a` a grain, or a wall (-1 - its core::Wall index) in Frame::wall_contacts. On b the
// force is force * n + ft * (ny, -nx) (on a, the opposite); n is the unit normal from a towards b, (px, py)
// where they touch (world frame, m). A version-1 contacts file (io/contacts.h) carries the normal force only
// (ft, the point and the normal 0).
struct Contact {
  int a, b;
  float force;   // N, normal, >= 0 (compression)
  float ft = 0;  // N, tangential (friction), signed
  float px = 0, py = 0;
  float nx = 0, ny = 0;
  bool has_geometry() const { return nx != 0 || ny != 0; }
};

// A contact's force as the solver applied it in the last step, split into its normal and tangential parts:
// what the Love-Weber stress, an arch's load and its force balance are made of. `b` is a grain; `a` is a
// grain or a wall (-1 - its core::Wall index). On b the force is fn * normal + ft * tangent() (on a, the
// opposite).
struct ContactForce {
  int a = 0, b = 0;
  Vec2 point;     // m, where they touch (world frame; the manifold's mean point)
  Vec2 normal;    // unit, from a towards b
  double fn = 0;  // N, >= 0: compression
  double ft = 0;  // N, signed, along tangent() (friction; |ft| <= friction * fn)
  Vec2 tangent() const { return {normal.y, -normal.x}; }
  Vec2 on_b() const { return {fn * normal.x + ft * normal.y, fn * normal.y - ft * normal.x}; }
};

struct Frame {
  double t = 0;                     // s since the aperture opened (negative while settling)
  std::uint64_t step = 0;           // time steps since the start of settling
  std::vector<Particle> particles;  // indexed by particle id
  // The clog open at this frame, as the simulation's step reported it (core/events.h): its arch (ids left to
  // right; empty when no clog is open or none was found), whether one is open, its row of clogs.csv, start
  // and arrest, and the seconds until the rule falls due (infinity with the rule off).
  std::vector<int> arch;
  bool clog_open = false;
  // The arch shown is forming: it stands, and the clog it will be is not yet confirmed (no exit for
  // clog_min_gap). Seen in hindsight: frames are handed on with that latency, the arch set from its formation
  // (app/services/hindsight.h); clog_number is then the clog it becomes.
  bool arch_forming = false;
  int clog_number = 0;
  double clog_start = 0;  // s
  bool clog_arrested = false;
  double rule_due_in = std::numeric_limits<double>::infinity();  // s
  double since_last_exit = 0;                                    // s, the clog timer
  // Exits so far of each species, by its place in the scene's list (the paper's shorthand: original, added).
  std::vector<std::int64_t> exits;
  std::int64_t exits_of(int species) const {
    return species >= 0 && static_cast<size_t>(species) < exits.size() ? exits[static_cast<size_t>(species)]
                                                                       : 0;
  }
  std::int64_t exits_total() const {
    std::int64_t n = 0;
    for (std::int64_t e : exits) n += e;
    return n;
  }
  double container_x = 0, container_y = 0;  // m, a vibrating container's displacement from rest
  // Grain-grain contacts with their forces, when forces were asked for (a live simulation's frames, or a
  // recording's contacts file; trajectories keep only each grain's summed force), and the grains' contacts
  // with walls (a < 0): what a grain's stress and an arch's force balance need beside them.
  std::vector<Contact> contacts;
  std::vector<Contact> wall_contacts;
};

struct ExitEvent {
  double t;  // s
  int id;
  Species species;
};

enum class ClogEnd : std::uint8_t {
  Spontaneous,  // flow resumed before the outlet came to rest (a transient jam)
  Vibration,    // the clog was arrested (arch standing, outlet held still) and flow resumed: a kick broke it
  Rule,         // nothing broke it: the clog_timeout rule removed the arch
  RunEnd,       // still clogged when the run ended (censored)
};
const char* clog_end_name(ClogEnd e);

struct ClogEvent {
  double start;  // s, the last exit before the gap
  double end;    // s, the next exit, the rule, or the end of the run
  ClogEnd ended_by;
  bool arrested;  // at some kick during the clog an arch stood and the outlet disks had held still
  // When its arch formed: the first arch check from which the grains that blocked the outlet when the clog
  // was confirmed (clog_min_gap after start) stood as the arch without a break; with no arch then, the first
  // check after that found one. NaN: no arch blocked it. A later replacement of the arch does not move it.
  // Pictures show the arch from here on (hindsight), while the statistics keep start and end.
  double formed = NAN;
  // That arch's members in the order they arrived (the check from which each has stood in the arch without
  // a break; ties left to right).
  std::vector<int> arrival;
};

struct ArchGeometry {
  double span = 0;           // m, horizontal distance between the outer edges of the end members
  double height = 0;         // m, highest member centre above the aperture line
  double max_angle_deg = 0;  // largest angle at a member between its two neighbours, measured below the arch
};

// A long-lasting arch: the clog_timeout rule fired and removed these particles.
// How the 5 s rule found the members of the arch it removed (scene key arch_method): the contact path across
// the aperture, or the disks visible from the aperture (the named fallback of either).
enum class ArchMethod : std::uint8_t { ContactPath = 0, Visible = 1 };
inline const char* arch_method_name(ArchMethod m) {
  return m == ArchMethod::Visible ? "visible" : "contact_path";
}
// False if `text` names no method.
inline bool parse_arch_method(const std::string& text, ArchMethod& out) {
  if (text == "contact_path") return out = ArchMethod::ContactPath, true;
  if (text == "visible") return out = ArchMethod::Visible, true;
  return false;
}

struct ArchEvent {
  double t = 0;                  // s, when the rule fired
  double clog_duration = 0;      // s, time since the last exit
  std::vector<int> ids;          // members, left to right
  std::vector<Species> species;  // of each member
  ArchGeometry geometry;
  ArchMethod method = ArchMethod::ContactPath;  // how the members were found
  std::vector<float> x, y;                      // m, where each member stood when it was removed
  // The arch's forces in the step the rule fired (core/forces.h; NaN where nobody measured them, as in an
  // imported run): the load the grains above put on it and what its walls held up, along gravity, and its
  // own weight, N; the imbalance |sum of forces| / held.
  double load_N = NAN, held_N = NAN, weight_N = NAN, imbalance = NAN;
};

struct Events {
  std::vector<ExitEvent> exits;
  std::vector<ClogEvent> clogs;
  std::vector<ArchEvent> arches;
};

}  // namespace core
