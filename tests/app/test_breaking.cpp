// siloscope breaking as a user meets it: a table per arrested clog beside its metadata, every bad input one
// clear line with exit 2 and nothing written.
#include <catch2/catch.hpp>

#include <filesystem>

#include "helpers.h"

namespace fs = std::filesystem;

TEST_CASE("breaking: each arrested clog's breaking kick in a table, bad input refused",
          "[app][forces][heavy]") {
  const fs::path d = test::temp_dir("breaking");
  const std::string paper = std::string(SILOSCOPE_SOURCE_DIR) + "/assets/scenes/paper.toml";
  auto r = test::cli("run " + paper + " --seed 3 --duration 4 --quiet --out " + (d / "run").string());
  REQUIRE(r.code == 0);
  // One clog, kicks from 0.5 m/s, one halving.
  const std::string quick = " --dv-first 0.5 --bisections 1 --jobs 1";
  r = test::cli("breaking " + (d / "run").string() + " --clog 1" + quick + " --out " + (d / "b").string());
  CAPTURE(r.output);
  REQUIRE(r.code == 0);
  const std::string table = test::slurp(d / "b" / "breaking.csv");
  CHECK(table.rfind("clog,t_s,outcome,grains,span_m,aspect_rise_over_half_span,theta_max_deg,defects,load_N,"
                    "held_N,dv_held_m_s,dv_broke_m_s,trials\n1,",
                    0) == 0);
  CHECK(std::count(table.begin(), table.end(), '\n') == 2);
  const std::string meta = test::slurp(d / "b" / "metadata.toml");
  CHECK_THAT(meta, Catch::Matchers::Contains("dv_first_m_s = 0.5"));
  CHECK_THAT(meta, Catch::Matchers::Contains("seed = 3"));
  // Again: refused without --force, the table intact.
  r = test::cli("breaking " + (d / "run").string() + " --clog 1" + quick + " --out " + (d / "b").string());
  CHECK(r.code == 2);
  CHECK_THAT(r.output, Catch::Matchers::Contains("already exists"));
  CHECK(test::slurp(d / "b" / "breaking.csv") == table);
  // Bad input: a clog the run does not have, a bracket upside down, a vibrating container.
  r = test::cli("breaking " + (d / "run").string() + " --clog 9 --out " + (d / "c").string());
  CHECK(r.code == 2);
  CHECK_THAT(r.output, Catch::Matchers::Contains("--clog 9: the run has"));
  r = test::cli("breaking " + (d / "run").string() + " --dv-first 2 --dv-max 1 --out " + (d / "c").string());
  CHECK(r.code == 2);
  CHECK_THAT(r.output, Catch::Matchers::Contains("expected 0 < FIRST <= MAX"));
  const std::string vibrated = std::string(SILOSCOPE_SOURCE_DIR) + "/assets/scenes/vibrated-silo.toml";
  REQUIRE(test::cli("run " + vibrated + " --duration 1 --quiet --out " + (d / "v").string()).code == 0);
  r = test::cli("breaking " + (d / "v").string() + " --out " + (d / "c").string());
  CHECK(r.code == 2);
  CHECK_THAT(r.output, Catch::Matchers::Contains("vibrates its container"));
  CHECK(!fs::exists(d / "c"));
}
