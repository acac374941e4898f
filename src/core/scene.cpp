#include "core/scene.h"

#include <toml++/toml.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "core/error.h"
#include "core/format.h"
#include "core/physics.h"

namespace core {

namespace {

std::string range_text(const Field& f) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "[%.10g, %.10g]", f.min, f.max);
  return buf;
}

std::string unit_text(const Field& f) {
  std::string u = f.unit ? f.unit : "";
  return (u.empty() || u == "1") ? "" : " " + u;
}

[[noreturn]] void bad(const std::string& origin, const std::string& key, const std::string& value,
                      const std::string& allowed) {
  throw InputError(origin + ": " + key + " = " + value + " is not allowed; " + allowed);
}
}  // namespace

std::int64_t Scene::n_added() const {
  return std::llround(chi * static_cast<double>(n_total));
}

const std::vector<Field>& scene_fields() {
  // key, member, unit, min, max, choices, doc
  static const std::vector<Field> fields = {
      {"radius_original", &Scene::radius_original, "m", 1e-3, 1.0, nullptr,
       "radius r_o of the original disks"},
      {"size_ratio", &Scene::size_ratio, "1", 0.2, 1.0, nullptr, "r = r_a / r_o, size ratio of added disks"},
      {"n_total", &Scene::n_total, "1", 1, 5000, nullptr, "N_o + N_a, total number of disks"},
      {"chi", &Scene::chi, "1", 0.0, 1.0, nullptr, "N_a / (N_o + N_a), number fraction of added disks"},
      {"density", &Scene::density, "kg/m^2", 1e-6, 1e4, nullptr, "areal density of both species"},
      {"friction", &Scene::friction, "1", 0.0, 10.0, nullptr, "friction coefficient, static = dynamic"},
      {"restitution", &Scene::restitution, "1", 0.0, 1.0, nullptr, "restitution coefficient"},
      {"restitution_threshold", &Scene::restitution_threshold, "m/s", 0.0, 100.0, nullptr,
       "impacts slower than this are perfectly inelastic (Box2D)"},
      {"mu", &Scene::mu, "A*m^2", 0.0, 100.0, nullptr, "dipole moment of the added disks"},
      {"dipole_cutoff", &Scene::dipole_cutoff, "m", 0.0, 100.0, nullptr,
       "dipole pairs farther apart are skipped; 0 = all pairs"},
      {"silo_width", &Scene::silo_width, "m", 0.01, 100.0, nullptr, "W, width of the silo"},
      {"silo_height", &Scene::silo_height, "m", 0.01, 1000.0, nullptr, "H_s, height of the vertical part"},
      {"hopper_height", &Scene::hopper_height, "m", 0.01, 100.0, nullptr, "H_t, height of the hopper part"},
      {"aperture", &Scene::aperture, "m", 1e-3, 100.0, nullptr, "D = 2R, total width of the outlet"},
      {"gravity", &Scene::gravity, "m/s^2", 0.0, 1000.0, nullptr, "gravitational acceleration, downward"},
      {"kick_period", &Scene::kick_period, "s", 1e-4, 1e4, nullptr, "time between kicks"},
      {"kick_impulse_max", &Scene::kick_impulse_max, "N*s", 0.0, 1e3, nullptr,
       "kick impulse magnitudes are uniform in [0, this]"},
      {"global_kick", &Scene::global_kick, "", 0, 0, nullptr,
       "also kick every particle by one shared impulse"},
      {"settle_kicks", &Scene::settle_kicks, "", 0, 0, nullptr, "also kick while settling (aperture closed)"},
      {"deposit_order", &Scene::deposit_order, "", 0, 0, "originals_first|shuffled",
       "order of the random deposition: original disks first, or species at random"},
      {"settle_time", &Scene::settle_time, "s", 0.0, 1e4, nullptr, "settling with the aperture closed"},
      {"duration", &Scene::duration, "s", 0.0, 1e6, nullptr, "discharge time after the aperture opens"},
      {"clog_timeout", &Scene::clog_timeout, "s", 1e-3, 1e6, nullptr,
       "time without exits before the blocking arch is removed"},
      {"clog_min_gap", &Scene::clog_min_gap, "s", 0.0, 1e6, nullptr,
       "exit gaps this long are recorded as clogs"},
      {"arrest_hold", &Scene::arrest_hold, "s", 1e-6, 1e4, nullptr,
       "a clog is arrested when the outlet disks held still this long before a kick"},
      {"arrest_shift", &Scene::arrest_shift, "1", 0.0, 10.0, nullptr,
       "largest move, in disk radii, over arrest_hold that still counts as held still"},
      {"arch_wall_reach", &Scene::arch_wall_reach, "m", 1e-3, 100.0, nullptr,
       "wall contacts below this height anchor arches"},
      {"arch_method", &Scene::arch_method, "", 0, 0, "contact_path|visible",
       "which particles the clog rule removes"},
      {"reinject_gap", &Scene::reinject_gap, "m", 0.0, 10.0, nullptr,
       "clearance above the column for re-injected disks"},
      {"dt", &Scene::dt, "s", 1e-6, 0.02, nullptr, "fixed time step"},
      {"velocity_iterations", &Scene::velocity_iterations, "1", 1, 500, nullptr, "Box2D velocity iterations"},
      {"position_iterations", &Scene::position_iterations, "1", 1, 500, nullptr, "Box2D position iterations"},
      {"length_scale", &Scene::length_scale, "1/m", 0.1, 1000.0, nullptr, "Box2D length units per metre"},
      {"continuous", &Scene::continuous, "", 0, 0, nullptr, "Box2D continuous collision for the disks"},
      {"unsafe", &Scene::unsafe, "", 0, 0, nullptr, "health monitor warns instead of stopping"},
      {"seed", &Scene::seed, "", 0, 1.8446744073709552e19, nullptr, "random seed of the run"},
  };
  return fields;
}

const Field* find_field(const std::string& key) {
  for (const auto& f : scene_fields())
    if (key == f.key) return &f;
  return nullptr;
}

std::string field_text(const Scene& s, const Field& f) {
  return std::visit(
      [&](auto ptr) -> std::string {
        const auto& v = s.*ptr;
        using T = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<T, double>)
          return format_shortest(v);
        else if constexpr (std::is_same_v<T, bool>)
          return v ? "true" : "false";
        else if constexpr (std::is_same_v<T, std::string>)
          return toml_string(v);
        else
          return std::to_string(v);
      },
      f.ptr);
}

void set_field(Scene& s, const std::string& key, const std::string& value, const std::string& origin) {
  const Field* f = find_field(key);
  if (!f) {
    std::string keys;
    for (const auto& g : scene_fields()) keys += std::string(keys.empty() ? "" : ", ") + g.key;
    throw InputError(origin + ": unknown key '" + key + "'; known keys: " + keys);
  }
  std::visit(
      [&](auto ptr) {
        auto& v = s.*ptr;
        using T = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<T, double>) {
          char* end = nullptr;
          double d = std::strtod(value.c_str(), &end);
          if (value.empty() || *end != '\0' || !std::isfinite(d))
            bad(origin, key, value, "expected a finite number");
          v = d;
        } else if constexpr (std::is_same_v<T, bool>) {
          if (value == "true" || value == "1")
            v = true;
          else if (value == "false" || value == "0")
            v = false;
          else
            bad(origin, key, value, "expected true or false");
        } else if constexpr (std::is_same_v<T, std::string>) {
          std::string t = value;
          if (t.size() >= 2 && t.front() == '"' && t.back() == '"') t = t.substr(1, t.size() - 2);
          v = t;
        } else {
          char* end = nullptr;
          errno = 0;
          T i{};
          if constexpr (std::is_unsigned_v<T>)
            i = std::strtoull(value.c_str(), &end, 10);
          else
            i = std::strtoll(value.c_str(), &end, 10);
          bool negative_unsigned = std::is_unsigned_v<T> && value.find('-') != std::string::npos;
          if (value.empty() || *end != '\0' || errno != 0 || negative_unsigned)
            bad(origin, key, value, "expected a whole number in " + range_text(*f));
          v = i;
        }
      },
      f->ptr);
}

void validate(const Scene& s) {
  const std::string origin = "scene";
  // Each field against its own range or choices.
  for (const auto& f : scene_fields()) {
    std::visit(
        [&](auto ptr) {
          const auto& v = s.*ptr;
          using T = std::decay_t<decltype(v)>;
          if constexpr (std::is_same_v<T, double> || std::is_same_v<T, std::int64_t>) {
            double d = static_cast<double>(v);
            if (!std::isfinite(d) || d < f.min || d > f.max)
              bad(origin, f.key, field_text(s, f), "allowed range is " + range_text(f) + unit_text(f));
          } else if constexpr (std::is_same_v<T, std::string>) {
            std::string choices = f.choices ? f.choices : "";
            bool ok = false;
            std::stringstream ss(choices);
            for (std::string c; std::getline(ss, c, '|');) ok = ok || c == v;
            if (!ok) bad(origin, f.key, field_text(s, f), "allowed values are " + choices);
          }
        },
        f.ptr);
  }
  // Relations between fields.
  if (s.aperture <= 2.0 * s.radius_added() && s.n_added() > 0)
    bad(origin, "aperture", format_shortest(s.aperture),
        "it must be wider than the smallest disk (diameter " + format_shortest(2.0 * s.radius_added()) +
            " m)");
  if (s.aperture <= 2.0 * s.radius_original && s.n_original() > 0)
    bad(origin, "aperture", format_shortest(s.aperture),
        "it must be wider than the smallest disk (diameter " + format_shortest(2.0 * s.radius_original) +
            " m)");
  if (s.aperture >= s.silo_width)
    bad(origin, "aperture", format_shortest(s.aperture),
        "it must be narrower than silo_width = " + format_shortest(s.silo_width));
  if (2.0 * s.radius_original >= s.silo_width)
    bad(origin, "radius_original", format_shortest(s.radius_original), "a disk must fit in silo_width");
  // Kicks land on steps: the period must be a whole number of steps (to 1e-6 of a step).
  double steps_per_kick = s.kick_period / s.dt;
  if (steps_per_kick < 1.0 || std::abs(steps_per_kick - std::round(steps_per_kick)) > 1e-6)
    bad(origin, "kick_period", format_shortest(s.kick_period),
        "it must be a whole multiple of dt = " + format_shortest(s.dt) + " s");
  const double hold_steps = std::round(s.arrest_hold / s.dt);
  if (hold_steps < 1.0 || hold_steps >= std::round(steps_per_kick))
    bad(origin, "arrest_hold", format_shortest(s.arrest_hold),
        "it must be at least dt = " + format_shortest(s.dt) +
            " s and shorter than kick_period = " + format_shortest(s.kick_period) + " s");
  if (s.clog_min_gap >= s.clog_timeout)
    bad(origin, "clog_min_gap", format_shortest(s.clog_min_gap),
        "it must be shorter than clog_timeout = " + format_shortest(s.clog_timeout) + " s");
  // The settled column (packing fraction at most ~0.8) must fit below the top of the container.
  double area_disks = kPi * (static_cast<double>(s.n_original()) * s.radius_original * s.radius_original +
                             static_cast<double>(s.n_added()) * s.radius_added() * s.radius_added());
  double area_box = s.silo_width * s.silo_height + 0.5 * (s.silo_width + s.aperture) * s.hopper_height;
  if (area_disks / 0.8 > 0.9 * area_box)
    bad(origin, "n_total", std::to_string(s.n_total),
        "the disks' packed area " + format_shortest(area_disks / 0.8) +
            " m^2 does not fit in the container (" + format_shortest(area_box) +
            " m^2); raise silo_height or lower n_total");
}

void check_text_file(const std::string& path, const std::string& what, const std::string& dir_hint) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path p(path);
  if (fs::is_directory(p, ec))
    throw InputError(path + " is a directory, not a " + what +
                     (dir_hint.empty() ? "" : "; did you mean " + (p / dir_hint).string() + "?"));
  if (!fs::exists(p, ec)) throw InputError(path + ": cannot open " + what + ": no such file");
  if (!fs::is_regular_file(p, ec))
    throw InputError(path + ": a " + what + " must be a regular file (this is a device, pipe or socket)");
  const auto size = fs::file_size(p, ec);
  if (!ec && size > kMaxTextFileBytes)
    throw InputError(path + ": " + std::to_string(size) + " bytes is too large for a " + what + " (at most " +
                     std::to_string(kMaxTextFileBytes) + " bytes)");
}

Scene load_scene(const std::string& path) {
  check_text_file(path, "scene file", "metadata.toml");
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open scene file");
  std::stringstream text;
  text << in.rdbuf();
  return parse_scene(text.str(), path);
}

Scene parse_scene(const std::string& text, const std::string& path) {
  toml::table tbl;
  try {
    tbl = toml::parse(text, path);
  } catch (const toml::parse_error& e) {
    std::ostringstream o;
    o << path << ":" << e.source().begin.line << ":" << e.source().begin.column
      << ": malformed TOML: " << e.description();
    throw InputError(o.str());
  }
  // A run's metadata.toml keeps the scene in a [scene] table: loading it repeats the run.
  if (auto* inner = tbl["scene"].as_table()) {
    toml::table copy = *inner;  // *inner lives inside tbl: copy before replacing
    tbl = std::move(copy);
  }
  Scene s;
  for (auto&& [k, node] : tbl) {
    std::string key(k.str());
    std::string where = path + ":" + std::to_string(node.source().begin.line);
    const Field* f = find_field(key);
    if (!f) set_field(s, key, "", where);  // throws "unknown key" with the list of keys
    std::string text;
    if (auto v = node.as_floating_point())
      text = format_shortest(v->get());
    else if (auto i = node.as_integer())
      text = std::to_string(i->get());
    else if (auto b = node.as_boolean())
      text = b->get() ? "true" : "false";
    else if (auto t = node.as_string())
      text = t->get();
    else
      throw InputError(where + ": " + key + " must be a number, boolean or string, not a " +
                       std::string(toml::impl::node_type_friendly_names[static_cast<int>(node.type())]));
    bool is_text_field = std::holds_alternative<std::string Scene::*>(f->ptr);
    if (is_text_field != static_cast<bool>(node.as_string()))
      throw InputError(where + ": " + key + " = " + text + " has the wrong type; expected " +
                       (is_text_field ? "a string" : "a number or boolean"));
    set_field(s, key, text, where);
  }
  return s;
}

void apply_overrides(Scene& s, const std::vector<std::string>& assignments) {
  for (const auto& a : assignments) {
    auto eq = a.find('=');
    if (eq == std::string::npos || eq == 0)
      throw InputError("--set " + a + ": expected key=value, for example --set mu=1.0");
    set_field(s, a.substr(0, eq), a.substr(eq + 1), "--set");
  }
}

std::string scene_toml(const Scene& s) {
  std::ostringstream o;
  for (const auto& f : scene_fields()) {
    o << f.key << " = " << field_text(s, f) << "  # ";
    if (f.unit && *f.unit) o << "[" << f.unit << "] ";
    o << f.doc << "\n";
  }
  return o.str();
}

}  // namespace core
