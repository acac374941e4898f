#include "io/metadata.h"
#include "core/format.h"

#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <iterator>

#include <toml++/toml.h>

#include "core/error.h"
#include "core/scene.h"

#include "core/geometry.h"
#include "core/physics.h"
#include "core/setup.h"
#include "siloscope_version.h"

namespace io {

namespace {
std::string quoted(const std::string& s) {
  return core::toml_string(s);
}
}  // namespace

Fact::Fact(std::string key, const std::string& v) : key_(std::move(key)), toml_(quoted(v)) {}

Fact::Fact(std::string key, const std::vector<std::string>& list) : key_(std::move(key)), toml_("[") {
  for (size_t k = 0; k < list.size(); ++k) toml_ += (k ? ", " : "") + quoted(list[k]);
  toml_ += "]";
}

Fact::Fact(std::string key, double v, int digits)
    : key_(std::move(key)),
      toml_(std::isfinite(v) ? core::format_toml_float(v, digits)
            : v > 0          ? "inf"
            : v < 0          ? "-inf"
                             : "nan") {}

std::string version_string() {
  return std::string(SILOSCOPE_VERSION) + " (git " + SILOSCOPE_GIT + ", " + SILOSCOPE_BUILD_TYPE + ")";
}

Facts derived_facts(const core::Model& model) {
  using core::kPi;
  const core::Scene& s = model.scene;
  const core::Setup& st = model.setup;
  const core::Geometry& g = st.geo;
  Facts f;
  if (st.shorthand) {
    const double ra = s.radius_added(), ma = core::mass_of(ra, s.density);
    const double contact_force = core::dipole_contact_force(s);
    f = {{"n_original", s.n_original()},
         {"n_added", s.n_added()},
         {"radius_added_m", ra},
         {"mass_original_kg", core::mass_of(s.radius_original, s.density)},
         {"mass_added_kg", ma},
         {"hopper_wall_angle_from_vertical_deg", g.wall_angle_from_vertical() * 180 / kPi},
         {"angle_between_hopper_walls_deg", 2 * g.wall_angle_from_vertical() * 180 / kPi},
         {"aperture_over_original_diameter", s.aperture / (2 * s.radius_original)},
         {"dipole_contact_force_over_weight", contact_force / (ma * s.gravity)}};
  } else {
    f.push_back({"species", st.species_names()});
    for (const auto& d : st.species) {
      f.push_back({"n_" + d.name, d.count});
      f.push_back({"radius_range_" + d.name + "_m",
                   core::format_g(d.radius_min, 6) + " .. " + core::format_g(d.radius_max, 6)});
      f.push_back({"mean_mass_" + d.name + "_kg", core::kPi * d.mean_square_radius() * d.density});
    }
    f.push_back({"n_total", st.n_total});
    f.push_back({"aperture_over_largest_mean_diameter", s.aperture / (2 * st.reference_radius)});
  }
  f.push_back({"hopper_height_m", g.hopper_height});
  f.push_back({"left_wall_angle_from_vertical_deg", g.left_wall_angle() * 180 / kPi});
  f.push_back({"right_wall_angle_from_vertical_deg", g.right_wall_angle() * 180 / kPi});
  f.push_back({"gravity_x_m_per_s2", st.gravity.x});
  f.push_back({"gravity_y_m_per_s2", st.gravity.y});
  if (st.drive.vibrating()) {
    f.push_back({"vibration_amplitude_m", st.drive.amplitude});
    f.push_back({"vibration_gamma", st.drive.amplitude * st.drive.omega * st.drive.omega / s.gravity});
    f.push_back({"vibration_peak_speed_m_per_s", st.drive.amplitude * st.drive.omega});
  }
  f.push_back({"clog_rule", st.clog_rule ? std::string("on")
                                         : std::string("off: clogs end only by the drive or the run's end")});
  f.push_back({"dipole_safe_dt_s", core::dipole_safe_dt(st)});
  f.push_back({"kinematic_safe_dt_s", core::kinematic_safe_dt(st, s.gravity)});
  f.push_back({"steps_per_kick", std::llround(s.kick_period / s.dt)});
  f.push_back({"box2d_linear_slop_m", 0.005 / s.length_scale});
  return f;
}

std::string metadata_toml(const core::Model& model, const RunInfo& info) {
  const core::Scene& scene = model.scene;
  std::string s = std::string(kMetadataFirstLine) + "\n[siloscope]\n";
  s += "version = " + quoted(SILOSCOPE_VERSION) + "\n";
  s += "git = " + quoted(SILOSCOPE_GIT) + "\n";
  s += "build_type = " + quoted(SILOSCOPE_BUILD_TYPE) + "\n";
  s += "box2d = " + quoted(SILOSCOPE_BOX2D_VERSION) + "\n";
  s += "command = " + quoted(info.command) + "\n";
  char when[64];
  std::time_t now = std::time(nullptr);
  std::strftime(when, sizeof when, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  s += "written_utc = " + quoted(when) + "\n\n[scene]\n" + core::scene_toml(scene, "scene") + "\n[derived]\n";
  for (const auto& f : derived_facts(model)) s += f.key() + " = " + f.toml() + "\n";
  if (!info.facts.empty()) {
    s += "\n[run]\n";
    for (const auto& f : info.facts) s += f.key() + " = " + f.toml() + "\n";
  }
  if (!info.look.empty()) {
    s += "\n[look]\n";
    for (const auto& f : info.look) s += f.key() + " = " + f.toml() + "\n";
  }
  if (!info.health.empty()) {
    s += "\n[health]\n";
    for (const auto& f : info.health) s += f.key() + " = " + f.toml() + "\n";
  }
  return s;
}

RunRecord read_run_record(const std::string& path) {
  core::check_text_file(path, "run metadata", core::kMetadataFile);
  std::ifstream in(path, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return run_record_of(text, path);
}

RunRecord run_record_of(const std::string& text, const std::string& path) {
  toml::table t;
  try {
    t = toml::parse(text, path);
  } catch (const toml::parse_error& e) {
    throw core::InputError(path + ": malformed TOML: " + std::string(e.description()));
  }
  // Written whole by siloscope, so every table is there: a missing one means a truncated or hand-cut file,
  // whose scene would otherwise be read with defaults (a duration or seed the run never had).
  for (const auto& [table, key] : {std::pair<const char*, const char*>{"siloscope", "version"},
                                   {"scene", "seed"},
                                   {"scene", "duration"},
                                   {"health", "status"}})
    if (!t[table][key])
      throw core::InputError(path + ": no " + table + "." + key +
                             " (a run's metadata.toml always has it: truncated or cut by hand?)");
  RunRecord r;
  r.command = t["siloscope"]["command"].value_or(std::string());
  r.health_warnings = t["health"]["warnings"].value_or<std::int64_t>(0);
  r.ballistic = t["health"]["ballistic"].value_or(false);
  r.airborne_fraction = t["health"]["airborne_fraction_mean"].value_or(0.0);
  r.interrupted = t["run"]["interrupted"].value_or(false);
  if (r.interrupted) r.covered_s = t["run"]["simulated_s"].value_or(-1.0);
  if (t["scene"]["drain"].value_or(false)) {
    r.drain_outcome = t["run"]["drain_outcome"].value_or(std::string());
    if (r.drain_outcome != "draining" && r.drain_outcome != "emptied" && r.drain_outcome != "jammed")
      throw core::InputError(path + ": run.drain_outcome = \"" + r.drain_outcome +
                             "\": a drain's outcome is draining, emptied or jammed (cut or edited by hand?)");
    r.drain_end_s = t["run"]["drain_end_s"].value_or(NAN);
    r.drain_remaining = t["run"]["drain_remaining"].value_or<std::int64_t>(-1);
    if (r.drain_remaining < 0)
      throw core::InputError(path + ": run.drain_remaining missing or negative (a drain's metadata has it)");
  }
  return r;
}

}  // namespace io
