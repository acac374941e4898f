#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include <toml++/toml.h>

#include "core/error.h"
#include "core/scene.h"
#include "core/scene_history.h"
#include "io/metadata.h"

using Catch::Matchers::Contains;

namespace {
std::string scene_dir() {
  return std::string(SILOSCOPE_SOURCE_DIR) + "/assets/scenes/";
}
std::string write_temp(const std::string& name, const std::string& text) {
  auto p = std::filesystem::temp_directory_path() / ("siloscope_test_" + name);
  std::ofstream(p) << text;
  return p.string();
}
// The message of the InputError that `f` throws.
template <class F>
std::string error_of(F f) {
  try {
    f();
  } catch (const core::InputError& e) {
    return e.what();
  }
  return "(no error)";
}
}  // namespace

TEST_CASE("paper.toml holds exactly the built-in defaults of model.md", "[sim][scene]") {
  core::Scene file = core::load_scene(scene_dir() + "paper.toml");
  core::Scene def;
  for (const auto& f : core::scene_fields()) CHECK(core::field_text(file, f) == core::field_text(def, f));
  CHECK(def.n_added() == 100);
  CHECK(def.n_original() == 150);
  CHECK(def.radius_added() == Approx(0.026));
  core::validate(file);
}

TEST_CASE("pure.toml is the chi = 0 system", "[sim][scene]") {
  core::Scene s = core::load_scene(scene_dir() + "pure.toml");
  CHECK(s.n_added() == 0);
  CHECK(s.n_original() == 250);
  core::validate(s);
}

TEST_CASE("validation names the key, the value and the allowed range", "[sim][scene]") {
  core::Scene s;
  s.size_ratio = 0.1;
  CHECK_THAT(error_of([&] { core::validate(s); }),
             Contains("size_ratio") && Contains("0.1") && Contains("[0.2, 1"));
  s = {};
  s.size_ratio = 1.5;
  CHECK_THAT(error_of([&] { core::validate(s); }), Contains("size_ratio"));
  s = {};
  s.chi = -0.1;
  CHECK_THAT(error_of([&] { core::validate(s); }), Contains("chi") && Contains("-0.1"));
  s = {};
  s.chi = 1.2;
  CHECK_THAT(error_of([&] { core::validate(s); }), Contains("chi"));
  s = {};
  s.duration = -1;
  CHECK_THAT(error_of([&] { core::validate(s); }), Contains("duration") && Contains("-1"));
  s = {};
  s.aperture = 0.04;  // narrower than an added disk (diameter 0.052 m)
  CHECK_THAT(error_of([&] { core::validate(s); }),
             Contains("aperture") && Contains("wider than every grain"));
  s = {};
  s.kick_period = 0.1005;  // not a whole number of 1 ms steps
  CHECK_THAT(error_of([&] { core::validate(s); }), Contains("kick_period"));
  s = {};
  s.arch_method = "magic";
  CHECK_THAT(error_of([&] { core::validate(s); }),
             Contains("arch_method") && Contains("contact_path|visible"));
  s = {};
  s.n_total = 2000;  // cannot fit
  CHECK_THAT(error_of([&] { core::validate(s); }), Contains("n_total"));
}

TEST_CASE("scene files: unknown keys, wrong types and malformed TOML are errors with a line",
          "[sim][scene]") {
  auto p = write_temp("unknown.toml", "chi = 0.4\nmagnetism = 3\n");
  CHECK_THAT(error_of([&] { core::load_scene(p); }), Contains("unknown key 'magnetism'") && Contains(":2"));
  p = write_temp("type.toml", "chi = \"lots\"\n");
  CHECK_THAT(error_of([&] { core::load_scene(p); }), Contains("chi") && Contains("wrong type"));
  p = write_temp("malformed.toml", "chi = = 0.4\n");
  CHECK_THAT(error_of([&] { core::load_scene(p); }), Contains("malformed TOML") && Contains(":1:"));
  CHECK_THAT(error_of([&] { core::load_scene("/nonexistent/scene.toml"); }), Contains("cannot open"));
}

TEST_CASE("command-line overrides edit the same fields", "[sim][scene]") {
  core::Scene s;
  core::apply_overrides(s,
                        {"mu=1.5", "size_ratio=0.6", "global_kick=false", "arch_method=visible", "seed=42"});
  CHECK(s.mu == 1.5);
  CHECK(s.size_ratio == 0.6);
  CHECK_FALSE(s.global_kick);
  CHECK(s.arch_method == "visible");
  CHECK(s.seed == 42);
  CHECK_THAT(error_of([&] { core::apply_overrides(s, {"mu"}); }), Contains("key=value"));
  CHECK_THAT(error_of([&] { core::apply_overrides(s, {"mu=abc"}); }), Contains("mu") && Contains("abc"));
  CHECK_THAT(error_of([&] { core::apply_overrides(s, {"nope=1"}); }), Contains("unknown key 'nope'"));
  CHECK_THAT(error_of([&] { core::apply_overrides(s, {"seed=-3"}); }), Contains("seed"));
}

TEST_CASE("a run's metadata file loads back as the same scene", "[sim][scene]") {
  core::Scene s;
  core::apply_overrides(s, {"mu=0.7", "size_ratio=0.25", "seed=99", "dt=0.0005", "arch_method=visible"});
  io::RunInfo info{"siloscope run test", {{"steps", 10}}, {}, {}};
  auto p = write_temp("metadata.toml", io::metadata_toml(core::compile(s), info));
  core::Scene back = core::load_scene(p);
  for (const auto& f : core::scene_fields()) CHECK(core::field_text(back, f) == core::field_text(s, f));
}

TEST_CASE(
    "metadata facts keep their types: integers, floats that stay floats, booleans, escaped strings, lists",
    "[scene]") {
  core::Scene s;
  io::RunInfo info{"siloscope run \"quoted\" \\ path\nnext",
                   {{"steps", 150000},
                    {"speed", 1.0, 6},
                    {"ratio", 2.5},
                    {"interrupted", false},
                    {"label", "mu = 2.2 \"strong\""},
                    {"labels", std::vector<std::string>{"a", "b\"c"}},
                    {"never", std::numeric_limits<double>::infinity()}},
                   {{"ballistic", true}},
                   {}};
  const toml::table t = toml::parse(io::metadata_toml(core::compile(s), info));
  CHECK(t["run"]["steps"].is_integer());
  CHECK(t["run"]["steps"].value<std::int64_t>() == 150000);
  CHECK(t["run"]["speed"].is_floating_point());  // 1.0, never the integer 1
  CHECK(t["run"]["ratio"].value<double>() == 2.5);
  CHECK(t["run"]["interrupted"].is_boolean());
  CHECK(t["run"]["label"].value<std::string>() == "mu = 2.2 \"strong\"");
  REQUIRE(t["run"]["labels"].is_array());
  CHECK(t["run"]["labels"][1].value<std::string>() == "b\"c");
  CHECK(std::isinf(t["run"]["never"].value<double>().value_or(0)));
  CHECK(t["health"]["ballistic"].value<bool>() == true);
  CHECK(t["siloscope"]["command"].value<std::string>() == info.command);
  CHECK(t["derived"]["n_original"].is_integer());
  CHECK(t["derived"]["mass_added_kg"].is_floating_point());
}

TEST_CASE(
    "retired keys: a run's stored scene from an earlier siloscope opens, a new scene file is told the "
    "replacement",
    "[scene][history]") {
  // The table itself: a retired key is no current key, and a renamed one names a current key.
  for (const core::RetiredKey& r : core::retired_keys()) {
    INFO(r.key);
    core::Scene s;
    CHECK_THROWS_AS(core::set_field(s, r.key, "1", "test"), core::InputError);
    if (r.renamed) CHECK(core::find_retired(r.renamed) == nullptr);
  }
  // A run's metadata (the scene in a [scene] table) written before arrest_speed was retired: dropped, said.
  const core::Scene old = core::parse_scene("[scene]\narrest_speed = 0.01\nmu = 0.5\n", "old/metadata.toml");
  CHECK(old.mu == 0.5);
  REQUIRE(old.history.size() == 1);
  CHECK_THAT(old.history[0], Contains("arrest_speed") && Contains("dropped") && Contains("arrest_hold"));
  // The same key in a scene file a person writes, or on the command line: refused, naming what replaced it.
  CHECK_THROWS_WITH(core::parse_scene("arrest_speed = 0.01\n", "mine.toml"),
                    Contains("mine.toml:1") && Contains("arrest_speed") && Contains("arrest_hold") &&
                        Contains("earlier siloscope"));
  core::Scene s;
  CHECK_THROWS_WITH(core::set_field(s, "arrest_speed", "0.01", "--set"),
                    Contains("--set") && Contains("arrest_shift"));
  // A current scene's history is empty.
  CHECK(core::parse_scene("[scene]\nmu = 0.5\n", "new/metadata.toml").history.empty());
}
