// The scene: every parameter of a siloscope run, in SI units (angles in degrees), with its default.
//
// One struct, one table of fields (scene_fields()), one validation (validate(), which resolves the scene: see
// core/setup.h). The scene file parser, the command line (--set key=value), campaigns, the metadata writer
// and the live panel all go through the same table, so a key means the same thing everywhere.
//
// Grains come as a list of species ([[species]] tables, species_fields()). Without such tables the paper's
// two-species shorthand applies: radius_original, size_ratio, n_total, chi and mu describe the "original" and
// the "added" disks of Carlevaro et al. (2022), bit for bit the runs every committed campaign made.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace core {

// One species of grains: a [[species]] table of a scene file, or `--set species.NAME.KEY=VALUE`.
struct SpeciesSpec {
  std::string name;            // [a-z][a-z0-9_]*, unique; names the species in every output
  std::string color;           // "#rrggbb"; empty: the palette's colour for this species' place in the list
  std::int64_t count = 0;      // grains of this species, or 0 and `fraction`
  double fraction = 0;         // number fraction of n_total (every species gives counts, or every fraction)
  std::string size = "fixed";  // fixed | uniform | lognormal: how each grain's radius is drawn
  double radius = 0;           // m: the radius (fixed) or the mean radius (lognormal)
  double radius_min = 0;       // m: uniform interval, or lognormal truncation (0: mean / e^(3 sigma))
  double radius_max = 0;       // m: uniform interval, or lognormal truncation (0: mean * e^(3 sigma))
  double spread = 0;           // lognormal: standard deviation of the radius over its mean
  std::int64_t sides = 0;      // 0: disk; 3-8: regular polygon (radius: of the disk of equal area)
  std::optional<double> density;      // kg/m^2; absent: the scene's density
  std::optional<double> friction;     // absent: the scene's friction
  std::optional<double> restitution;  // absent: the scene's restitution
  double dipole = 0;                  // A*m^2, dipole moment perpendicular to the plane (0: none)
};

// Defaults follow ../shared/model.md (Carlevaro et al., Granular Matter 24, 2022). The allowed range, unit
// and meaning of every field are written once, in the field tables of scene.cpp (`siloscope scene --keys`
// prints them).
struct Scene {
  // --- particles: the paper's two-species shorthand (ignored where [[species]] tables are given) ---
  double radius_original = 0.065;  // m, r_o
  double size_ratio = 0.4;         // r = r_a / r_o
  std::int64_t n_total = 250;      // N_o + N_a (with [[species]] fractions: the total they divide)
  double chi = 0.4;                // N_a / (N_o + N_a), number fraction of added disks
  double mu = 0.0;                 // A*m^2, dipole moment of added disks (perpendicular to the plane)
  // --- particles: materials (every species' default) ---
  double density = 1.0;                // kg/m^2, areal
  double friction = 0.5;               // particle-particle and particle-wall, static = dynamic
  double restitution = 0.1;            // coefficient of restitution
  double restitution_threshold = 1.0;  // m/s; impacts slower than this are perfectly inelastic (Box2D rule)
  double dipole_cutoff = 0.0;          // m; dipole pairs farther apart are skipped; 0 = all pairs
  std::vector<SpeciesSpec> species;    // [[species]]; empty: the shorthand above

  // --- container ---
  std::string container = "hopper";  // hopper | flat (outlet in a horizontal floor)
  double silo_width = 1.00;          // m, W
  double silo_height = 5.00;         // m, H_s: vertical part above the hopper (or above the floor)
  double hopper_height = 1.36;       // m, H_t
  double hopper_angle = 0.0;         // deg, each hopper wall from the vertical; 0: set by hopper_height
  double aperture = 0.299;           // m, D = 2R = 4.6 r_o; the outlet is centred at x = 0, y = 0
  double outlet_x = 0.0;             // m, the outlet's centre from the silo's axis (the walls move, not it)
  std::string obstacle = "none";     // none | disk | bar
  double obstacle_size = 0.0;        // m, the disk's diameter or the bar's width
  double obstacle_thickness = 0.0;   // m, the bar's height
  double obstacle_height = 0.0;      // m, the obstacle's centre above the outlet
  double obstacle_x = 0.0;           // m, the obstacle's centre from the outlet's centre
  double tilt = 0.0;     // deg, the whole container turned counter-clockwise (gravity at an angle)
  double gravity = 9.8;  // m/s^2

  // --- drive ---
  double kick_period = 0.1;        // s, time between kicks (and between the arrest checks of every drive)
  double kick_impulse_max = 5e-5;  // N*s; impulse magnitudes uniform in [0, this]; 0: no kicks
  bool global_kick = true;         // one extra impulse, same law, applied to every particle at each kick
  bool settle_kicks =
      false;  // also kick while settling with the aperture closed (strong kicks fling disks out)
  double vibration_amplitude = 0.0;              // m, of the container's harmonic motion (0: none)
  double vibration_gamma = 0.0;                  // A (2 pi f)^2 / g, instead of the amplitude (0: unused)
  double vibration_frequency = 0.0;              // Hz
  std::string vibration_direction = "vertical";  // vertical | horizontal

  // --- protocol ---
  // Order of random sequential deposition: "originals_first" (species in the order of the list: for the
  // shorthand the original disks, then the added ones; every campaign so far) or "shuffled" (species
  // interleaved at random; see docs/campaigns/README.md, "The initial packing").
  std::string deposit_order = "originals_first";
  double settle_time = 4.0;   // s, settling with the aperture closed before t = 0
  double duration = 150.0;    // s of discharge after the aperture opens
  double clog_timeout = 5.0;  // s without an exit before the blocking arch is removed (the 5 s rule); 0: off
  double clog_min_gap = 0.5;  // s; an exit gap at least this long is recorded as a clog
  // A clog is "arrested" at a kick when a blocking arch stands and every grain near the outlet moved less
  // than arrest_shift of its own radius over the arrest_hold seconds before the kick (see core/clog.h).
  double arrest_hold = 0.05;      // s
  double arrest_shift = 0.1;      // fraction of a grain's radius
  double arch_wall_reach = 1.36;  // m; wall contacts below this height anchor arches (default: the hopper)
  std::string arch_method = "contact_path";  // contact_path | visible; how the 5 s rule picks the arch
  double reinject_gap = 0.05;                // m, clearance between a re-injected grain and the column top
  // Drain a fixed number of grains (To, Lai and Pak's protocol): exits leave for good, and the run's outcome
  // is "emptied" (every grain out) or "jammed" (a clog lasted clog_timeout; its arch is not removed).
  bool drain = false;

  // --- numerics (not in the paper; chosen by the speed-versus-accuracy study) ---
  double dt = 1e-3;                      // s, fixed time step
  std::int64_t velocity_iterations = 8;  // Box2D velocity solver iterations
  std::int64_t position_iterations = 3;  // Box2D position solver iterations
  double length_scale = 10.0;            // Box2D length units per metre
  bool continuous = false;               // Box2D continuous collision for the grains
  bool unsafe = false;                   // let the health monitor warn instead of stopping
  // The arrested-state shortcut (off by default; docs/accuracy/campaign-numerics.md): once the outlet has
  // been arrested at arrest_skip consecutive kicks and no grain moved more than arrest_skip_shift of its
  // radius from one kick to the next, the run jumps to the clog rule instead of integrating the still
  // packing, drawing the skipped kicks so that a seed stays one run. 0: off (every step integrated).
  std::int64_t arrest_skip = 0;     // kicks
  double arrest_skip_shift = 0.01;  // fraction of a grain's radius per kick period

  std::uint64_t seed = 1;  // one seed determines the whole run

  // Where each key was set ("FILE:LINE" or "--set"), for error messages; not a parameter.
  std::map<std::string, std::string> origin;
  // Keys of an earlier siloscope met in a run's stored scene and translated or dropped
  // (core/scene_history.h), one sentence each; not a parameter.
  std::vector<std::string> history;

  // The shorthand's derived counts (rounded N_a = chi * N).
  std::int64_t n_added() const;
  std::int64_t n_original() const { return n_total - n_added(); }
  double radius_added() const { return size_ratio * radius_original; }
  // True when the grains are the paper's two shorthand species (no [[species]] tables).
  bool shorthand() const { return species.empty(); }
  // "FILE:LINE: " where `key` was set, or "scene: " when it keeps its default.
  std::string where(const std::string& key) const;
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
  const char* section;  // particles, container, drive, protocol, numerics, run
};

// A field of one species ([[species]] key, or species.NAME.KEY on the command line).
struct SpeciesField {
  using Ptr = std::variant<double SpeciesSpec::*, std::int64_t SpeciesSpec::*, std::string SpeciesSpec::*,
                           std::optional<double> SpeciesSpec::*>;
  const char* key;
  Ptr ptr;
  const char* unit;
  double min, max;
  const char* choices;  // text fields with a closed set: "a|b"; nullptr: free text
  const char* doc;
};

// At most this many species in a scene (they are stored as one byte per grain in trajectories).
constexpr std::size_t kMaxSpecies = 16;

// Scene and campaign files are small text files: a regular file of at most this many bytes. A directory, a
// device or a larger file is refused with a message that says which (a directory: "did you mean DIR/HINT?").
constexpr std::uintmax_t kMaxTextFileBytes = 1u << 20;
// The file every output directory keeps its metadata in; a run's [scene] table loads back as a scene file.
constexpr const char* kMetadataFile = "metadata.toml";
void check_text_file(const std::string& path, const std::string& what, const std::string& dir_hint);
// The same for any file siloscope reads, at most `max_bytes` (links are followed: a link to a device is
// refused as the device), so no input can exhaust memory or block.
void check_input_file(const std::string& path, const std::string& what, std::uintmax_t max_bytes,
                      const std::string& dir_hint = "");

const std::vector<Field>& scene_fields();
const Field* find_field(const std::string& key);
const std::vector<SpeciesField>& species_fields();
const SpeciesField* find_species_field(const std::string& key);
// The shorthand keys that [[species]] tables replace (radius_original, size_ratio, chi, mu).
bool is_shorthand_key(const std::string& key);

// Set one field from text ("0.4", "true", "visible", or "species.small.radius" = "0.02"). Throws
// core::InputError naming key, value and range.
void set_field(Scene& s, const std::string& key, const std::string& value, const std::string& origin);
// The value of a field as text (round-trips through set_field).
std::string field_text(const Scene& s, const Field& f);
std::string species_field_text(const SpeciesSpec& sp, const SpeciesField& f);
// Every key of the scene as "key" -> text, species keys as species.NAME.KEY: what a campaign point is made of
// and what two scenes are compared by.
std::map<std::string, std::string> scene_values(const Scene& s);

// Check every field and the relations between them (by resolving the scene, core/setup.h). Throws
// core::InputError naming FILE:LINE (where the key was set), the key, the value and what is allowed.
void validate(const Scene& s);

// Read a scene file (TOML: flat keys, [[species]] tables). Unknown keys and wrong types are errors. Does not
// validate.
Scene load_scene(const std::string& path);
// The same from TOML text; `origin` names it in errors.
Scene parse_scene(const std::string& text, const std::string& origin);
// True when the (valid) scene file sets no key at all: it runs the built-in defaults.
bool scene_is_empty_file(const std::string& path);
// Apply "key=value" overrides from the command line.
void apply_overrides(Scene& s, const std::vector<std::string>& assignments);

// The scene as TOML text, every field with its unit: the metadata files and `siloscope scene FILE`. With
// [[species]], the shorthand keys are left out and the species follow as tables.
// `species_table` prefixes the species tables ([[scene.species]] inside a metadata file's [scene]).
std::string scene_toml(const Scene& s, const std::string& species_table = "");

}  // namespace core
