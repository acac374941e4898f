// The scene file: parsing TOML into core::Scene, overrides, validation of each field against its table
// (scene_fields.cpp), and writing a scene back as TOML. Over 400 lines because reading, validating and
// writing one format belong together: a field's text form is parsed and printed by the same templates here.
#include "core/scene.h"
#include "core/model.h"
#include "core/scene_history.h"

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
#include "core/setup.h"

namespace core {

namespace {

std::string range_text(double min, double max) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "[%.10g, %.10g]", min, max);
  return buf;
}

std::string unit_suffix(const char* unit) {
  std::string u = unit ? unit : "";
  return (u.empty() || u == "1") ? "" : " " + u;
}

[[noreturn]] void bad(const std::string& origin, const std::string& key, const std::string& value,
                      const std::string& allowed) {
  throw InputError(origin + ": " + key + " = " + value + " is not allowed; " + allowed);
}

bool in_choices(const char* choices, const std::string& v) {
  std::stringstream ss(choices ? choices : "");
  for (std::string c; std::getline(ss, c, '|');)
    if (c == v) return true;
  return false;
}

// Parse `value` into `v` (a number, whole number, boolean or text), naming `key` and `origin` on failure.
template <class T>
void parse_value(T& v, const std::string& key, const std::string& value, const std::string& origin,
                 double min, double max) {
  if constexpr (std::is_same_v<T, double> || std::is_same_v<T, std::optional<double>>) {
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
      bad(origin, key, value, "expected a whole number in " + range_text(min, max));
    // TOML holds signed 64-bit integers: a larger value could be written into metadata.toml but never read
    // back, so the run could not be repeated from its metadata.
    if constexpr (std::is_unsigned_v<T>)
      if (static_cast<unsigned long long>(i) > 9223372036854775807ULL)
        bad(origin, key, value,
            "expected a whole number from 0 to 9223372036854775807 (2^63 - 1: what TOML can "
            "hold, so the run's metadata.toml repeats it)");
    v = i;
  }
}

template <class T>
std::string value_text(const T& v) {
  if constexpr (std::is_same_v<T, double>)
    return format_shortest(v);
  else if constexpr (std::is_same_v<T, std::optional<double>>)
    return v ? format_shortest(*v) : std::string();
  else if constexpr (std::is_same_v<T, bool>)
    return v ? "true" : "false";
  else if constexpr (std::is_same_v<T, std::string>)
    return toml_string(v);
  else
    return std::to_string(v);
}

// A species name: a lower-case letter, then lower-case letters, digits or '_', at most 32 characters (it
// names columns, legends and command-line keys).
bool valid_species_name(const std::string& n) {
  if (n.empty() || n.size() > 32 || !(n[0] >= 'a' && n[0] <= 'z')) return false;
  for (char c : n)
    if (!((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_')) return false;
  return true;
}

SpeciesSpec* species_named(Scene& s, const std::string& name) {
  for (auto& sp : s.species)
    if (sp.name == name) return &sp;
  return nullptr;
}
}  // namespace

std::int64_t Scene::n_added() const {
  return std::llround(chi * static_cast<double>(n_total));
}

std::string Scene::where(const std::string& key) const {
  auto it = origin.find(key);
  return it == origin.end() ? std::string("scene") : it->second;
}

const Field* find_field(const std::string& key) {
  for (const auto& f : scene_fields())
    if (key == f.key) return &f;
  return nullptr;
}

const SpeciesField* find_species_field(const std::string& key) {
  for (const auto& f : species_fields())
    if (key == f.key) return &f;
  return nullptr;
}

bool is_shorthand_key(const std::string& key) {
  return key == "radius_original" || key == "size_ratio" || key == "chi" || key == "mu";
}

std::string field_text(const Scene& s, const Field& f) {
  return std::visit([&](auto ptr) -> std::string { return value_text(s.*ptr); }, f.ptr);
}

std::string species_field_text(const SpeciesSpec& sp, const SpeciesField& f) {
  return std::visit([&](auto ptr) -> std::string { return value_text(sp.*ptr); }, f.ptr);
}

std::map<std::string, std::string> scene_values(const Scene& s) {
  std::map<std::string, std::string> out;
  for (const auto& f : scene_fields()) {
    if (!s.shorthand() && is_shorthand_key(f.key)) continue;  // not part of a scene with [[species]]
    out[f.key] = field_text(s, f);
  }
  // Species that give counts make n_total their sum (as scene_toml writes it).
  if (!s.species.empty() && s.species.front().count > 0) {
    std::int64_t n = 0;
    for (const auto& sp : s.species) n += sp.count;
    out["n_total"] = std::to_string(n);
  }
  for (const auto& sp : s.species)
    for (const auto& f : species_fields())
      out["species." + sp.name + "." + f.key] = species_field_text(sp, f);
  return out;
}

namespace {
void set_species_field(Scene& s, const std::string& key, const std::string& value,
                       const std::string& origin) {
  // species.NAME.KEY
  const auto dot = key.find('.', 8);
  const std::string name = dot == std::string::npos ? "" : key.substr(8, dot - 8);
  const std::string sub = dot == std::string::npos ? "" : key.substr(dot + 1);
  SpeciesSpec* sp = species_named(s, name);
  if (!sp) {
    std::string names;
    for (const auto& x : s.species) names += (names.empty() ? "" : ", ") + x.name;
    throw InputError(origin + ": " + key + ": no species named '" + name + "'" +
                     (names.empty()
                          ? "; this scene has no [[species]] tables (it uses the two-species shorthand)"
                          : "; the species are " + names));
  }
  const SpeciesField* f = find_species_field(sub);
  if (!f || sub == "name") {
    std::string keys;
    for (const auto& g : species_fields())
      if (std::string(g.key) != "name") keys += std::string(keys.empty() ? "" : ", ") + g.key;
    throw InputError(origin + ": " + key + ": unknown species key '" + sub + "'; species keys: " + keys);
  }
  std::visit([&](auto ptr) { parse_value(sp->*ptr, key, value, origin, f->min, f->max); }, f->ptr);
  s.origin[key] = origin;
}
}  // namespace

void set_field(Scene& s, const std::string& key, const std::string& value, const std::string& origin) {
  if (key.rfind("species.", 0) == 0) return set_species_field(s, key, value, origin);
  const Field* f = find_field(key);
  if (const RetiredKey* r = f ? nullptr : find_retired(key))
    throw InputError(origin + ": '" + key + "' is a key of an earlier siloscope, retired in " + r->since +
                     ": " +
                     (r->renamed ? std::string("it is now '") + r->renamed + "'" : std::string(r->why)));
  if (!f) {
    std::string keys;
    for (const auto& g : scene_fields()) keys += std::string(keys.empty() ? "" : ", ") + g.key;
    throw InputError(origin + ": unknown key '" + key + "'; known keys: " + keys +
                     ", and species.NAME.KEY for a species' KEY");
  }
  if (!s.shorthand() && is_shorthand_key(key))
    throw InputError(origin + ": " + key +
                     " belongs to the two-species shorthand; this scene lists its grains as [[species]]: set "
                     "species.NAME.radius, species.NAME.count or species.NAME.dipole instead");
  std::visit([&](auto ptr) { parse_value(s.*ptr, key, value, origin, f->min, f->max); }, f->ptr);
  s.origin[key] = origin;
}

// Each field against its own range or choices, naming where it was set.
static void check_fields(const Scene& s) {
  for (const auto& f : scene_fields()) {
    std::visit(
        [&](auto ptr) {
          const auto& v = s.*ptr;
          using T = std::decay_t<decltype(v)>;
          if constexpr (std::is_same_v<T, double> || std::is_same_v<T, std::int64_t>) {
            double d = static_cast<double>(v);
            if (!std::isfinite(d) || d < f.min || d > f.max)
              bad(s.where(f.key), f.key, field_text(s, f),
                  "allowed range is " + range_text(f.min, f.max) + unit_suffix(f.unit));
          } else if constexpr (std::is_same_v<T, std::string>) {
            if (!in_choices(f.choices, v))
              bad(s.where(f.key), f.key, field_text(s, f), std::string("allowed values are ") + f.choices);
          }
        },
        f.ptr);
  }
  if (s.species.size() > kMaxSpecies)
    throw InputError("scene: " + std::to_string(s.species.size()) + " [[species]] tables; at most " +
                     std::to_string(kMaxSpecies));
  for (size_t k = 0; k < s.species.size(); ++k) {
    const SpeciesSpec& sp = s.species[k];
    if (!valid_species_name(sp.name))
      throw InputError(
          s.where("species." + sp.name + ".name") + ": species " + std::to_string(k + 1) +
          ": name = " + toml_string(sp.name) +
          " is not allowed; a lower-case letter, then lower-case letters, digits or _ (at most 32)");
    for (size_t j = 0; j < k; ++j)
      if (s.species[j].name == sp.name)
        throw InputError(s.where("species." + sp.name + ".name") + ": two species are named " +
                         toml_string(sp.name) + "; names must be unique");
    for (const auto& f : species_fields()) {
      const std::string key = "species." + sp.name + "." + f.key;
      std::visit(
          [&](auto ptr) {
            const auto& v = sp.*ptr;
            using T = std::decay_t<decltype(v)>;
            double d = 0;
            bool numeric = true;
            if constexpr (std::is_same_v<T, std::optional<double>>) {
              numeric = v.has_value();
              d = v.value_or(0);
            } else if constexpr (std::is_same_v<T, std::string>) {
              numeric = false;
              if (f.choices && !in_choices(f.choices, v))
                bad(s.where(key), key, species_field_text(sp, f),
                    std::string("allowed values are ") + f.choices);
            } else {
              d = static_cast<double>(v);
            }
            if (numeric && (!std::isfinite(d) || d < f.min || d > f.max))
              bad(s.where(key), key, species_field_text(sp, f),
                  "allowed range is " + range_text(f.min, f.max) + unit_suffix(f.unit));
          },
          f.ptr);
    }
  }
}

void validate(const Scene& s) {
  // The relations between fields: compiling the scene (resolving it) checks them all.
  (void)compile(s);
}

Model compile(const Scene& s) {
  check_fields(s);
  return {s, resolve(s)};
}

std::vector<std::string> ineffective_keys(const Model& m) {
  const Scene& s = m.scene;
  std::vector<std::string> out;
  auto given = [&](const char* key, const std::string& why) {
    const auto it = s.origin.find(key);
    if (it != s.origin.end()) out.push_back(std::string(key) + " (" + it->second + ") does nothing: " + why);
  };
  if (s.obstacle == "none")
    for (const char* k : {"obstacle_size", "obstacle_thickness", "obstacle_height", "obstacle_x"})
      given(k, "obstacle = \"none\" (set obstacle = \"disk\" or \"bar\")");
  else if (s.obstacle == "disk")
    given("obstacle_thickness", "a disk obstacle is as thick as it is wide (obstacle_size)");
  if (!(s.kick_impulse_max > 0))
    for (const char* k : {"kick_period", "global_kick"}) given(k, "kick_impulse_max = 0 (no kicks)");
  if (!(s.vibration_amplitude > 0) && !(s.vibration_gamma > 0))
    for (const char* k : {"vibration_frequency", "vibration_direction"})
      given(k, "the container does not vibrate (vibration_amplitude = vibration_gamma = 0)");
  if (!(s.clog_timeout > 0)) given("arrest_hold", "clog_timeout = 0 (the clog rule is off)");
  if (s.drain) {
    given("reinject_gap", "drain = true (exits are not re-injected)");
    if (!(s.clog_timeout > 0))
      out.push_back(
          "drain = true with clog_timeout = 0: a jam is never declared, so every drain that does "
          "not empty ends \"draining\" (set clog_timeout, e.g. 1 s)");
  }
  // Grains lost to rounding: a species asked for by a fraction (or the shorthand's chi) that has none.
  for (const auto& sp : m.setup.species)
    if (sp.count == 0) {
      const bool shorthand_added = m.setup.shorthand && sp.name == "added";
      if (shorthand_added && !(s.chi > 0)) continue;
      out.push_back("species " + sp.name + " has no grains: " +
                    (shorthand_added ? "chi = " + format_shortest(s.chi) : std::string("its fraction")) +
                    " of n_total = " + std::to_string(s.n_total) +
                    " rounds to 0 (raise n_total or the fraction)");
    }
  return out;
}

void check_text_file(const std::string& path, const std::string& what, const std::string& dir_hint) {
  check_input_file(path, what, kMaxTextFileBytes, dir_hint);
}

void check_input_file(const std::string& path, const std::string& what, std::uintmax_t max_bytes,
                      const std::string& dir_hint) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path p(path);
  if (fs::is_directory(p, ec))
    throw InputError(path + " is a directory, not " + with_article(what) +
                     (dir_hint.empty() ? "" : "; did you mean " + (p / dir_hint).string() + "?"));
  if (!fs::exists(p, ec)) throw InputError(path + ": cannot open " + what + ": no such file");
  if (!fs::is_regular_file(p, ec))
    throw InputError(path + ": " + with_article(what) +
                     " must be a regular file (this is a device, pipe or socket)");
  const auto size = fs::file_size(p, ec);
  if (!ec && size > max_bytes)
    throw InputError(path + ": " + std::to_string(size) + " bytes is too large for a " + what + " (at most " +
                     std::to_string(max_bytes) + " bytes)");
}

Scene load_scene(const std::string& path) {
  check_text_file(path, "scene file", kMetadataFile);
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open scene file");
  std::stringstream text;
  text << in.rdbuf();
  return parse_scene(text.str(), path);
}

namespace {
// A TOML value as the text set_field takes; `is_text` says whether the field wants a string.
std::string node_text(const toml::node& node, const std::string& where, const std::string& key,
                      bool is_text) {
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
  if (is_text != static_cast<bool>(node.as_string()))
    throw InputError(where + ": " + key + " = " + text + " has the wrong type; expected " +
                     (is_text ? "a string" : "a number or boolean"));
  return text;
}

void parse_species(Scene& s, const toml::array& arr, const std::string& path) {
  int k = 0;
  for (auto&& e : arr) {
    ++k;
    const std::string where0 = path + ":" + std::to_string(e.source().begin.line);
    const toml::table* t = e.as_table();
    if (!t) throw InputError(where0 + ": species must be tables ([[species]]), not values");
    SpeciesSpec sp;
    const toml::node* name = t->get("name");
    if (!name || !name->as_string())
      throw InputError(where0 + ": species " + std::to_string(k) + " has no name = \"...\"");
    sp.name = name->as_string()->get();
    if (!valid_species_name(sp.name))
      throw InputError(
          path + ":" + std::to_string(name->source().begin.line) + ": species " + std::to_string(k) +
          ": name = " + toml_string(sp.name) +
          " is not allowed; a lower-case letter, then lower-case letters, digits or _ (at most 32)");
    if (species_named(s, sp.name))
      throw InputError(path + ":" + std::to_string(name->source().begin.line) + ": two species are named " +
                       toml_string(sp.name) + "; names must be unique");
    s.species.push_back(sp);
    s.origin["species." + sp.name + ".name"] = path + ":" + std::to_string(name->source().begin.line);
    for (auto&& [kk, node] : *t) {
      const std::string key(kk.str());
      if (key == "name") continue;
      const std::string where = path + ":" + std::to_string(node.source().begin.line);
      const SpeciesField* f = find_species_field(key);
      if (!f) set_field(s, "species." + sp.name + "." + key, "", where);  // throws with the list of keys
      const bool is_text = std::holds_alternative<std::string SpeciesSpec::*>(f->ptr);
      set_field(s, "species." + sp.name + "." + key, node_text(node, where, key, is_text), where);
    }
  }
}
}  // namespace

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
  // A campaign file given where a scene belongs: say so, not "unknown key 'grid'".
  for (const char* key : {"grid", "points", "realizations"})
    if (tbl.contains(key) && !tbl["scene"].as_table())
      throw InputError(path + " is a campaign file (it has " +
                       (std::string(key) == "grid"     ? "[grid]"
                        : std::string(key) == "points" ? "[[points]]"
                                                       : "realizations") +
                       "), not a scene: run it with `siloscope sweep " + path + "`");
  // A run's metadata.toml keeps the scene in a [scene] table: loading it repeats the run.
  const bool from_run = tbl["scene"].as_table() != nullptr;
  if (auto* inner = tbl["scene"].as_table()) {
    toml::table copy = *inner;  // *inner lives inside tbl: copy before replacing
    tbl = std::move(copy);
  }
  Scene s;
  // Species first: they decide whether the shorthand keys are allowed.
  if (const toml::node* sp = tbl.get("species")) {
    const std::string where = path + ":" + std::to_string(sp->source().begin.line);
    if (!sp->as_array()) throw InputError(where + ": species must be [[species]] tables");
    parse_species(s, *sp->as_array(), path);
  }
  for (auto&& [k, node] : tbl) {
    std::string key(k.str());
    if (key == "species") continue;
    std::string where = path + ":" + std::to_string(node.source().begin.line);
    // A run's stored scene from an earlier siloscope: its retired keys translated or dropped, and said so. A
    // scene file a person wrote is refused by set_field, naming what replaced the key.
    if (const RetiredKey* r = from_run && !find_field(key) ? find_retired(key) : nullptr) {
      s.history.push_back(
          "'" + key + "' (retired in " + r->since + ") " +
          (r->renamed ? std::string("read as '") + r->renamed + "'" : "dropped: " + std::string(r->why)));
      if (!r->renamed) continue;
      key = r->renamed;
    }
    const Field* f = find_field(key);
    if (!f) set_field(s, key, "", where);  // throws "unknown key" with the list of keys
    const bool is_text = std::holds_alternative<std::string Scene::*>(f->ptr);
    set_field(s, key, node_text(node, where, key, is_text), where);
  }
  return s;
}

bool scene_is_empty_file(const std::string& path) {
  try {
    return toml::parse_file(path).empty();
  } catch (const toml::parse_error&) {
    return false;
  }
}

void apply_overrides(Scene& s, const std::vector<std::string>& assignments) {
  for (const auto& a : assignments) {
    auto eq = a.find('=');
    if (eq == std::string::npos || eq == 0)
      throw InputError("--set " + a + ": expected key=value, for example --set mu=1.0");
    set_field(s, a.substr(0, eq), a.substr(eq + 1), "--set");
  }
}

std::string scene_toml(const Scene& s, const std::string& table) {
  std::ostringstream o;
  const bool counts = !s.species.empty() && s.species.front().count > 0;
  for (const auto& f : scene_fields()) {
    if (!s.shorthand() && is_shorthand_key(f.key)) continue;
    std::string value = field_text(s, f);
    if (counts && std::string(f.key) == "n_total") {
      std::int64_t n = 0;
      for (const auto& sp : s.species) n += sp.count;
      value = std::to_string(n);
    }
    o << f.key << " = " << value << "  # ";
    if (f.unit && *f.unit) o << "[" << f.unit << "] ";
    o << f.doc << "\n";
  }
  for (const auto& sp : s.species) {
    o << "\n[[" << (table.empty() ? "" : table + ".") << "species]]\n";
    for (const auto& f : species_fields()) {
      const std::string v = species_field_text(sp, f);
      if (v.empty()) continue;  // an absent optional: the scene's value applies
      o << f.key << " = " << v << "\n";
    }
  }
  return o.str();
}

}  // namespace core
