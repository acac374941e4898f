#include "app/services/campaign.h"

#include <algorithm>

#include <toml++/toml.h>

#include <cctype>
#include <climits>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "core/error.h"
#include "core/physics.h"
#include "core/rng.h"

namespace app {

namespace {
namespace fs = std::filesystem;
constexpr const char* kForceRatio = "dipole_force_ratio";

std::string value_text(const toml::node& n, const std::string& where) {
  if (auto v = n.as_floating_point()) {
    char b[40];
    std::snprintf(b, sizeof b, "%.10g", v->get());
    return b;
  }
  if (auto i = n.as_integer()) return std::to_string(i->get());
  if (auto b = n.as_boolean()) return b->get() ? "true" : "false";
  if (auto s = n.as_string()) return s->get();
  throw core::InputError(where + ": expected a number, boolean or string");
}

std::uint64_t hash_text(const std::string& s, std::uint64_t h) {
  for (unsigned char c : s) h = (h ^ c) * 1099511628211ULL;
  return h;
}

// Apply a point's assignments to the base scene; dipole_force_ratio is applied last (it needs size_ratio).
core::Scene apply(const core::Scene& base, const std::vector<Assignment>& set, const std::string& where) {
  core::Scene s = base;
  const std::string* ratio = nullptr;
  for (const auto& [k, v] : set) {
    if (k == kForceRatio)
      ratio = &v;
    else
      core::set_field(s, k, v, where);
  }
  if (ratio) {
    if (!s.shorthand())
      throw core::InputError(where +
                             ": dipole_force_ratio applies to the paper's two-species shorthand; with "
                             "[[species]] set species.NAME.dipole (A*m^2)");
    char* end = nullptr;
    double r = std::strtod(ratio->c_str(), &end);
    if (ratio->empty() || *end || !(r >= 0) || !std::isfinite(r))
      throw core::InputError(where + ": dipole_force_ratio = " + *ratio + " must be a number >= 0");
    s.mu = core::mu_for_force_ratio(s, r);
  }
  core::validate(s);
  return s;
}
}  // namespace

std::uint64_t Campaign::realization_seed(size_t p, int k) const {
  std::uint64_t h = hash_text(points[p].label, 1469598103934665603ULL ^ seed);
  std::uint64_t x = h + static_cast<std::uint64_t>(k) * 0x9e3779b97f4a7c15ULL;
  return core::splitmix64(x) >> 1;  // 63 bits: fits any signed reader too
}

std::string Campaign::run_dir(size_t p, int k) const {
  char b[64];
  std::snprintf(b, sizeof b, "p%03zu/r%03d", p, k);
  return b;
}

Campaign load_campaign(const std::string& path) {
  core::check_text_file(path, "campaign file", "campaign.toml");
  std::ifstream in(path);
  if (!in) throw core::InputError(path + ": cannot open campaign file");
  std::stringstream ss;
  ss << in.rdbuf();
  return parse_campaign(ss.str(), path);
}

// The campaign's points as sets of key = value: the [grid]'s Cartesian product (keys in file order), then
// each of [[points]].
static std::vector<std::vector<Assignment>> point_sets(const toml::table& t, const std::string& path) {
  std::vector<std::pair<std::string, std::vector<std::string>>> axes;
  if (auto* grid = t["grid"].as_table()) {
    for (auto&& [k, v] : *grid) {
      std::string key(k.str()), where = path + ": grid." + key;
      // Species keys (species.NAME.KEY, quoted in TOML) are checked when the points are applied.
      if (key != kForceRatio && !core::find_field(key) && key.rfind("species.", 0) != 0) {
        core::Scene probe;
        core::set_field(probe, key, "", where);  // throws "unknown key" with the list of keys
      }
      if (key == "seed" || key == "duration")
        throw core::InputError(where + ": set it at the top of the campaign");
      auto* arr = v.as_array();
      if (!arr || arr->empty()) throw core::InputError(where + " must be a non-empty list, e.g. [0.4, 0.6]");
      std::vector<std::string> values;
      for (auto&& e : *arr) values.push_back(value_text(e, where));
      axes.emplace_back(key, values);
    }
  }
  std::vector<std::vector<Assignment>> sets;
  if (!axes.empty()) {
    sets.push_back({});
    for (const auto& [key, values] : axes) {
      if (sets.size() * values.size() > 10000)
        throw core::InputError(path + ": the grid has more than 10000 points; at most 10000");
      std::vector<std::vector<Assignment>> next;
      for (const auto& s : sets)
        for (const auto& v : values) {
          auto n = s;
          n.emplace_back(key, v);
          next.push_back(n);
        }
      sets.swap(next);
    }
  }
  if (auto* pts = t["points"].as_array()) {
    int i = 0;
    for (auto&& e : *pts) {
      auto* tbl = e.as_table();
      std::string where = path + ": points[" + std::to_string(i++) + "]";
      if (!tbl || tbl->empty()) throw core::InputError(where + " must be a table of scene keys");
      std::vector<Assignment> s;
      for (auto&& [k, v] : *tbl) s.emplace_back(std::string(k.str()), value_text(v, where));
      sets.push_back(s);
    }
  }
  return sets;
}

Campaign parse_campaign(const std::string& text, const std::string& path) {
  Campaign c;
  c.path = path;
  c.text = text;
  toml::table t;
  try {
    t = toml::parse(c.text, path);
  } catch (const toml::parse_error& e) {
    throw core::InputError(path + ":" + std::to_string(e.source().begin.line) +
                           ": malformed TOML: " + std::string(e.description()));
  }
  static const std::set<std::string> known = {"name",     "scene", "seed",   "realizations",
                                              "duration", "grid",  "points", "trajectory_fps"};
  for (auto&& [k, v] : t)
    if (!known.count(std::string(k.str())))
      throw core::InputError(
          path + ": unknown key '" + std::string(k.str()) +
          "'; known keys: name, scene, seed, realizations, duration, trajectory_fps, grid, "
          "points");
  c.name = t["name"].value_or(std::string(fs::path(path).stem()));
  for (char ch : c.name)
    if (!(std::isalnum(static_cast<unsigned char>(ch)) || ch == '-' || ch == '_'))
      throw core::InputError(path + ": name = \"" + c.name +
                             "\" may hold only letters, digits, - and _ (it names a directory)");
  auto scene_rel = t["scene"].value<std::string>();
  if (!scene_rel) throw core::InputError(path + ": scene = \"...\" (the base scene file) is missing");
  c.scene_path = fs::absolute(fs::path(path).parent_path() / *scene_rel).lexically_normal().string();
  // Whole numbers must be TOML integers: toml++ converts a float like 1e300 to int64 without a range check.
  auto integer = [&](const char* key, std::int64_t fallback, std::int64_t lo, std::int64_t hi) {
    const toml::node* n = t.get(key);
    if (!n) return fallback;
    const auto* i = n->as_integer();
    if (!i || i->get() < lo || i->get() > hi)
      throw core::InputError(path + ": " + key + " must be a whole number from " + std::to_string(lo) +
                             " to " + std::to_string(hi));
    return i->get();
  };
  c.seed = static_cast<std::uint64_t>(integer("seed", 1, 0, INT64_MAX));
  c.realizations = static_cast<int>(integer("realizations", 0, 1, 100000));
  const core::Scene base = core::load_scene(c.scene_path);
  c.duration = base.duration;
  if (const toml::node* n = t.get("duration")) {
    if (auto f = n->as_floating_point())
      c.duration = f->get();
    else if (auto i = n->as_integer())
      c.duration = static_cast<double>(i->get());
    else
      throw core::InputError(path + ": duration must be a number of seconds");
  }
  if (!(c.duration <= 1e6)) throw core::InputError(path + ": duration must be at most 1e6 s");
  if (!(c.duration > 0)) throw core::InputError(path + ": duration must be > 0 s");
  if (const toml::node* n = t.get("trajectory_fps")) {
    const auto f = n->value<double>();
    if (!f || !(*f > 0 && *f <= 1000))
      throw core::InputError(path +
                             ": trajectory_fps must be a number of frames per second in (0, 1000] (each "
                             "realization keeps a trajectory at this rate; leave it out for none)");
    c.trajectory_fps = *f;
  }

  std::vector<std::vector<Assignment>> sets = point_sets(t, path);
  if (sets.empty()) throw core::InputError(path + ": the grid is empty: give [grid] lists or [[points]]");
  if (sets.size() > 10000)
    throw core::InputError(path + ": the grid has " + std::to_string(sets.size()) + " points; at most 10000");

  std::set<std::string> seen;
  for (const auto& s : sets) {
    CampaignPoint p;
    p.set = s;
    for (const auto& [k, v] : s) p.label += (p.label.empty() ? "" : ",") + k + "=" + v;
    p.scene = apply(base, s, path + ": point " + p.label);
    p.scene.duration = c.duration;
    // Two points are duplicates when they give the same scene, however they were written.
    std::string fingerprint = core::scene_toml(p.scene);
    if (!seen.insert(fingerprint).second)
      throw core::InputError(path + ": point " + p.label + " duplicates an earlier point (same scene)");
    c.points.push_back(std::move(p));
  }
  return c;
}

std::vector<std::string> Campaign::extra_point_keys() const {
  std::vector<std::string> keys;
  for (const auto& p : points)
    for (const auto& [k, v] : p.set) {
      if (k == "size_ratio" || k == "chi" || k == "mu" || k == "kick_impulse_max" || k == kForceRatio)
        continue;
      if (std::find(keys.begin(), keys.end(), k) == keys.end()) keys.push_back(k);
    }
  return keys;
}

}  // namespace app
