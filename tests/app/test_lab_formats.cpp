// Issue 54 (lab data, formats and mixtures): one recording's tracks written as labs' tools write them
// (trackpy without a diameter column, a spreadsheet's semicolons with a byte-order mark, quotes and decimal
// commas, TrackMate's spots with their description lines and untracked spots) import to the same run as
// trackpy's own layout with a diameter: the same exits, species included, byte for byte.
#include <catch2/catch.hpp>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <random>
#include <set>
#include <sstream>

#include "app/services/lab.h"
#include "helpers.h"
#include "io/trajectory.h"
#include "vision/detect.h"
#include "vision/lens.h"

namespace fs = std::filesystem;
using test::cli;
using test::kScene;
using test::slurp;

namespace {

constexpr double kScale = 0.004;                  // m per pixel
constexpr double kOriginX = 400, kOriginY = 600;  // the outlet's centre, px

struct Spot {
  long frame, id;
  double x_px, y_px, radius_px;
};

// Every grain of every frame in pixels (y down), a new id whenever a grain jumps (an exit or a re-injection):
// what a lab's tracker sees; with keep_ids, the grain's own index throughout (what a tracker that keeps ids
// across re-injection gives, and siloscope's own export).
std::vector<Spot> spots_of(const fs::path& traj, bool keep_ids = false) {
  io::Trajectory t(traj);
  std::vector<Spot> out;
  std::map<size_t, long> id_of;
  std::map<size_t, float> last_y;
  long next = 0;
  for (long k = 0; k < t.size(); ++k) {
    const core::Frame f = t.frame(k);
    for (size_t i = 0; i < f.particles.size(); ++i) {
      const core::Particle& p = f.particles[i];
      if (!id_of.count(i) || std::fabs(p.y - last_y[i]) > 0.5f) id_of[i] = next++;
      last_y[i] = p.y;
      out.push_back({k, keep_ids ? static_cast<long>(i) : id_of[i], kOriginX + p.x / kScale,
                     kOriginY - p.y / kScale, p.radius / kScale});
    }
  }
  return out;
}

// Numbers as a comma-decimal spreadsheet writes them.
std::string decimal_comma(double v) {
  std::ostringstream s;
  s.precision(10);
  s << v;
  std::string t = s.str();
  for (char& c : t)
    if (c == '.') c = ',';
  return t;
}

void write(const fs::path& p, const std::string& header, const std::vector<Spot>& spots,
           const std::function<std::string(const Spot&, long)>& row, const std::string& extra = "") {
  std::ofstream out(p, std::ios::binary);
  out << header << extra;
  long n = 0;
  for (const Spot& s : spots) out << row(s, n++);
}

std::string num(double v) {
  std::ostringstream s;
  s.precision(10);
  s << v;
  return s.str();
}

// The calibration detect wrote in a tracks' metadata: metres per pixel, and the outlet's pixel as "X,Y".
double toml_number(const std::string& meta, const std::string& key) {
  return std::stod(meta.substr(meta.find(key + " = ") + key.size() + 3));
}
double scale_of(const std::string& meta) {
  return toml_number(meta, "scale_m_per_px");
}
std::string origin_of(const std::string& meta) {
  return num(toml_number(meta, "origin_x_px")) + "," + num(toml_number(meta, "origin_y_px"));
}

}  // namespace

TEST_CASE("import: trackpy without diameters, spreadsheet dialects and TrackMate's spots give the same run",
          "[lab][app][heavy]") {
  const fs::path d = test::temp_dir("lab_formats");
  REQUIRE(
      cli("run " + kScene + " --seed 3 --duration 6 --trajectory-fps 30 --quiet --out " + (d / "r").string())
          .code == 0);
  const std::vector<Spot> spots = spots_of(d / "r" / "trajectory.sstraj");
  const std::string args = " --geometry " + kScene + " --scale 0.004 --origin 400,600 --fps 30.303030303";
  auto import = [&](const std::string& file, const std::string& out, const std::string& more = "") {
    const auto r = cli("import " + (d / file).string() + args + more + " --out " + (d / out).string());
    INFO(file << ": " << r.output);
    REQUIRE(r.code == 0);
    return r.output;
  };
  // trackpy's layout with a diameter: the reference.
  write(d / "diameter.csv", ",y,x,mass,size,ecc,signal,raw_mass,ep,frame,particle,diameter\n", spots,
        [](const Spot& s, long n) {
          return std::to_string(n) + "," + num(s.y_px) + "," + num(s.x_px) + ",100," +
                 num(s.radius_px / std::sqrt(2.0)) + ",0.1,10,120,0.1," + std::to_string(s.frame) + "," +
                 std::to_string(s.id) + "," + num(2 * s.radius_px) + "\n";
        });
  import("diameter.csv", "ref");
  const std::string exits = slurp(d / "ref" / "exits.csv");
  REQUIRE(test::count_of(exits, ",added") > 5);  // both species leave
  REQUIRE(test::count_of(exits, ",original") > 5);

  // trackpy's own columns: no diameter, `size` (a radius of gyration) a little noisy: the species by size.
  write(d / "size.csv", ",y,x,mass,size,ecc,signal,raw_mass,ep,frame,particle\n", spots,
        [](const Spot& s, long n) {
          const double noise = 1 + 0.04 * std::sin(0.7 * static_cast<double>(n));
          return std::to_string(n) + "," + num(s.y_px) + "," + num(s.x_px) + ",100," +
                 num(noise * s.radius_px / std::sqrt(2.0)) + ",0.1,10,120,0.1," + std::to_string(s.frame) +
                 "," + std::to_string(s.id) + "\n";
        });
  const std::string by_size = import("size.csv", "size");
  CHECK_THAT(by_size,
             Catch::Matchers::Contains("the likeliest for each grain's size in the file's size column"));
  CHECK_THAT(by_size,
             Catch::Matchers::Contains("(spread 4.2%;"));  // 0.04 sin: its median |deviation| x 1.4826
  CHECK(slurp(d / "size" / "exits.csv") == exits);
  CHECK(slurp(d / "size" / "metadata.toml").find("species_by_size = true") != std::string::npos);

  // A spreadsheet's export: byte-order mark, quoted header, semicolons, decimal commas, CRLF.
  write(d / "excel.csv", "\xEF\xBB\xBF\"frame\";\"particle\";\"x\";\"y\";\"diameter\"\r\n", spots,
        [](const Spot& s, long) {
          return std::to_string(s.frame) + ";" + std::to_string(s.id) + ";" + decimal_comma(s.x_px) + ";" +
                 decimal_comma(s.y_px) + ";" + decimal_comma(2 * s.radius_px) + "\r\n";
        });
  import("excel.csv", "excel");
  CHECK(slurp(d / "excel" / "exits.csv") == exits);

  // TrackMate's spots: its header, three lines of names and units, frames as time (an image without a frame
  // interval), and spots it linked to no track (skipped and counted).
  const std::string header =
      "LABEL,ID,TRACK_ID,QUALITY,POSITION_X,POSITION_Y,POSITION_Z,POSITION_T,FRAME,RADIUS,VISIBILITY\n"
      "Label,Spot ID,Track ID,Quality,X,Y,Z,T,Frame,Radius,Visibility\n"
      "Label,Spot ID,Track ID,Quality,X,Y,Z,T,Frame,R,Visibility\n"
      ",,,(quality),(pixel),(pixel),(pixel),(frame),,(pixel),\n";
  const std::string untracked =
      "ID900001,900001,,3.0,400,300,0,2,2,16,1\nID900002,900002,,3.0,410,320,0,5,5,6,1\n";
  write(
      d / "trackmate.csv", header, spots,
      [](const Spot& s, long n) {
        return "ID" + std::to_string(n) + "," + std::to_string(n) + "," + std::to_string(s.id) + ",20," +
               num(s.x_px) + "," + num(s.y_px) + ",0," + std::to_string(s.frame) + "," +
               std::to_string(s.frame) + "," + num(s.radius_px) + ",1\n";
      },
      untracked);
  const std::string tm = import("trackmate.csv", "trackmate");
  CHECK_THAT(tm, Catch::Matchers::Contains("skipped     2 spots without a track id"));
  CHECK(slurp(d / "trackmate" / "exits.csv") == exits);
  CHECK(slurp(d / "trackmate" / "metadata.toml").find("untracked_spots_skipped = 2") != std::string::npos);

  // TrackMate's XML (its saved session): spots by frame, tracks as edges between spots, the tracks its filter
  // kept listed; two spots in no track and a track the filter left out are skipped and counted, as are the
  // grains seen in one frame only (no edge: TrackMate has no track of one spot).
  long single = 0;
  {
    std::map<long, std::string> frames;
    std::map<long, std::string> edges;  // per track
    std::map<long, long> last;          // per track, its last spot
    long n = 0;
    for (const Spot& s : spots) {
      ++n;
      frames[s.frame] += "<Spot ID=\"" + std::to_string(n) + "\" name=\"ID" + std::to_string(n) +
                         "\" POSITION_X=\"" + num(s.x_px) + "\" POSITION_Y=\"" + num(s.y_px) +
                         "\" POSITION_Z=\"0.0\" POSITION_T=\"" + std::to_string(s.frame) + ".0\" FRAME=\"" +
                         std::to_string(s.frame) + "\" RADIUS=\"" + num(s.radius_px) +
                         "\" QUALITY=\"20\"/>\n";
      if (last.count(s.id))
        edges[s.id] += "<Edge SPOT_SOURCE_ID=\"" + std::to_string(last[s.id]) + "\" SPOT_TARGET_ID=\"" +
                       std::to_string(n) + "\"/>\n";
      last[s.id] = n;
    }
    for (const auto& [id, spot] : last) single += !edges.count(id);
    frames[2] += "<Spot ID=\"900001\" POSITION_X=\"400\" POSITION_Y=\"300\" FRAME=\"2\" RADIUS=\"16\"/>\n";
    frames[3] +=
        "<Spot ID=\"900002\" POSITION_X=\"410\" POSITION_Y=\"320\" FRAME=\"3\" RADIUS=\"6\"/>\n"
        "<Spot ID=\"900003\" POSITION_X=\"380\" POSITION_Y=\"320\" FRAME=\"3\" RADIUS=\"16\"/>\n";
    frames[4] += "<Spot ID=\"900004\" POSITION_X=\"381\" POSITION_Y=\"321\" FRAME=\"4\" RADIUS=\"16\"/>\n";
    std::ofstream x(d / "trackmate.xml");
    x << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<TrackMate version=\"7.11.1\">\n"
      << "<Model spatialunits=\"pixel\" timeunits=\"frame\">\n<AllSpots nspots=\"" << n + 4 << "\">\n";
    for (const auto& [k, text] : frames)
      x << "<SpotsInFrame frame=\"" << k << "\">\n" << text << "</SpotsInFrame>\n";
    x << "</AllSpots>\n<AllTracks>\n";
    for (const auto& [id, text] : edges)
      x << "<Track name=\"Track_" << id << "\" TRACK_ID=\"" << id << "\">\n" << text << "</Track>\n";
    x << "<Track name=\"Track_x\" TRACK_ID=\"999999\">\n<Edge SPOT_SOURCE_ID=\"900003\" "
         "SPOT_TARGET_ID=\"900004\"/>\n</Track>\n</AllTracks>\n<FilteredTracks>\n";
    for (const auto& [id, text] : edges) x << "<TrackID TRACK_ID=\"" << id << "\"/>\n";
    x << "</FilteredTracks>\n</Model>\n</TrackMate>\n";
  }
  const std::string tmx = import("trackmate.xml", "trackmate_xml");
  CHECK_THAT(
      tmx, Catch::Matchers::Contains("skipped     " + std::to_string(4 + single) + " spots without a track"));
  CHECK(slurp(d / "trackmate_xml" / "exits.csv") == exits);
  // Not TrackMate's XML, and not XML at all: refused naming the file and what was expected.
  std::ofstream(d / "other.xml") << "<?xml version=\"1.0\"?>\n<svg/>\n";
  const auto other = cli("import " + (d / "other.xml").string() + args + " --out " + (d / "o1").string());
  CHECK(other.code == 2);
  CHECK_THAT(other.output, Catch::Matchers::Contains("other.xml: not a TrackMate file"));
  std::ofstream(d / "broken.xml") << "<TrackMate><Model>\n";
  const auto broken = cli("import " + (d / "broken.xml").string() + args + " --out " + (d / "o2").string());
  CHECK(broken.code == 2);
  CHECK_THAT(broken.output, Catch::Matchers::Contains("broken.xml: not readable as XML"));
  CHECK_FALSE(fs::exists(d / "o1"));
  CHECK_FALSE(fs::exists(d / "o2"));

  // Ids kept across the exit and the re-injection at the top (a jump of metres in one frame): each track is
  // split where it jumps, so the exits and clogs are the reference's (grain numbers aside).
  write(d / "kept.csv", "frame,particle,x,y,diameter\n", spots_of(d / "r" / "trajectory.sstraj", true),
        [](const Spot& s, long) {
          return std::to_string(s.frame) + "," + std::to_string(s.id) + "," + num(s.x_px) + "," +
                 num(s.y_px) + "," + num(2 * s.radius_px) + "\n";
        });
  const std::string kept = import("kept.csv", "kept");
  CHECK_THAT(kept, !Catch::Matchers::Contains(" 0 split where one jumped"));
  auto times_and_species = [](const std::string& csv) {
    std::multiset<std::string> out;
    std::istringstream in(csv);
    std::string line;
    while (std::getline(in, line)) out.insert(line.substr(0, line.find(',')) + line.substr(line.rfind(',')));
    return out;
  };
  CHECK(times_and_species(slurp(d / "kept" / "exits.csv")) == times_and_species(exits));
  CHECK(slurp(d / "kept" / "clogs.csv") == slurp(d / "ref" / "clogs.csv"));

  // An arch member unseen for a third of a second inside a clog (occluded: a gap longer than --max-gap): no
  // frame's arch has a member that is not in the frame, and the clog's arch is the one last seen whole.
  {
    std::istringstream arches(slurp(d / "ref" / "clog_arches.csv"));
    std::string line;
    std::getline(arches, line);
    REQUIRE(std::getline(arches, line));
    std::vector<std::string> f;
    std::istringstream cells(line);
    for (std::string cell; std::getline(cells, cell, ',');) f.push_back(cell);
    const long member = std::stol(f[4]);                            // the first of its track ids
    const long seen = std::lround(std::stod(f[1]) * 30.303030303);  // the frame the arch was last seen whole
    write(d / "occluded.csv", ",y,x,mass,size,ecc,signal,raw_mass,ep,frame,particle,diameter\n", spots,
          [&](const Spot& s, long n) {
            if (s.id == member && s.frame > seen - 15 && s.frame <= seen - 5) return std::string();
            return std::to_string(n) + "," + num(s.y_px) + "," + num(s.x_px) + ",100,3,0.1,10,120,0.1," +
                   std::to_string(s.frame) + "," + std::to_string(s.id) + "," + num(2 * s.radius_px) + "\n";
          });
    import("occluded.csv", "occluded");
    io::Trajectory t(d / "occluded" / "trajectory.sstraj");
    long with_arch = 0;
    for (long k = 0; k < t.size(); ++k) {
      const core::Frame fr = t.frame(k);
      with_arch += !fr.arch.empty();
      for (int g : fr.arch) {
        INFO("frame " << k << ", arch member " << g);
        CHECK(fr.particles[static_cast<size_t>(g)].y > -0.5f);
      }
    }
    CHECK(with_arch > 30);
    std::istringstream out(slurp(d / "occluded" / "clog_arches.csv"));
    std::getline(out, line);
    while (std::getline(out, line)) {
      std::vector<std::string> c;
      std::istringstream cs(line);
      for (std::string cell; std::getline(cs, cell, ',');) c.push_back(cell);
      INFO(line);
      CHECK(std::stod(c[6]) < 1.0);  // span_m: across the outlet, not to a grain parked out of view
    }
  }

  // Positions with noise of 0.05 of the large grains' diameter (a lab's detection): the noise is measured
  // from the tracks and sets the arrest check's floor, so the clogs are marked arrested as the exact tracks'
  // are.
  {
    std::mt19937_64 rng(11);
    auto normal = [&] {  // Box-Muller: the same numbers with any standard library
      const double u = (static_cast<double>(rng() >> 11) + 0.5) / 9007199254740992.0;
      const double v = static_cast<double>(rng() >> 11) / 9007199254740992.0;
      return std::sqrt(-2 * std::log(u)) * std::cos(2 * M_PI * v);
    };
    const double sigma_px = 0.05 * 0.13 / kScale;  // 0.05 of the original grains' 0.13 m
    std::vector<Spot> noisy = spots;
    for (Spot& s : noisy) s.x_px += sigma_px * normal(), s.y_px += sigma_px * normal();
    write(d / "noisy.csv", "frame,particle,x,y,diameter\n", noisy, [](const Spot& s, long) {
      return std::to_string(s.frame) + "," + std::to_string(s.id) + "," + num(s.x_px) + "," + num(s.y_px) +
             "," + num(2 * s.radius_px) + "\n";
    });
    import("noisy.csv", "noisy");
    const std::string meta = slurp(d / "noisy" / "metadata.toml");
    const size_t at = meta.find("position_noise_m = ");
    REQUIRE(at != std::string::npos);
    const double noise = std::stod(meta.substr(at + 19));
    CHECK(noise > 0.8 * 0.05 * 0.13);
    CHECK(noise < 1.25 * 0.05 * 0.13);
    auto arrested = [](const std::string& csv) {
      std::string flags;
      std::istringstream in(csv);
      std::string line;
      while (std::getline(in, line)) flags += line.substr(line.rfind(',') + 1) + " ";
      return flags;
    };
    const std::string truth = arrested(slurp(d / "ref" / "clogs.csv"));
    INFO("arrested flags, exact tracks: " << truth);
    CHECK(truth.find(" 1 ") != std::string::npos);
    CHECK(arrested(slurp(d / "noisy" / "clogs.csv")) == truth);
    // arrest_shift given is taken as it is: without the floor the noise hides the arrest.
    import("noisy.csv", "noisy-given", " --set arrest_shift=0.1");
    CHECK(slurp(d / "noisy-given" / "metadata.toml").find("arrest_floor_m = 0.0\n") != std::string::npos);
    CHECK(arrested(slurp(d / "noisy-given" / "clogs.csv")) != truth);
  }

  // Calibrations that cannot be the experiment's: y the wrong way up (every grain below the outlet), a scale
  // ten times too small with sizes (grains a tenth of the scene's) and without (grains overlapping).
  auto refused = [&](const std::string& file, const std::string& more, const std::string& says) {
    const auto r = cli("import " + (d / file).string() + args + more + " --out " + (d / "bad").string());
    INFO(file << more << ": " << r.output);
    CHECK(r.code == 2);
    CHECK_THAT(r.output,
               Catch::Matchers::Contains(says) && Catch::Matchers::Contains("check --scale, --origin"));
    CHECK_FALSE(fs::exists(d / "bad"));
  };
  refused("diameter.csv", " --y-up", "grains leave through the outlet at once");
  const std::string small = " --geometry " + kScene + " --scale 0.0004 --origin 400,600 --fps 30.303030303";
  for (const char* file : {"diameter.csv", "size.csv"}) {
    const auto r = cli("import " + (d / file).string() + small + " --out " + (d / "bad").string());
    INFO(file << ": " << r.output);
    CHECK(r.code == 2);
    CHECK_THAT(r.output, Catch::Matchers::Contains(std::string(file) == "diameter.csv"
                                                       ? "times their species' radius in the geometry scene"
                                                       : "grains overlap"));
  }

  // A scene's species the sizes cannot tell apart (one species filmed): refused, naming what to give.
  std::vector<Spot> big;
  for (const Spot& s : spots)
    if (s.radius_px > 10) big.push_back(s);
  write(d / "one.csv", "frame,particle,x,y,size\n", big, [](const Spot& s, long n) {
    return std::to_string(s.frame) + "," + std::to_string(s.id) + "," + num(s.x_px) + "," + num(s.y_px) +
           "," + num((1 + 0.05 * std::sin(static_cast<double>(n))) * s.radius_px / std::sqrt(2.0)) + "\n";
  });
  const auto one = cli("import " + (d / "one.csv").string() + args + " --out " + (d / "one").string());
  CHECK(one.code == 2);
  CHECK_THAT(one.output, Catch::Matchers::Contains("do not fall into the scene's 2 species") &&
                             Catch::Matchers::Contains("--columns species=COLUMN or radius=COLUMN"));
  CHECK_FALSE(fs::exists(d / "one"));
}

TEST_CASE(
    "detect: the obstacle is no grain, a dark background is found by itself, --force replaces its own files",
    "[lab][app][heavy]") {
  const fs::path d = test::temp_dir("detect_films");
  const std::string film =
      " --seed 3 --duration 1 --camera window:-1.4,-0.4,1.4,1.6 --size 960x540 --overlay none "
      "--arch-halo off --quiet --out ";
  const std::string obstacle = std::string(SILOSCOPE_SOURCE_DIR) + "/assets/scenes/silo-obstacle.toml";
  REQUIRE(cli("record " + obstacle + film + (d / "ob").string()).code == 0);
  const auto ob = cli("detect " + (d / "ob.mp4").string() + " --out " + (d / "ob.csv").string());
  INFO(ob.output);
  REQUIRE(ob.code == 0);
  CHECK_THAT(ob.output, Catch::Matchers::Contains("dark on a light background"));
  // No detection's centre inside the obstacle (a disk of 0.35 m, its centre 0.525 m above the outlet's).
  const std::string meta = slurp(d / "ob.meta.toml");
  const double scale = scale_of(meta), ox = toml_number(meta, "origin_x_px"),
               oy = toml_number(meta, "origin_y_px");
  std::istringstream rows(slurp(d / "ob.csv"));
  std::string line;
  std::getline(rows, line);
  long n = 0, inside = 0;
  while (std::getline(rows, line)) {
    std::vector<std::string> c;
    std::istringstream cs(line);
    for (std::string cell; std::getline(cs, cell, ',');) c.push_back(cell);
    const double x = (std::stod(c[2]) - ox) * scale, y = (oy - std::stod(c[3])) * scale;
    inside += std::hypot(x, y - 0.525) < 0.175;
    ++n;
  }
  CHECK(n > 30 * 150);  // about 180 grains in view in each of 31 frames
  CHECK(inside == 0);
  // Its own tracks and their metadata are replaced with --force (the metadata's first line was mistaken for a
  // user's); a file of the user's in the metadata's place is not.
  CHECK(cli("detect " + (d / "ob.mp4").string() + " --out " + (d / "ob.csv").string()).code == 2);
  CHECK(cli("detect " + (d / "ob.mp4").string() + " --force --out " + (d / "ob.csv").string()).code == 0);
  std::ofstream(d / "mine.meta.toml") << "# my notes\n";
  const auto mine = cli("detect " + (d / "ob.mp4").string() + " --force --out " + (d / "mine.csv").string());
  CHECK(mine.code == 2);
  CHECK(slurp(d / "mine.meta.toml") == "# my notes\n");
  CHECK_FALSE(fs::exists(d / "mine.csv"));

  // The same film on a dark background: bright disks, found without --bright, as many as on white.
  REQUIRE(cli("record " + kScene + film + (d / "light").string()).code == 0);
  REQUIRE(cli("record " + kScene + film + (d / "dark").string() + " --background dark").code == 0);
  auto disks = [&](const std::string& name, const std::string& says) {
    const auto r =
        cli("detect " + (d / (name + ".mp4")).string() + " --out " + (d / (name + ".csv")).string());
    INFO(r.output);
    REQUIRE(r.code == 0);
    CHECK_THAT(r.output, Catch::Matchers::Contains(says));
    return test::count_of(slurp(d / (name + ".csv")), "\n") - 1;
  };
  const long light = disks("light", "dark on a light background");
  const long dark = disks("dark", "bright on a dark background");
  INFO("disks found: light " << light << ", dark " << dark);
  CHECK(light > 30 * 80);
  CHECK(std::abs(dark - light) < 0.05 * light);

  // The light film as a multi-page TIFF stack (a lab camera's format): every page a frame, the same tracks as
  // the video's; the video cut short: a warning, and the metadata says so.
  {
    vision::FrameSource video((d / "light.mp4").string());
    std::vector<cv::Mat> pages;
    for (cv::Mat f; video.next(f);) pages.push_back(f.clone());
    REQUIRE(pages.size() == 30);
    REQUIRE(cv::imwritemulti((d / "stack.tif").string(), pages));
  }
  const std::string light_meta = slurp(d / "light.meta.toml");
  const std::string calibrated = " --geometry " + kScene + " --scale " + num(scale_of(light_meta)) +
                                 " --origin " + origin_of(light_meta);
  const auto stack = cli("detect " + (d / "stack.tif").string() + " --fps 30.303030303 --out " +
                         (d / "stack.csv").string() + calibrated);
  INFO(stack.output);
  REQUIRE(stack.code == 0);
  CHECK_THAT(stack.output, Catch::Matchers::Contains("30 frames"));
  CHECK(test::count_of(slurp(d / "stack.csv"), "\n") - 1 == light);
  const std::string whole = slurp(d / "light.mp4");
  std::ofstream(d / "cut.mp4", std::ios::binary) << whole.substr(0, whole.size() * 2 / 3);
  const auto cut =
      cli("detect " + (d / "cut.mp4").string() + " --out " + (d / "cut.csv").string() + calibrated);
  INFO(cut.output);
  REQUIRE(cut.code == 0);
  CHECK_THAT(cut.output, Catch::Matchers::Contains("of the 30 frames its header announces (cut short?)"));
  CHECK(slurp(d / "cut.meta.toml").find("ended_early = true") != std::string::npos);
  CHECK(light_meta.find("ended_early = false") != std::string::npos);
}

namespace {

// The median distance (m) from each whole disk of the truth's frames to the nearest position found, over the
// frames of `found` (frame number -> positions in metres).
double median_error(const io::Trajectory& truth, const std::map<long, std::vector<core::Vec2>>& found) {
  std::vector<double> e;
  for (const auto& [k, pos] : found) {
    if (k >= truth.size()) continue;
    for (const core::Particle& p : truth.frame(k).particles) {
      if (p.y < 0.3 || p.y > 1.5) continue;  // in view, above the outlet
      double best = INFINITY;
      for (const core::Vec2& q : pos) best = std::min(best, std::hypot(q.x - p.x, q.y - p.y));
      if (best < p.radius) e.push_back(best);
    }
  }
  std::sort(e.begin(), e.end());
  return e.empty() ? INFINITY : e[e.size() / 2];
}

}  // namespace

TEST_CASE("detect and import: a camera turned 2 degrees, calibrated from marked points, gives true positions",
          "[lab][app][heavy]") {
  const fs::path d = test::temp_dir("detect_turned");
  REQUIRE(cli("record " + kScene +
              " --seed 3 --duration 0.5 --camera window:-1.4,-0.4,1.4,1.6 --size 960x540 --overlay none "
              "--arch-halo off --quiet --out " +
              (d / "rec").string())
              .code == 0);
  app::Calibration straight;
  core::Model model;
  std::string why;
  REQUIRE(app::movie_calibration(d / "rec.mp4", straight, model, why));
  // The film as a camera turned the other way sees it: every frame turned 2 degrees counter-clockwise about
  // its centre, written as images.
  const double deg = 2;
  const cv::Mat turn = cv::getRotationMatrix2D(cv::Point2f(480, 270), deg, 1.0);
  fs::create_directories(d / "frames");
  vision::FrameSource video((d / "rec.mp4").string());
  int n = 0;
  for (cv::Mat f, g; video.next(f); ++n) {
    cv::warpAffine(f, g, turn, f.size(), cv::INTER_LINEAR, cv::BORDER_CONSTANT, cv::Scalar(255, 255, 255));
    char name[32];
    std::snprintf(name, sizeof name, "f%04d.png", n);
    REQUIRE(cv::imwrite((d / "frames" / name).string(), g));
  }
  REQUIRE(n >= 10);
  // Three marked points (the outlet's centre, two on the silo's axis and wall), where the turned film has
  // them.
  std::string points;
  for (core::Vec2 m : {core::Vec2{0, 0}, core::Vec2{0, 1.2}, core::Vec2{0.5, 1.2}}) {
    const core::Vec2 p = straight.to_pixels(m);
    const double x = turn.at<double>(0, 0) * p.x + turn.at<double>(0, 1) * p.y + turn.at<double>(0, 2);
    const double y = turn.at<double>(1, 0) * p.x + turn.at<double>(1, 1) * p.y + turn.at<double>(1, 2);
    points += (points.empty() ? "" : ":") + num(x) + "," + num(y) + "=" + num(m.x) + "," + num(m.y);
  }
  const std::string common = " --geometry " + kScene + " --fps 30.303030303";
  const auto det = cli("detect " + (d / "frames").string() + common + " --points " + points + " --out " +
                       (d / "t.csv").string() + " --rectified " + (d / "up.mp4").string());
  INFO(det.output);
  REQUIRE(det.code == 0);
  CHECK_THAT(det.output,
             Catch::Matchers::Contains("3 marked points") && Catch::Matchers::Contains("turned 2 deg"));
  const std::string meta = slurp(d / "t.meta.toml");
  app::Calibration fit;
  fit.scale = scale_of(meta);
  fit.origin_x = toml_number(meta, "origin_x_px");
  fit.origin_y = toml_number(meta, "origin_y_px");
  fit.rotation = toml_number(meta, "rotation_deg") * M_PI / 180;
  CHECK(std::fabs(fit.rotation * 180 / M_PI - deg) < 0.01);
  CHECK(std::fabs(fit.scale / straight.scale - 1) < 1e-6);
  CHECK(toml_number(meta, "points_residual_m") < 1e-6);
  // Positions in metres from the tracks, with the rotation and without it (the calibration of a straight
  // camera: what --scale and --origin alone gave).
  std::map<long, std::vector<core::Vec2>> turned, ignored, upright;
  app::Calibration flat = fit;
  flat.rotation = 0;
  auto positions = [](const fs::path& csv, const app::Calibration& cal,
                      std::map<long, std::vector<core::Vec2>>& to) {
    std::istringstream rows(slurp(csv));
    std::string line;
    std::getline(rows, line);
    while (std::getline(rows, line)) {
      std::vector<std::string> c;
      std::istringstream cs(line);
      for (std::string cell; std::getline(cs, cell, ',');) c.push_back(cell);
      to[std::stol(c[0])].push_back(cal.to_metres(std::stod(c[2]), std::stod(c[3])));
    }
  };
  positions(d / "t.csv", fit, turned);
  positions(d / "t.csv", flat, ignored);
  const io::Trajectory truth(d / "rec" / "trajectory.sstraj");
  const double diameter = 2 * 0.065, with = median_error(truth, turned),
               without = median_error(truth, ignored);
  INFO("median error with the rotation " << with / diameter << " d, without " << without / diameter << " d");
  CHECK(with < 0.01 * diameter);
  CHECK(without > 0.05 * diameter);
  // The rectified film is the straight camera's: detected with the fit's scale and origin and no rotation,
  // its grains stand where the recording's did. Its comment holds the upright calibration.
  REQUIRE(det.output.find("rectified film -> ") != std::string::npos);
  vision::FrameSource up((d / "up.mp4").string());
  CHECK(up.width() == 960);
  CHECK(up.height() == 540);
  const auto again =
      cli("detect " + (d / "up.mp4").string() + common + " --scale " + num(fit.scale) + " --origin " +
          num(fit.origin_x) + "," + num(fit.origin_y) + " --out " + (d / "up.csv").string());
  INFO(again.output);
  REQUIRE(again.code == 0);
  positions(d / "up.csv", flat, upright);
  INFO("median error of the rectified film " << median_error(truth, upright) / diameter << " d");
  CHECK(median_error(truth, upright) < 0.01 * diameter);
  CHECK(upright.size() == turned.size());
  CHECK(slurp(d / "t.meta.toml").find("rectified_film = ") != std::string::npos);
  // import takes the rotation from detect's calibration: the run's grains stand where the recording's did.
  const auto imp = cli("import " + (d / "t.csv").string() + " --quiet --out " + (d / "imp").string());
  INFO(imp.output);
  REQUIRE(imp.code == 0);
  CHECK(std::fabs(toml_number(slurp(d / "imp" / "metadata.toml"), "rotation_deg") - deg) < 0.01);
  const io::Trajectory run(d / "imp" / "trajectory.sstraj");
  std::map<long, std::vector<core::Vec2>> imported;
  for (long k = 0; k < run.size(); ++k)
    for (const core::Particle& p : run.frame(k).particles) imported[k].push_back({p.x, p.y});
  CHECK(median_error(truth, imported) < 0.01 * diameter);
  // A rotation out of range is refused naming the option.
  const auto bad = cli("detect " + (d / "frames").string() + common +
                       " --scale 0.004 --origin 480,500 --rotation 60 --out " + (d / "bad.csv").string());
  CHECK(bad.code == 2);
  CHECK_THAT(bad.output, Catch::Matchers::Contains("--rotation 60: expected -45 to 45 degrees"));
  CHECK_FALSE(fs::exists(d / "bad.csv"));
  // The rectified film is an MP4, checked before any work; nothing is written.
  const auto avi = cli("detect " + (d / "frames").string() + common + " --points " + points + " --out " +
                       (d / "bad.csv").string() + " --rectified " + (d / "up.avi").string());
  CHECK(avi.code == 2);
  CHECK_THAT(avi.output,
             Catch::Matchers::Contains("--rectified " + (d / "up.avi").string() + ": expected an .mp4 file"));
  CHECK_FALSE(fs::exists(d / "bad.csv"));
  CHECK_FALSE(fs::exists(d / "up.avi"));
}

TEST_CASE("detect: a lens's distortion found from a chessboard is taken out of the positions",
          "[lab][app][heavy]") {
  const fs::path d = test::temp_dir("detect_lens");
  REQUIRE(cli("record " + kScene +
              " --seed 3 --duration 0.5 --camera window:-1.4,-0.4,1.4,1.6 --size 960x540 --overlay none "
              "--arch-halo off --quiet --out " +
              (d / "rec").string())
              .code == 0);
  app::Calibration straight;
  core::Model model;
  std::string why;
  REQUIRE(app::movie_calibration(d / "rec.mp4", straight, model, why));
  // A barrel-distorting lens (k1 = -0.12 at a focal length of 960 px: the picture's corners move 14 px
  // inwards), and what it films: a 10 x 7 chessboard (9 x 6 inner corners) and the recording.
  vision::Lens truth_lens;
  truth_lens.present = true;
  truth_lens.camera = cv::Matx33d(960, 0, 479.5, 0, 960, 269.5, 0, 0, 1);
  truth_lens.distortion = {-0.12, 0, 0, 0, 0};
  cv::Mat board(540, 960, CV_8UC3, cv::Scalar(255, 255, 255));
  for (int r = 0; r < 7; ++r)
    for (int c = 0; c < 10; ++c)
      if ((r + c) % 2 == 0)
        cv::rectangle(board, cv::Rect(80 + 80 * c, -10 + 80 * r, 80, 80), cv::Scalar(0, 0, 0), cv::FILLED);
  REQUIRE(cv::imwrite((d / "board.png").string(), vision::distort_picture(board, truth_lens)));
  fs::create_directories(d / "frames");
  vision::FrameSource video((d / "rec.mp4").string());
  int n = 0;
  for (cv::Mat f; video.next(f); ++n) {
    char name[32];
    std::snprintf(name, sizeof name, "f%04d.png", n);
    REQUIRE(cv::imwrite((d / "frames" / name).string(), vision::distort_picture(f, truth_lens)));
  }
  REQUIRE(n >= 10);
  // Marked points on the distorted film (where the lens puts the outlet's centre and two wall points).
  std::string points;
  for (core::Vec2 m : {core::Vec2{0, 0}, core::Vec2{-0.5, 1.4}, core::Vec2{0.5, 1.4}}) {
    const core::Vec2 ideal = straight.to_pixels(m);
    const cv::Point2d p = truth_lens.raw({ideal.x, ideal.y});
    points += (points.empty() ? "" : ":") + num(p.x) + "," + num(p.y) + "=" + num(m.x) + "," + num(m.y);
  }
  const io::Trajectory truth(d / "rec" / "trajectory.sstraj");
  const double diameter = 2 * 0.065;
  auto error_of = [&](const std::string& extra, const std::string& name,
                      const std::string& input = "frames") {
    const auto det = cli("detect " + (d / input).string() + " --geometry " + kScene + " --fps 30.303030303" +
                         extra + " --out " + (d / name).string());
    INFO(det.output);
    REQUIRE(det.code == 0);
    const std::string meta = slurp(d / (name.substr(0, name.size() - 4) + ".meta.toml"));
    app::Calibration cal;
    cal.scale = scale_of(meta);
    cal.origin_x = toml_number(meta, "origin_x_px");
    cal.origin_y = toml_number(meta, "origin_y_px");
    cal.rotation = toml_number(meta, "rotation_deg") * M_PI / 180;
    std::map<long, std::vector<core::Vec2>> found;
    std::istringstream rows(slurp(d / name));
    std::string line;
    std::getline(rows, line);
    while (std::getline(rows, line)) {
      std::vector<std::string> c;
      std::istringstream cs(line);
      for (std::string cell; std::getline(cs, cell, ',');) c.push_back(cell);
      found[std::stol(c[0])].push_back(cal.to_metres(std::stod(c[2]), std::stod(c[3])));
    }
    return std::make_pair(median_error(truth, found) / diameter, meta);
  };
  const auto [with, meta] = error_of(" --points " + points + " --lens " + (d / "board.png").string() +
                                         " --rectified " + (d / "up.mp4").string(),
                                     "lens.csv");
  const auto [without, unused] = error_of(" --points " + points, "none.csv");
  // The rectified film is the ideal camera's: detected without a lens, at the scale and origin the lens's
  // calibration found, its grains stand where the recording's did.
  const auto [rectified, up_meta] =
      error_of(" --scale " + num(scale_of(meta)) + " --origin " + num(toml_number(meta, "origin_x_px")) +
                   "," + num(toml_number(meta, "origin_y_px")),
               "up.csv", "up.mp4");
  INFO("median error with the lens " << with << " d, without " << without << " d, of the rectified film "
                                     << rectified << " d; k1 " << toml_number(meta, "lens_k1") << ", rms "
                                     << toml_number(meta, "lens_rms_px") << " px");
  CHECK(std::fabs(toml_number(meta, "lens_k1") + 0.12) < 0.01);
  CHECK(toml_number(meta, "lens_rms_px") < 0.5);
  CHECK(with < 0.01);
  CHECK(without > 2 * with);
  CHECK(rectified < 0.01);
  // A chessboard of another pattern, or of another size than the film, is refused naming what to fix.
  const auto pattern =
      cli("detect " + (d / "frames").string() + " --geometry " + kScene + " --points " + points + " --lens " +
          (d / "board.png").string() + " --pattern 7x5 --out " + (d / "p.csv").string());
  CHECK(pattern.code == 2);
  CHECK_THAT(pattern.output, Catch::Matchers::Contains("no chessboard of 7x5 inner corners found"));
  cv::Mat small;
  cv::resize(board, small, cv::Size(480, 270));
  REQUIRE(cv::imwrite((d / "small.png").string(), small));
  const auto size =
      cli("detect " + (d / "frames").string() + " --geometry " + kScene + " --points " + points + " --lens " +
          (d / "small.png").string() + " --pattern 9x6 --out " + (d / "s.csv").string());
  CHECK(size.code == 2);
  CHECK_THAT(size.output,
             Catch::Matchers::Contains("its pictures are 480x270 and the film's frames 960x540"));
  CHECK_FALSE(fs::exists(d / "p.csv"));
  CHECK_FALSE(fs::exists(d / "s.csv"));
}
