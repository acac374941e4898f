// Scenes as data: [[species]] tables, containers, obstacles and drives, parsed, resolved and refused with
// FILE:LINE, the key, the value and what is allowed.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "core/physics.h"
#include "core/scene.h"
#include "core/setup.h"
#include "io/metadata.h"

using Catch::Matchers::Contains;

namespace {
std::string write_temp(const std::string& name, const std::string& text) {
  auto p = std::filesystem::temp_directory_path() / ("siloscope_species_" + name);
  std::ofstream(p) << text;
  return p.string();
}
template <class F>
std::string error_of(F f) {
  try {
    f();
  } catch (const core::InputError& e) {
    return e.what();
  }
  return "(no error)";
}
// The error of validating the scene file with `text`, named NAME.toml.
std::string scene_error(const std::string& name, const std::string& text) {
  const std::string p = write_temp(name + ".toml", text);
  return error_of([&] { core::validate(core::load_scene(p)); });
}
const char* kTwo =
    "container = \"flat\"\nsilo_width = 1.2\nsilo_height = 3.5\naperture = 0.35\n"
    "[[species]]\nname = \"big\"\ncount = 100\nradius = 0.05\n"
    "[[species]]\nname = \"small\"\ncount = 50\nsize = \"uniform\"\nradius_min = 0.02\nradius_max = 0.03\n"
    "sides = 5\ndipole = 0.1\ncolor = \"#2a9d8f\"\n";
}  // namespace

TEST_CASE("the shorthand resolves to the paper's two species", "[scene][species]") {
  const core::Setup st = core::resolve(core::Scene{});
  REQUIRE(st.species.size() == 2);
  CHECK(st.shorthand);
  CHECK(st.species[0].name == "original");
  CHECK(st.species[0].count == 150);
  CHECK(st.species[1].name == "added");
  CHECK(st.species[1].count == 100);
  CHECK(st.species[1].first_id == 150);
  CHECK(st.species[1].radius == Approx(0.026));
  CHECK(st.species[1].dipole == 0.0);
  CHECK(st.reference_radius == 0.065);
  CHECK(st.geo.hopper_height == 1.36);
  CHECK(st.gravity.x == 0.0);
  CHECK(st.gravity.y == -9.8);
  CHECK_FALSE(st.drive.vibrating());
  CHECK(st.clog_rule);
}

TEST_CASE("species tables parse, resolve and round-trip through a run's metadata", "[scene][species]") {
  const core::Scene s = core::parse_scene(kTwo, "two.toml");
  core::validate(s);
  const core::Setup st = core::resolve(s);
  REQUIRE(st.species.size() == 2);
  CHECK_FALSE(st.shorthand);
  CHECK(st.n_total == 150);
  CHECK(st.species[1].first_id == 100);
  CHECK(st.species[1].law == core::SizeLaw::Uniform);
  CHECK(st.species[1].sides == 5);
  CHECK(st.species[1].has_color);
  CHECK(st.species[1].color[0] == Approx(0x2a / 255.0));
  CHECK(st.species[1].density == s.density);  // inherited
  // A pentagon of circumradius R has the area of the disk of radius r: (5/2) R^2 sin(72 deg) = pi r^2.
  const double R = st.species[1].extent_factor();
  CHECK(2.5 * R * R * std::sin(2 * M_PI / 5) == Approx(M_PI).epsilon(1e-12));
  CHECK(st.geo.kind == core::ContainerKind::Flat);
  CHECK(st.geo.hopper_height == 0.0);
  CHECK(st.reference_radius == Approx(0.05));
  // Through a metadata file and back: every key, species included, the same.
  io::RunInfo info{"test", {}, {}, {}};
  const core::Scene back =
      core::load_scene(write_temp("meta.toml", io::metadata_toml(core::compile(s), info)));
  CHECK(core::scene_values(back) == core::scene_values(s));
  // --set reaches a species' key.
  core::Scene t = s;
  core::apply_overrides(t, {"species.small.sides=0", "species.big.count=120"});
  CHECK(t.species[1].sides == 0);
  CHECK(core::resolve(t).n_total == 170);
  CHECK_THAT(error_of([&] { core::apply_overrides(t, {"species.tiny.radius=1"}); }),
             Contains("no species named 'tiny'") && Contains("big, small"));
  CHECK_THAT(error_of([&] { core::apply_overrides(t, {"species.big.colour=1"}); }),
             Contains("unknown species key 'colour'"));
  CHECK_THAT(error_of([&] { core::apply_overrides(t, {"size_ratio=0.5"}); }),
             Contains("two-species shorthand"));
}

TEST_CASE("fractions divide n_total by largest remainders and must sum to 1", "[scene][species]") {
  core::Scene s = core::parse_scene(
      "n_total = 10\n[[species]]\nname = \"a\"\nfraction = 0.35\nradius = 0.05\n"
      "[[species]]\nname = \"b\"\nfraction = 0.35\nradius = 0.04\n[[species]]\nname = \"c\"\nfraction = 0.3\n"
      "radius = 0.03\n",
      "f.toml");
  const core::Setup st = core::resolve(s);
  CHECK(st.species[0].count + st.species[1].count + st.species[2].count == 10);
  CHECK(st.species[2].count == 3);
  const std::string e = scene_error(
      "sum",
      "n_total = 10\n[[species]]\nname = \"a\"\nfraction = 0.5\nradius = 0.05\n[[species]]\nname = "
      "\"b\"\nfraction = 0.4\nradius = 0.04\n");
  CHECK_THAT(e, Contains("sum.toml:4") && Contains("0.5 + 0.4") && Contains("not 1"));
  CHECK_THAT(scene_error("mixed",
                         "[[species]]\nname = \"a\"\ncount = 5\nradius = 0.05\n[[species]]\nname = "
                         "\"b\"\nfraction = 0.5\nradius = 0.04\n"),
             Contains("every species gives a count, or every species a fraction"));
}

TEST_CASE("bad species: one clear line naming FILE:LINE, the key, the value and what is allowed",
          "[scene][species]") {
  CHECK_THAT(scene_error("sides", "[[species]]\nname = \"a\"\ncount = 5\nradius = 0.05\nsides = 2\n"),
             Contains("sides.toml:5") && Contains("species.a.sides = 2") && Contains("3 to 8"));
  CHECK_THAT(scene_error("sides9", "[[species]]\nname = \"a\"\ncount = 5\nradius = 0.05\nsides = 9\n"),
             Contains("sides9.toml:5") && Contains("[0, 8]"));
  CHECK_THAT(scene_error("negative",
                         "[[species]]\nname = \"a\"\ncount = 5\nsize = \"uniform\"\n"
                         "radius_min = -0.01\nradius_max = 0.05\n"),
             Contains("negative.toml:5") && Contains("non-positive radii"));
  CHECK_THAT(scene_error("lognormal",
                         "[[species]]\nname = \"a\"\ncount = 5\nsize = \"lognormal\"\n"
                         "radius = 0.05\n"),
             Contains("spread") && Contains("lognormal"));
  CHECK_THAT(scene_error("name", "[[species]]\nname = \"Big One\"\ncount = 5\nradius = 0.05\n"),
             Contains("name.toml:2") && Contains("lower-case"));
  CHECK_THAT(scene_error("twice",
                         "[[species]]\nname = \"a\"\ncount = 5\nradius = 0.05\n"
                         "[[species]]\nname = \"a\"\ncount = 5\nradius = 0.05\n"),
             Contains("twice.toml:6") && Contains("unique"));
  CHECK_THAT(scene_error("short", "size_ratio = 0.5\n[[species]]\nname = \"a\"\ncount = 5\nradius = 0.05\n"),
             Contains("short.toml:1") && Contains("shorthand"));
  CHECK_THAT(scene_error("color", "[[species]]\nname = \"a\"\ncount = 5\nradius = 0.05\ncolor = \"red\"\n"),
             Contains("color.toml:5") && Contains("#rrggbb"));
  CHECK_THAT(scene_error("full", "[[species]]\nname = \"a\"\ncount = 5000\nradius = 0.06\n"),
             Contains("full.toml:2") && Contains("cannot hold the grains"));
}

TEST_CASE("containers, obstacles and drives are checked against each other", "[scene][species]") {
  // A range error names the file and line.
  CHECK_THAT(scene_error("range", "# a comment\nchi = 2.0\n"),
             Contains("range.toml:2") && Contains("chi = 2.0 is not allowed") && Contains("[0, 1]"));
  // An obstacle that closes the outlet, one inside a wall, one through the top.
  const std::string flat = "container = \"flat\"\nobstacle = \"disk\"\nobstacle_size = 0.3\n";
  CHECK_THAT(scene_error("low", flat + "obstacle_height = 0.2\n"),
             Contains("low.toml:4") && Contains("closing it") && Contains("lowest height"));
  CHECK_THAT(scene_error("wide",
                         "container = \"flat\"\nobstacle = \"bar\"\nobstacle_size = 0.9\n"
                         "obstacle_thickness = 0.05\nobstacle_height = 1.0\n"),
             Contains("wide.toml:3") && Contains("wall") && Contains("at most"));
  CHECK_THAT(scene_error("bar",
                         "container = \"flat\"\nobstacle = \"bar\"\nobstacle_size = 0.2\n"
                         "obstacle_height = 1.0\n"),
             Contains("obstacle_thickness"));
  // The outlet within the floor; a flat silo has no hopper angle.
  CHECK_THAT(scene_error("off", "outlet_x = 0.4\n"), Contains("off.toml:1") && Contains("outlet_x"));
  CHECK_THAT(scene_error("angle", "container = \"flat\"\nhopper_angle = 30.0\n"),
             Contains("angle.toml:2") && Contains("flat silo has no hopper"));
  // Vibration: amplitude or Gamma, with a frequency the time step resolves.
  CHECK_THAT(
      scene_error("both", "vibration_amplitude = 0.01\nvibration_gamma = 2.0\nvibration_frequency = 10.0\n"),
      Contains("both.toml:2") && Contains("not both"));
  CHECK_THAT(scene_error("nof", "vibration_gamma = 2.0\n"),
             Contains("vibration_frequency") && Contains("> 0 Hz"));
  CHECK_THAT(scene_error("fast", "vibration_gamma = 2.0\nvibration_frequency = 100.0\n"),
             Contains("fast.toml:2") && Contains("20 time steps"));
  // The rule off: clog_min_gap is then free.
  core::Scene s = core::parse_scene("clog_timeout = 0.0\nclog_min_gap = 2.0\n", "off.toml");
  core::validate(s);
  CHECK_FALSE(core::resolve(s).clog_rule);
}

TEST_CASE("angles, Gamma and tilt resolve to the geometry, amplitude and gravity they mean",
          "[scene][species]") {
  core::Scene s;
  core::apply_overrides(s, {"hopper_angle=30"});
  core::Setup st = core::resolve(s);
  CHECK(st.geo.hopper_height == Approx((0.5 - 0.1495) / std::tan(30 * M_PI / 180)));
  CHECK(st.geo.wall_angle_from_vertical() * 180 / M_PI == Approx(30).epsilon(1e-9));
  s = {};
  core::apply_overrides(s, {"vibration_gamma=2", "vibration_frequency=10", "tilt=30"});
  st = core::resolve(s);
  CHECK(st.drive.amplitude == Approx(2 * 9.8 / std::pow(2 * M_PI * 10, 2)).epsilon(1e-12));
  CHECK(st.gravity.x == Approx(-9.8 * 0.5).epsilon(1e-12));
  CHECK(st.gravity.y == Approx(-9.8 * std::sqrt(3) / 2).epsilon(1e-12));
  // The container's motion: A sin(omega t), nothing before the opening.
  CHECK(core::container_offset(st, -1).y == 0.0);
  CHECK(core::container_offset(st, 0.025).y ==
        Approx(st.drive.amplitude).epsilon(1e-12));  // a quarter period
  CHECK(core::container_offset(st, 0.05).y == Approx(0).margin(1e-15));
}
