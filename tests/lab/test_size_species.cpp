// A grain's species from its size alone (lab/size_species.h): the likeliest species under the scene's laws.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "core/model.h"
#include "core/scene.h"
#include "lab/size_species.h"

namespace {

std::vector<core::SpeciesDef> preset_species(const std::string& name) {
  return core::compile(
             core::load_scene(std::string(SILOSCOPE_SOURCE_DIR) + "/assets/scenes/" + name + ".toml"))
      .setup.species;
}

int index_of(const std::vector<core::SpeciesDef>& s, const std::string& name) {
  for (size_t k = 0; k < s.size(); ++k)
    if (s[k].name == name) return static_cast<int>(k);
  FAIL("no species " << name);
  return -1;
}

}  // namespace

TEST_CASE("size species: a lognormal's tail past a uniform interval is its own, not the nearer group's",
          "[lab]") {
  const std::vector<core::SpeciesDef> s = preset_species("three-species");
  const int large = index_of(s, "large"), medium = index_of(s, "medium"), small = index_of(s, "small");
  const lab::SizeSpecies exact(s, 0, 0.005);
  CHECK(exact.species(0.065) == large);
  CHECK(exact.species(0.045) == medium);
  CHECK(exact.species(0.026) == small);
  CHECK(exact.species(0.029) == small);    // inside small's interval, where it is 20 times as likely
  CHECK(exact.species(0.0315) == medium);  // past small's end (0.030 m): only medium grows this large
  // The same in trackpy's units: a radius of gyration in pixels (r / sqrt 2 at 0.004 m a pixel).
  const double px = std::log(1 / std::sqrt(2.0) / 0.004);
  const lab::SizeSpecies pixels(s, px, 0.005);
  CHECK(pixels.species(0.0315 / std::sqrt(2.0) / 0.004) == medium);
  CHECK(pixels.species(0.029 / std::sqrt(2.0) / 0.004) == small);

  // Grains drawn from the laws as a run draws them: the share given another species than their own is the
  // error rate the classifier states (here: medium grains below 0.030 m, about 1% of all). The midpoint
  // between neighbouring species' mean log radii (as the groups were cut before) gives away more than twice
  // as many.
  std::mt19937_64 rng(11);
  long wrong = 0, midpoint_wrong = 0, total = 0;
  auto by_midpoint = [&](double r) {
    int best = 0;
    for (size_t c = 1; c < s.size(); ++c)
      if (std::fabs(std::log(r) - exact.mean_log_radius(static_cast<int>(c))) <
          std::fabs(std::log(r) - exact.mean_log_radius(best)))
        best = static_cast<int>(c);
    return best;
  };
  for (size_t k = 0; k < s.size(); ++k)
    for (int i = 0; i < 400 * s[k].count; ++i) {
      double r = s[k].radius;
      if (s[k].law == core::SizeLaw::Uniform) {
        r = std::uniform_real_distribution<double>(s[k].radius_min, s[k].radius_max)(rng);
      } else if (s[k].law == core::SizeLaw::Lognormal) {
        const double s2 = std::log(1 + s[k].spread * s[k].spread);
        std::lognormal_distribution<double> law(std::log(s[k].radius) - 0.5 * s2, std::sqrt(s2));
        do r = law(rng);
        while (r < s[k].radius_min || r > s[k].radius_max);
      }
      wrong += exact.species(r) != static_cast<int>(k);
      midpoint_wrong += by_midpoint(r) != static_cast<int>(k);
      ++total;
    }
  const double measured = static_cast<double>(wrong) / static_cast<double>(total);
  const double midpoint = static_cast<double>(midpoint_wrong) / static_cast<double>(total);
  INFO("measured " << measured << ", stated " << exact.error_rate() << ", by the midpoint " << midpoint);
  CHECK(exact.error_rate() > 0.001);
  CHECK(std::fabs(measured - exact.error_rate()) < 0.1 * exact.error_rate() + 0.0005);
  CHECK(midpoint > 2 * measured);
}

TEST_CASE("size species: two fixed sizes are told apart at any measurement spread up to 10%", "[lab]") {
  const std::vector<core::SpeciesDef> s = preset_species("paper");
  REQUIRE(s.size() == 2);
  const int big = s[0].radius > s[1].radius ? 0 : 1;
  for (double sigma : {0.005, 0.02, 0.1}) {
    const lab::SizeSpecies c(s, 0, sigma);
    INFO("spread " << sigma);
    CHECK(c.species(s[static_cast<size_t>(big)].radius * 1.1) == big);
    CHECK(c.species(s[static_cast<size_t>(big)].radius * 0.9) == big);
    CHECK(c.species(s[static_cast<size_t>(1 - big)].radius * 1.1) == 1 - big);
    CHECK(c.species(s[static_cast<size_t>(1 - big)].radius * 0.9) == 1 - big);
    CHECK(c.species(1e-6) == 1 - big);  // far outside every law: the nearest
    CHECK(c.species(10.0) == big);
    CHECK(c.error_rate() < 1e-3);
  }
}
