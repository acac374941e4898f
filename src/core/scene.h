// The scene: every parameter of a siloscope run, in SI units, with its default.
//
// One struct, one table of fields (scene_fields()), one validation function (validate()).
// The scene file parser, the command line (--set key=value), the metadata writer and the
// inspector's panel all go through the same table, so a key means the same thing everywhere.
#pragma once

#include <cstdint>
#include <string>
#include <variant>
#include <vector>

namespace core {

// Defaults follow ../shared/model.md (Carlevaro et al., Granular Matter 24, 2022). The allowed range, unit
// and meaning of every field are written once, in the field table of scene.cpp (`siloscope scene --keys`
// prints it).
struct Scene {
  // --- particles ---
  double radius_original = 0.065;      // m, r_o
  double size_ratio = 0.4;             // r = r_a / r_o
  std::int64_t n_total = 250;          // N_o + N_a
  double chi = 0.4;                    // N_a / (N_o + N_a), number fraction of added disks
  double density = 1.0;                // kg/m^2, areal, both species
  double friction = 0.5;               // particle-particle and particle-wall, static = dynamic
  double restitution = 0.1;            // coefficient of restitution
  double restitution_threshold = 1.0;  // m/s; impacts slower than this are perfectly inelastic (Box2D rule)
  double mu = 0.0;                     // A*m^2, dipole moment of added disks (perpendicular to the plane)
  double dipole_cutoff = 0.0;          // m; dipole pairs farther apart are skipped; 0 = all pairs

  // --- container ---
  double silo_width = 1.00;     // m, W
  double silo_height = 5.00;    // m, H_s: vertical part above the hopper
  double hopper_height = 1.36;  // m, H_t
  double aperture = 0.299;      // m, D = 2R = 4.6 r_o, centred at x = 0, y = 0
  double gravity = 9.8;         // m/s^2, downward

  // --- driving ---
  double kick_period = 0.1;        // s, time between kicks
  double kick_impulse_max = 5e-5;  // N*s; impulse magnitudes uniform in [0, this]
  bool global_kick = true;         // one extra impulse, same law, applied to every particle at each kick
  bool settle_kicks =
      false;  // also kick while settling with the aperture closed (strong kicks fling disks out)

  // --- protocol ---
  // Order of random sequential deposition: "originals_first" (the original disks, then the added ones: every
  // campaign so far) or "shuffled" (species interleaved at random; the bottom then holds chi added disks, see
  // docs/campaigns/README.md, "The initial packing").
  std::string deposit_order = "originals_first";
  double settle_time = 4.0;   // s, settling with the aperture closed before t = 0
  double duration = 150.0;    // s of discharge after the aperture opens
  double clog_timeout = 5.0;  // s without an exit before the blocking arch is removed (the 5 s rule)
  double clog_min_gap = 0.5;  // s; an exit gap at least this long is recorded as a clog
  // A clog is "arrested" at a kick when a blocking arch stands and every disk near the outlet moved less than
  // arrest_shift of its own radius over the arrest_hold seconds before the kick (see sim/clog.h).
  double arrest_hold = 0.05;      // s
  double arrest_shift = 0.1;      // fraction of a disk's radius
  double arch_wall_reach = 1.36;  // m; wall contacts below this height anchor arches (default: the hopper)
  std::string arch_method = "contact_path";  // contact_path | visible; how the 5 s rule picks the arch
  double reinject_gap = 0.05;                // m, clearance between a re-injected disk and the column top

  // --- numerics (not in the paper; chosen by the speed-versus-accuracy study) ---
  double dt = 1e-3;                      // s, fixed time step
  std::int64_t velocity_iterations = 8;  // Box2D velocity solver iterations
  std::int64_t position_iterations = 3;  // Box2D position solver iterations
  double length_scale = 10.0;            // Box2D length units per metre
  bool continuous = false;               // Box2D continuous collision for the disks
  bool unsafe = false;                   // let the health monitor warn instead of stopping

  std::uint64_t seed = 1;  // one seed determines the whole run

  // Derived counts (rounded N_a = chi * N).
  std::int64_t n_added() const;
  std::int64_t n_original() const { return n_total - n_added(); }
  double radius_added() const { return size_ratio * radius_original; }
};

// A field of the scene, for parsing, printing and editing.
struct Field {
  using Ptr = std::variant<double Scene::*, std::int64_t Scene::*, bool Scene::*, std::string Scene::*,
                           std::uint64_t Scene::*>;
  const char* key;
  Ptr ptr;
  const char* unit;
  double min, max;      // numeric range (inclusive), ignored for bool and text
  const char* choices;  // for text fields: "a|b"
  const char* doc;
};

// Scene and campaign files are small text files: a regular file of at most this many bytes. A directory, a
// device or a larger file is refused with a message that says which (a directory: "did you mean DIR/HINT?").
constexpr std::uintmax_t kMaxTextFileBytes = 1u << 20;
void check_text_file(const std::string& path, const std::string& what, const std::string& dir_hint);

const std::vector<Field>& scene_fields();
const Field* find_field(const std::string& key);

// Set one field from text ("0.4", "true", "visible"). Throws core::InputError naming key, value and range.
void set_field(Scene& s, const std::string& key, const std::string& value, const std::string& origin);
// The value of a field as text (round-trips through set_field).
std::string field_text(const Scene& s, const Field& f);

// Check every field and the relations between them. Throws core::InputError naming the key.
void validate(const Scene& s);

// Read a scene file (TOML, flat keys). Unknown keys and wrong types are errors. Does not validate.
Scene load_scene(const std::string& path);
// The same from TOML text; `origin` names it in errors.
Scene parse_scene(const std::string& text, const std::string& origin);
// Apply "key=value" overrides from the command line.
void apply_overrides(Scene& s, const std::vector<std::string>& assignments);

// The scene as TOML text, every field with its unit: the metadata files and `siloscope scene --print`.
std::string scene_toml(const Scene& s);

}  // namespace core
