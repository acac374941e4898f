// "What if" in the inspector (issue 56): a recorded run branched at an arrested clog, an arch member removed,
// continued and saved as a run of its own, by a script that replays to the same pictures.
#include <catch2/catch.hpp>

#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "helpers.h"
#include "io/csv_table.h"

namespace fs = std::filesystem;
using test::temp_dir;

namespace {
// The first arrested clog of a run and a frame one second into it (the arch standing, the outlet still).
struct ArrestedClog {
  double start = 0, end = 0;
  long frame = -1;
};
ArrestedClog first_arrested(const fs::path& run, double fps) {
  const io::CsvTable clogs = io::CsvTable::read((run / "clogs.csv").string(), "clogs.csv");
  for (size_t r = 0; r < clogs.rows(); ++r)
    if (clogs.num(r, "arrested") == 1 && clogs.num(r, "duration_s") > 2)
      return {clogs.num(r, "start_s"), clogs.num(r, "end_s"),
              std::lround((clogs.num(r, "start_s") + 1) * fps)};
  return {};
}
}  // namespace

TEST_CASE("a scripted branch removes an arch member of an arrested clog, ends the clog there and replays",
          "[ui][app][heavy]") {
  const fs::path d = temp_dir("branch");
  REQUIRE(test::cli("run " + test::kScene + " --seed 3 --duration 8 --trajectory-fps 30 --quiet --out " +
                    (d / "run").string())
              .code == 0);
  const ArrestedClog c = first_arrested(d / "run", 30);
  REQUIRE(c.frame > 0);
  // The arch's members at that frame, as the inspector lists them.
  std::ofstream(d / "arch.txt") << "goto frame " << c.frame << "\nprint arch\n";
  const test::Result arch =
      test::cli("inspect " + (d / "run").string() + " --quiet --script " + (d / "arch.txt").string());
  REQUIRE(arch.code == 0);
  std::stringstream rows(arch.output);
  std::string line;
  std::getline(rows, line);  // the header
  REQUIRE(line.rfind("id,species", 0) == 0);
  std::getline(rows, line);
  const int member = std::stoi(line.substr(0, line.find(',')));

  auto session = [&](const std::string& tag) {
    std::ofstream(d / (tag + ".txt"))
        << "goto frame " << c.frame << "\nbranch at " << c.frame << "\nremove grain " << member
        << "\ncontinue 2\nsnapshot " << (d / (tag + ".png")).string() << " 640x360\nsave branch "
        << (d / tag).string() << "\n";
    return test::cli("inspect " + (d / "run").string() + " --quiet --script " +
                     (d / (tag + ".txt")).string());
  };
  const test::Result a = session("a");
  INFO(a.output);
  REQUIRE(a.code == 0);
  // The saved branch is a run: its clog ends at the removal, by hand (the rule's way: the removed grain is
  // its row of arches.csv), and the outlet flows again within a second.
  const double t_branch = c.frame / 30.0;
  const io::CsvTable clogs = io::CsvTable::read((d / "a" / "clogs.csv").string(), "clogs.csv");
  bool found = false;
  for (size_t r = 0; r < clogs.rows(); ++r)
    if (std::fabs(clogs.num(r, "start_s") - c.start) < 1e-9) {
      found = true;
      CHECK(std::fabs(clogs.num(r, "end_s") - t_branch) < 0.02);
      CHECK(clogs.text(r, "ended_by") == "rule");
    }
  CHECK(found);
  CHECK(c.end > t_branch + 1);  // the recording's clog lasted on
  const io::CsvTable arches = io::CsvTable::read((d / "a" / "arches.csv").string(), "arches.csv");
  REQUIRE(arches.rows() >= 1);
  CHECK(arches.text(0, "ids") == std::to_string(member));
  const io::CsvTable exits = io::CsvTable::read((d / "a" / "exits.csv").string(), "exits.csv");
  long after = 0;
  for (size_t r = 0; r < exits.rows(); ++r)
    after += exits.num(r, "t_s") > t_branch && exits.num(r, "t_s") < t_branch + 1;
  CHECK(after > 5);
  const std::string meta = test::slurp(d / "a" / "metadata.toml");
  CHECK(meta.find("branch_frame = " + std::to_string(c.frame)) != std::string::npos);
  CHECK(meta.find("grain " + std::to_string(member) + " removed") != std::string::npos);
  // The saved branch opens in the inspector like any run.
  std::ofstream(d / "open.txt") << "goto end\nprint\n";
  CHECK(test::cli("inspect " + (d / "a").string() + " --quiet --script " + (d / "open.txt").string()).code ==
        0);
  // The same session again: the same picture, byte for byte, and the same events.
  REQUIRE(session("b").code == 0);
  CHECK(test::slurp(d / "a.png") == test::slurp(d / "b.png"));
  CHECK(test::slurp(d / "a" / "exits.csv") == test::slurp(d / "b" / "exits.csv"));
  // The recording is untouched.
  CHECK(io::CsvTable::read((d / "run" / "clogs.csv").string(), "clogs.csv").num(0, "end_s") == c.end);
}

TEST_CASE("branch lines are refused with what to do: no branch yet, a saved branch, a key it cannot change",
          "[ui][app][heavy]") {
  const fs::path d = temp_dir("branch_errors");
  REQUIRE(test::cli("run " + test::kScene + " --duration 2 --trajectory-fps 30 --quiet --out " +
                    (d / "run").string())
              .code == 0);
  auto refused = [&](const std::string& script, const std::string& says) {
    std::ofstream(d / "s.txt") << script;
    const test::Result r =
        test::cli("inspect " + (d / "run").string() + " --quiet --script " + (d / "s.txt").string());
    INFO(script << "\n" << r.output);
    CHECK(r.code == 2);
    CHECK(r.output.find(says) != std::string::npos);
  };
  refused("remove grain 3\n", "s.txt:1: 'remove grain 3': remove grain: no branch");
  refused("branch at 10\nset gravity 5\n", "a branch changes kick_impulse_max (N s) and the dipole moments");
  refused("branch at 10\nset mu 200\n", "allowed 0 to 100 A*m^2");
  refused("branch at 10\nkick -1\n", "must be > 0");
  refused("branch at 10\nremove grain 99999\n", "ids run from 0 to");
  refused("branch at 10\ncontinue inf\n", "is not a number");
  refused("branch at 999\n", "out of range");
  refused("branch at 10\nsave branch " + (d / "run").string() + "\n", "exists");
  refused("branch at 10\ncontinue 0.1\nsave branch " + (d / "b").string() + "\ncontinue 1\n",
          "this branch was saved and ended there");
  // A run changed after it was written is refused before any re-simulation (its manifest).
  std::string ex = test::slurp(d / "run" / "exits.csv");
  const size_t last_digit = ex.find(',', ex.find('\n') + 1) - 1;
  ex[last_digit] = ex[last_digit] == '1' ? '2' : '1';
  std::ofstream(d / "run" / "exits.csv") << ex;
  const test::Result r =
      test::cli("inspect " + (d / "run").string() + " --quiet --script " + (d / "s.txt").string());
  CHECK(r.code == 2);
  CHECK(r.output.find("exits.csv differs from what siloscope wrote") != std::string::npos);
}

TEST_CASE("the inspector's arch table carries each member's load and the arch's force balance at rest",
          "[ui][app][forces]") {
  // No kicks and no rule: the first arrested clog's arch stands at rest to the run's end. Its forces come
  // from the recording's contacts (version 2: the tangential force, the point, the walls' contacts).
  const fs::path d = temp_dir("arch_loads");
  REQUIRE(test::cli("run " + test::kScene +
                    " --set kick_impulse_max=0 --set clog_timeout=0 --duration 6 --trajectory-fps 30 --quiet "
                    "--out " +
                    (d / "run").string())
              .code == 0);
  const io::CsvTable clogs = io::CsvTable::read((d / "run" / "clogs.csv").string(), "clogs.csv");
  REQUIRE(clogs.rows() >= 1);
  const size_t last = clogs.rows() - 1;
  REQUIRE(clogs.num(last, "arrested") == 1);
  REQUIRE(clogs.num(last, "start_s") < 5);
  // 5.91 s: at rest, still clogged; the stress colouring and the arrows taken (the recording's contacts
  // carry their points).
  std::ofstream(d / "arch.txt") << "goto frame 179\ncolor stress\narch forces on\nprint arch\n";
  const test::Result r =
      test::cli("inspect " + (d / "run").string() + " --quiet --script " + (d / "arch.txt").string());
  INFO(r.output);
  REQUIRE(r.code == 0);
  std::stringstream rows(r.output);
  std::string line;
  std::getline(rows, line);
  REQUIRE(line == "id,species,x_m,y_m,bead_angle_deg,force_left_N,force_right_N,load_N,wall_N,walls");
  double members_load = 0;
  int members = 0, on_walls = 0;
  double load = NAN, held = NAN, weight = NAN, residual = NAN;
  while (std::getline(rows, line)) {
    if (line.rfind("# balance:", 0) == 0) {
      REQUIRE(std::sscanf(line.c_str(), "# balance: load_N=%lf held_N=%lf weight_N=%lf residual_N=%lf", &load,
                          &held, &weight, &residual) == 4);
      continue;
    }
    if (line.empty() || !std::isdigit(static_cast<unsigned char>(line[0]))) continue;
    std::vector<std::string> f;
    std::stringstream cells(line);
    for (std::string c; std::getline(cells, c, ',');) f.push_back(c);
    REQUIRE(f.size() >= 10);
    members_load += std::stod(f[7]);
    on_walls += std::stod(f[8]) > 0;
    ++members;
  }
  REQUIRE(members >= 2);
  CHECK(on_walls >= 2);  // its two ends lean on the hopper's walls
  // The arch as a body at rest: the walls hold up the load from above and its own weight, to within 2% of
  // what they hold; the members' loads add up to the arch's.
  CHECK(load > 0);
  CHECK(weight > 0);
  CHECK(held > load);
  CHECK(residual < 0.02 * held);
  CHECK(members_load == Approx(load).epsilon(0.01));
}
