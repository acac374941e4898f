// The paper is the regression suite: whatever scenes can do now, the paper's presets give the events they
// gave before scenes became data (tests/golden/events/, made by the binary of commit 4e8c5b5, the last one
// before), and every committed campaign analyses to its committed points.csv.
#include <catch2/catch.hpp>

#include <filesystem>
#include <sstream>

#include "helpers.h"

namespace fs = std::filesystem;
using test::cli;
using test::slurp;

namespace {
const std::string kSource = SILOSCOPE_SOURCE_DIR;
}

TEST_CASE("the paper's presets give the committed events, byte for byte", "[app][scene][golden][heavy]") {
  struct Case {
    const char* name;
    const char* args;
  };
  // The golden runs' own command lines (12 s of discharge each).
  const Case cases[] = {
      {"paper-s1", "assets/scenes/paper.toml --seed 1"},
      {"paper-s2-dipoles", "assets/scenes/paper.toml --seed 2 --set size_ratio=0.3 --set mu=0.15"},
      {"vibrated-s1", "assets/scenes/paper-vibrated.toml --seed 1"},
      {"vibrated-s3-dipoles", "assets/scenes/paper-vibrated.toml --seed 3 --set size_ratio=1.0 --set mu=3"},
  };
  const fs::path d = test::temp_dir("paper_equality");
  for (const auto& c : cases) {
    INFO(c.name);
    const auto r =
        cli("run " + kSource + "/" + c.args + " --duration 12 --quiet --out " + (d / c.name).string());
    REQUIRE(r.code == 0);
    for (const char* f : {"exits.csv", "clogs.csv", "arches.csv"}) {
      INFO(f);
      const std::string want = slurp(fs::path(kSource) / "tests/golden/events" / c.name / f);
      REQUIRE(!want.empty());
      CHECK(slurp(d / c.name / f) == want);
    }
  }
}

TEST_CASE("every committed campaign analyses to its committed points.csv", "[app][analysis][golden][heavy]") {
  const fs::path d = test::temp_dir("campaign_equality");
  int campaigns = 0;
  for (const auto& e : fs::directory_iterator(fs::path(kSource) / "docs/campaigns")) {
    const fs::path packed = e.path() / "runs/runs.tar.xz";
    if (!fs::exists(packed)) continue;
    ++campaigns;
    const std::string name = e.path().filename().string();
    INFO(name);
    REQUIRE(test::sh("mkdir -p " + (d / name).string() + " && tar -xJf " + packed.string() + " -C " +
                     (d / name).string()) == 0);
    // The keys the campaign told its points apart by (sweep passes its grid's own), as the committed
    // analysis recorded them: `by = ["obstacle_height", "obstacle"]`.
    std::string by;
    {
      std::istringstream meta(slurp(e.path() / "analysis/metadata.toml"));
      for (std::string line; std::getline(meta, line);)
        if (line.rfind("by = [", 0) == 0)
          for (size_t q = line.find('"'); q != std::string::npos;
               q = line.find('"', line.find('"', q + 1) + 1))
            by += " --by " + line.substr(q + 1, line.find('"', q + 1) - q - 1);
    }
    const auto r =
        cli("analyze " + (d / name / "runs").string() + " --out " + (d / name / "analysis").string() + by);
    REQUIRE(r.code == 0);
    CHECK(slurp(d / name / "analysis/points.csv") == slurp(e.path() / "analysis/points.csv"));
    CHECK(slurp(d / name / "analysis/survival.csv") == slurp(e.path() / "analysis/survival.csv"));
    CHECK(slurp(d / name / "analysis/avalanches.csv") == slurp(e.path() / "analysis/avalanches.csv"));
    if (fs::exists(e.path() / "analysis/clog_survival.csv"))  // packs made by docs/campaigns/pack.sh
      CHECK(slurp(d / name / "analysis/clog_survival.csv") == slurp(e.path() / "analysis/clog_survival.csv"));
    if (fs::exists(e.path() / "analysis/drain.csv"))  // a drain campaign's jamming probabilities
      CHECK(slurp(d / name / "analysis/drain.csv") == slurp(e.path() / "analysis/drain.csv"));
    if (fs::exists(e.path() / "analysis/column.csv"))  // where each species sits, from kept trajectories
      CHECK(slurp(d / name / "analysis/column.csv") == slurp(e.path() / "analysis/column.csv"));
  }
  CHECK(campaigns >= 3);  // kicks, paper, paper-vibrated
}
