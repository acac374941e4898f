// Issue 16: export for the field's tools, and the scene command.
#include <stb_image.h>
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/scene.h"
#include "helpers.h"
#include "io/trajectory.h"

namespace fs = std::filesystem;
using test::cli;
using test::kScene;
using test::slurp;
using test::temp_dir;

namespace {
fs::path recorded(const std::string& name) {
  fs::path d = temp_dir(name);
  REQUIRE(cli("record " + kScene + " --duration 3 --size 64x48 --quiet --out " + (d / "r").string()).code ==
          0);
  return d / "r";
}
}  // namespace

TEST_CASE("export --format xyz loads in ASE with the right atoms, radii and arch flags", "[export][app]") {
  const fs::path r = recorded("export_xyz");
  REQUIRE(cli("export " + r.string()).code == 0);
  io::Trajectory t(r / "trajectory.sstraj");
  long arch_members = 0;
  for (long k = 0; k < t.size(); ++k) arch_members += static_cast<long>(t.frame(k).arch.size());
  // The 3 s clip holds a clog (from 1.52 s, open from 2.02 s), so the flags are really tested.
  REQUIRE(arch_members > 0);
  const core::Frame last = t.frame(t.size() - 1);
  std::ostringstream py;
  py << "import ase.io\n"
     << "fr = ase.io.read('" << (r / "trajectory.xyz").string() << "', index=':')\n"
     << "assert len(fr) == " << t.size() << ", len(fr)\n"
     << "assert all(len(f) == 250 for f in fr)\n"
     << "a = fr[-1]\n"
     << "n_added = int((a.numbers == 2).sum())\n"
     << "assert n_added == 100, n_added\n"
     << "assert abs(a.arrays['radius'][a.numbers == 1][0] - 0.065) < 1e-9\n"
     << "assert abs(a.arrays['radius'][a.numbers == 2][0] - 0.026) < 1e-9\n"
     << "assert sum(int(f.arrays['arch'].sum()) for f in fr) == " << arch_members << "\n"
     << "assert abs(a.positions[7][0] - (" << last.particles[7].x << ")) < 1e-5\n"
     << "assert abs(a.info['Time'] - " << last.t << ") < 1e-6\n"
     << "assert abs(a.cell[1][1] - 6.36) < 1e-9\n"
     << "assert set(a.arrays['kind']) == {'original', 'added'}, set(a.arrays['kind'])\n"
     << "assert abs(a.arrays['angle'][7] - (" << last.particles[7].angle << ")) < 1e-5\n"
     << "assert a.info['species_names'] == 'original added', a.info['species_names']\n"
     << "print('ase ok')\n";
  std::ofstream(r / "check.py") << py.str();
  REQUIRE(test::sh("/usr/bin/python3 " + (r / "check.py").string() + " > " + (r / "check.log").string() +
                   " 2>&1") == 0);
  CHECK_THAT(slurp(r / "check.log"), Catch::Matchers::Contains("ase ok"));
}

TEST_CASE("export --format csv writes one frame or a range, values equal to the trajectory frame",
          "[export][app][heavy]") {
  const fs::path r = recorded("export_csv");
  REQUIRE(cli("export " + r.string() + " --format csv --frames 10 --out " + (r / "f10.csv").string()).code ==
          0);
  io::Trajectory t(r / "trajectory.sstraj");
  const core::Frame f = t.frame(10);
  std::istringstream in(slurp(r / "f10.csv"));
  std::string line;
  std::getline(in, line);
  CHECK(line ==
        "frame,t_s,id,species,x_m,y_m,radius_m,vx_m_per_s,vy_m_per_s,force_n,in_arch,angle_rad,sides");
  long rows = 0;
  while (std::getline(in, line)) {
    std::istringstream row(line);
    std::string cell;
    std::vector<std::string> c;
    while (std::getline(row, cell, ',')) c.push_back(cell);
    REQUIRE(c.size() == 13);
    const int id = std::stoi(c[2]);
    CHECK(std::stol(c[0]) == 10);
    CHECK(std::stod(c[1]) == Approx(f.t));
    CHECK(c[3] == (f.particles[id].species == core::Species::Original ? "original" : "added"));
    CHECK(std::stod(c[4]) == Approx(f.particles[id].x).margin(1e-6));
    CHECK(std::stod(c[5]) == Approx(f.particles[id].y).margin(1e-6));
    CHECK(std::stod(c[11]) == Approx(f.particles[id].angle).margin(1e-6));
    CHECK(c[12] == "0");  // the paper's disks
    ++rows;
  }
  CHECK(rows == 250);
  REQUIRE(
      cli("export " + r.string() + " --format csv --frames 2:4 --out " + (r / "range.csv").string()).code ==
      0);
  const std::string range = slurp(r / "range.csv");
  CHECK(std::count(range.begin(), range.end(), '\n') == 1 + 3 * 250);
  // Bad input: a range past the end, a format, an output that is a user's file.
  auto bad = cli("export " + r.string() + " --frames 5:9999 --format csv --out " + (r / "x.csv").string());
  CHECK(bad.code == 2);
  CHECK_THAT(bad.output, Catch::Matchers::Contains("frames 0 to"));
  CHECK(cli("export " + r.string() + " --format pdb").code == 2);
  std::ofstream(r / "mine.xyz") << "2\nmy own\nH 0 0 0\nH 1 0 0\n";
  CHECK(cli("export " + r.string() + " --force --out " + (r / "mine.xyz").string()).code == 2);
  CHECK(slurp(r / "mine.xyz") == "2\nmy own\nH 0 0 0\nH 1 0 0\n");
}

TEST_CASE("scene --keys lists exactly the field table, scene FILE resolves and validates", "[scene][app]") {
  auto r = cli("scene --keys");
  REQUIRE(r.code == 0);
  std::istringstream in(r.output);
  std::string line;
  // Key lines start with two blanks and the key; section headers with '['; wrapped meanings with 8 blanks.
  std::vector<std::string> keys;
  bool species = false;
  size_t widest = 0;
  while (std::getline(in, line)) {
    widest = std::max(widest, line.size());
    if (line.rfind("[[species]]", 0) == 0) species = true;
    if (line.size() > 2 && line[0] == ' ' && line[1] == ' ' && line[2] != ' ' && !species)
      keys.push_back(line.substr(2, line.find(' ', 2) - 2));
  }
  CHECK(widest <= 100);  // fits a terminal
  std::vector<std::string> table;
  for (const auto& f : core::scene_fields()) table.push_back(f.key);
  std::sort(keys.begin(), keys.end());
  std::sort(table.begin(), table.end());
  CHECK(keys == table);
  CHECK_THAT(r.output, Catch::Matchers::Contains("  kick_impulse_max      5e-05 N*s        [0, 1000]"));
  CHECK_THAT(r.output, Catch::Matchers::Contains("[container]") && Catch::Matchers::Contains("  sides "));
  // Bounds as a reader writes them (issue 57): no binary noise, whole numbers whole, the seed's the parser's.
  CHECK_THAT(r.output, Catch::Matchers::Contains("[1e-06, 0.02]") &&
                           Catch::Matchers::Contains("[0, 9223372036854775807]"));
  CHECK_THAT(r.output, !Catch::Matchers::Contains("0000000000"));
  r = cli("scene " + kScene + " --set mu=0.5");
  REQUIRE(r.code == 0);
  CHECK_THAT(r.output,
             Catch::Matchers::Contains("\nmu = 0.5 ") && Catch::Matchers::Contains("dipole_safe_dt_s"));
  r = cli("scene " + kScene + " --set chi=2");
  CHECK(r.code == 2);
  CHECK_THAT(r.output, Catch::Matchers::Contains("chi = 2.0 is not allowed"));
}

TEST_CASE("gallery: one tile per long-lasting arch, re-simulated without a trajectory, in PDF, SVG and PNG",
          "[gallery][app][heavy]") {
  fs::path d = temp_dir("gallery");
  REQUIRE(cli("run " + kScene + " --duration 18 --seed 4 --quiet --out " + (d / "run").string()).code == 0);
  REQUIRE_FALSE(fs::exists(d / "run" / "trajectory.sstraj"));
  std::istringstream arches(slurp(d / "run" / "arches.csv"));
  std::string line;
  long n = -1;
  while (std::getline(arches, line)) ++n;
  REQUIRE(n >= 2);
  auto r = cli("gallery " + (d / "run").string() + " --out " + (d / "sheet.svg").string() + " --tile 160");
  REQUIRE(r.code == 0);
  CHECK_THAT(r.output, Catch::Matchers::Contains(std::to_string(n) + " arches"));
  // Vector: no bitmap anywhere, grains as paths (about 60 in each outlet view), labels as text with the
  // arch's descriptors.
  const std::string svg = slurp(d / "sheet.svg");
  const auto count = test::count_of;
  CHECK(count(svg, "<image") == 0);
  CHECK(count(svg, "<path") > 40 * n);
  CHECK(count(svg, "\u03b8max") == n + 1);  // each tile, and the footer that explains it
  CHECK(count(svg, "span ") == n);
  CHECK(count(svg, "rise ") >= n);
  // Force chains: each tile's contact network on top (more paths), the range named in the title.
  REQUIRE(cli("gallery " + (d / "run").string() + " --force-chains 1:10 --out " + (d / "chains.svg").string())
              .code == 0);
  const std::string chains = slurp(d / "chains.svg");
  CHECK(count(chains, "<path") > count(svg, "<path") + 5 * n);
  CHECK(count(chains, "force chains from 1 N") == 1);
  auto bad = cli("gallery " + (d / "run").string() + " --force-chains 5:1 --out " + (d / "x.svg").string());
  CHECK(bad.code == 2);
  CHECK_THAT(bad.output, Catch::Matchers::Contains("--force-chains 5:1"));
  CHECK_FALSE(fs::exists(d / "x.svg"));
  REQUIRE(
      cli("gallery " + (d / "run").string() + " --out " + (d / "sheet.pdf").string() + " --tile 160").code ==
      0);
  const std::string pdf = slurp(d / "sheet.pdf");
  CHECK(pdf.rfind("%PDF", 0) == 0);
  CHECK(count(pdf, "/Subtype /Image") == 0);
  // One column: the narrowest sheet; its title and footer are wrapped, never cut: nothing touches the edges.
  REQUIRE(cli("gallery " + (d / "run").string() + " --columns 1 --out " + (d / "sheet.png").string() +
              " --tile 160")
              .code == 0);
  int w = 0, h = 0, c = 0;
  unsigned char* px = stbi_load((d / "sheet.png").c_str(), &w, &h, &c, 3);
  REQUIRE(px);
  long inked = 0;
  for (int y = 0; y < h; ++y)
    for (int x : {0, 1, w - 2, w - 1})
      for (int k = 0; k < 3; ++k) inked += px[(static_cast<size_t>(y) * w + x) * 3 + k] < 240;
  for (int x = 0; x < w; ++x)
    for (int y : {0, 1, h - 2, h - 1})
      for (int k = 0; k < 3; ++k) inked += px[(static_cast<size_t>(y) * w + x) * 3 + k] < 240;
  stbi_image_free(px);
  CHECK(inked == 0);
  CHECK(h > w);  // the tiles stacked
  // Its own sheet is replaced with --force; a user's file is not.
  CHECK(
      cli("gallery " + (d / "run").string() + " --force --out " + (d / "sheet.png").string() + " --tile 160")
          .code == 0);
  std::ofstream(d / "poster.pdf") << "%PDF-1.4 my poster";
  r = cli("gallery " + (d / "run").string() + " --force --out " + (d / "poster.pdf").string() +
          " --tile 160");
  CHECK(r.code == 2);
  CHECK(slurp(d / "poster.pdf") == "%PDF-1.4 my poster");
  CHECK(cli("gallery " + (d / "run").string() + " --out " + (d / "sheet.jpg").string()).code == 2);
  for (const auto& e : fs::directory_iterator(d))
    CHECK(e.path().filename().string().find(".tiles-") == std::string::npos);  // no temporary tiles left
}

TEST_CASE("timeline: the discharge staircase with clog bands in PDF, SVG and PNG, vector text, owned outputs",
          "[export][app][heavy]") {
  fs::path d = temp_dir("timeline");
  REQUIRE(cli("run " + kScene + " --duration 10 --quiet --out " + (d / "r").string()).code == 0);
  for (const char* ext : {".svg", ".pdf", ".png"}) {
    const fs::path out = d / (std::string("t") + ext);
    const auto r = cli("timeline " + (d / "r").string() + " --out " + out.string());
    INFO(r.output);
    REQUIRE(r.code == 0);
    CHECK_THAT(r.output, Catch::Matchers::Contains("clogs -> "));
    const std::string body = slurp(out);
    if (std::string(ext) == ".svg") {
      // Text kept as text: the axis labels, the legend, the command that made it; no bitmap inside.
      CHECK_THAT(body, Catch::Matchers::Contains("cumulative exits") &&
                           Catch::Matchers::Contains("time since the outlet opened") &&
                           Catch::Matchers::Contains("original: ") && Catch::Matchers::Contains("added: ") &&
                           Catch::Matchers::Contains("clog ended by the rule") &&
                           Catch::Matchers::Contains("siloscope timeline"));
      CHECK(body.find("<image") == std::string::npos);
      // Each species' staircase in the colour the movies give it (the paper palette's red and blue).
      CHECK_THAT(
          body, Catch::Matchers::Contains("stroke: #d92924") && Catch::Matchers::Contains("stroke: #2961d9"));
    } else if (std::string(ext) == ".pdf") {
      CHECK(body.rfind("%PDF", 0) == 0);
      CHECK(body.find("/Subtype /Image") == std::string::npos);
    } else {
      CHECK(body.substr(1, 3) == "PNG");
    }
  }
  // Not over an existing figure without --force; --force replaces its own figure, never the user's file.
  CHECK(cli("timeline " + (d / "r").string() + " --out " + (d / "t.svg").string()).code == 2);
  CHECK(cli("timeline " + (d / "r").string() + " --out " + (d / "t.svg").string() + " --force").code == 0);
  std::ofstream(d / "mine.svg") << "<svg>my own drawing</svg>\n";
  const auto refused =
      cli("timeline " + (d / "r").string() + " --out " + (d / "mine.svg").string() + " --force");
  CHECK(refused.code == 2);
  CHECK(slurp(d / "mine.svg") == "<svg>my own drawing</svg>\n");
  // Bad requests name what is allowed and write nothing.
  CHECK_THAT(cli("timeline " + (d / "r").string() + " --out " + (d / "t.jpg").string()).output,
             Catch::Matchers::Contains(".pdf, .svg or .png"));
  CHECK_THAT(cli("timeline " + (d / "r").string() + " --to 50 --out " + (d / "u.svg").string()).output,
             Catch::Matchers::Contains("the run's duration (10 s)"));
  CHECK_FALSE(fs::exists(d / "u.svg"));
  CHECK(cli("timeline " + d.string() + " --out " + (d / "v.svg").string()).code == 2);
}

TEST_CASE("frame: one picture of a recording at a clog, a time or a frame, at any size, in PNG, SVG and PDF",
          "[export][app][heavy]") {
  const fs::path rec = recorded("frame");
  const fs::path d = rec.parent_path();
  auto r = cli("frame " + rec.string() + " --at clog:1 --size 640x360 --camera outlet --out " +
               (d / "clog-{frame}.png").string());
  INFO(r.output);
  REQUIRE(r.code == 0);
  CHECK_THAT(r.output, Catch::Matchers::Contains("clog:1 at frame "));
  const std::string written =
      r.output.substr(r.output.rfind("-> ") + 3, r.output.rfind('\n') - r.output.rfind("-> ") - 3);
  const std::string png = slurp(written);
  REQUIRE(png.size() > 24);
  CHECK(png.substr(1, 3) == "PNG");
  // The PNG header's width and height (big-endian at bytes 16 and 20).
  auto be32 = [&](size_t at) {
    return (static_cast<unsigned char>(png[at]) << 24) | (static_cast<unsigned char>(png[at + 1]) << 16) |
           (static_cast<unsigned char>(png[at + 2]) << 8) | static_cast<unsigned char>(png[at + 3]);
  };
  CHECK(be32(16) == 640u);
  CHECK(be32(20) == 360u);
  // Vector: circles as shapes, no bitmap.
  REQUIRE(cli("frame " + rec.string() + " --at t:1.0 --out " + (d / "t1.svg").string()).code == 0);
  CHECK(slurp(d / "t1.svg").find("<image") == std::string::npos);
  // Never over a file; bad requests name the option and what is allowed.
  CHECK(cli("frame " + rec.string() + " --at t:1.0 --out " + (d / "t1.svg").string()).code == 2);
  CHECK_THAT(cli("frame " + rec.string() + " --at soon --out " + (d / "x.png").string()).output,
             Catch::Matchers::Contains("clog:K, rule:K, t:SECONDS or frame:N"));
  CHECK_THAT(cli("frame " + rec.string() + " --at clog:99 --out " + (d / "x.png").string()).output,
             Catch::Matchers::Contains("--at") && Catch::Matchers::Contains("clog 99 does not exist"));
  CHECK_THAT(cli("frame " + rec.string() + " --at t:1 --color nope --out " + (d / "x.png").string()).output,
             Catch::Matchers::Contains("--color"));
  CHECK_FALSE(fs::exists(d / "x.png"));
}

TEST_CASE("filmstrip: one clog at several times in one row, vector with its text, every tile captioned",
          "[export][app][heavy]") {
  const fs::path rec = recorded("filmstrip");
  const fs::path d = rec.parent_path();
  for (const char* ext : {".svg", ".pdf", ".png"}) {
    const fs::path out = d / (std::string("strip") + ext);
    const auto r = cli("filmstrip " + rec.string() + " --clog 1 --times=-1,0,1 --out " + out.string());
    INFO(r.output);
    REQUIRE(r.code == 0);
    CHECK_THAT(r.output, Catch::Matchers::Contains("clog 1 at 3 times"));
    const std::string body = slurp(out);
    if (std::string(ext) == ".svg") {
      CHECK_THAT(body, Catch::Matchers::Contains("-1 s (t = ") && Catch::Matchers::Contains("+0 s (t = ") &&
                           Catch::Matchers::Contains("+1 s (t = ") && Catch::Matchers::Contains("clog 1 of"));
      CHECK(body.find("<image") == std::string::npos);
    } else if (std::string(ext) == ".pdf") {
      CHECK(body.find("/Subtype /Image") == std::string::npos);
    } else {
      CHECK(body.substr(1, 3) == "PNG");
    }
  }
  CHECK_THAT(cli("filmstrip " + rec.string() + " --clog 7 --out " + (d / "x.svg").string()).output,
             Catch::Matchers::Contains("--clog 7: the recording has 1 clogs"));
  CHECK_THAT(cli("filmstrip " + rec.string() + " --times=-1,soon --out " + (d / "x.svg").string()).output,
             Catch::Matchers::Contains("'soon' is not a number of seconds"));
  CHECK_THAT(cli("filmstrip " + rec.string() + " --times=-30 --out " + (d / "x.svg").string()).output,
             Catch::Matchers::Contains("--times: -30 s from clog 1's start"));
  CHECK_FALSE(fs::exists(d / "x.svg"));
  CHECK(cli("filmstrip " + rec.string() + " --times=0 --out " + (d / "strip.svg").string()).code == 2);
}

TEST_CASE(
    "journal figures: filmstrip gallery timeline and frame at 85 mm have text of 7 to 9 pt read from the PDF",
    "[export][app][heavy]") {
  const fs::path rec = recorded("journal");
  const fs::path d = rec.parent_path();
  // The page's width (MediaBox) and every font size the content streams set (Tf), read back from the PDF.
  std::ofstream(d / "pdf_text.py") << R"(import re, sys, zlib
b = open(sys.argv[1], "rb").read()
box = [float(v) for v in re.search(rb"/MediaBox \[ *([-\d.]+) ([-\d.]+) ([-\d.]+) ([-\d.]+) *\]", b).groups()]
sizes = []
for m in re.finditer(rb"stream\r?\n(.*?)\r?\nendstream", b, re.S):
    try:
        sizes += [float(v) for v in re.findall(rb"/F\d+ ([\d.]+) Tf", zlib.decompress(m.group(1)))]
    except zlib.error:
        pass
print(f"width_mm {(box[2] - box[0]) * 25.4 / 72:.2f} smallest_pt {min(sizes):.2f} largest_pt {max(sizes):.2f} "
      f"texts {len(sizes)}")
)";
  auto pdf_text = [&](const fs::path& pdf) {
    const fs::path log = d / (pdf.stem().string() + ".log");
    REQUIRE(test::sh("/usr/bin/python3 " + (d / "pdf_text.py").string() + " " + pdf.string() + " > " +
                     log.string() + " 2>&1") == 0);
    std::istringstream in(slurp(log));
    std::string k1, k2, k3, k4;
    double width = 0, smallest = 0, largest = 0;
    long texts = 0;
    in >> k1 >> width >> k2 >> smallest >> k3 >> largest >> k4 >> texts;
    INFO(slurp(log));
    CHECK(texts >= 5);
    return std::array<double, 3>{width, smallest, largest};
  };
  const std::string strip = "filmstrip " + rec.string() + " --clog 1 --times=-1,-0.5,0,1 ";
  for (const auto& [how, mm] : std::vector<std::pair<std::string, double>>{
           {"--width 85mm", 85.0}, {"--width single", 86.0}, {"--width 7in", 177.8}}) {
    const fs::path pdf = d / ("strip_" + std::to_string(static_cast<int>(mm)) + ".pdf");
    const auto r = cli(strip + how + " --font-scale 2 --out " + pdf.string());
    INFO(how << ": " << r.output);
    REQUIRE(r.code == 0);
    const auto [width, smallest, largest] = pdf_text(pdf);
    CHECK(std::fabs(width - mm) < 0.1);
    // At that width the text is 7 to 9 pt, whatever the look's text size (here 2x).
    CHECK(smallest >= 7.0 - 1e-6);
    CHECK(largest <= 9.0 + 1e-6);
  }
  // Without a width, the sheet's own size (the old look: captions under 7 pt).
  REQUIRE(cli(strip + "--out " + (d / "strip_own.pdf").string()).code == 0);
  CHECK(pdf_text(d / "strip_own.pdf")[1] < 7.0);
  // The legend (each species, the arch's ring) and a scale bar, as text in the SVG.
  REQUIRE(cli(strip + "--width 85mm --out " + (d / "strip.svg").string()).code == 0);
  const std::string svg = slurp(d / "strip.svg");
  CHECK_THAT(svg, Catch::Matchers::Contains(">original<") && Catch::Matchers::Contains(">added<") &&
                      Catch::Matchers::Contains(">arch members<") && Catch::Matchers::Contains(" cm<"));
  // The gallery (of a run long enough for the rule to remove an arch, at 6.5 s) and the timeline at a double
  // and a single column.
  REQUIRE(cli("run " + kScene + " --duration 7 --quiet --out " + (d / "run7").string()).code == 0);
  REQUIRE(cli("gallery " + (d / "run7").string() + " --width double --out " + (d / "gallery.pdf").string())
              .code == 0);
  const auto g = pdf_text(d / "gallery.pdf");
  CHECK(std::fabs(g[0] - 178.0) < 0.1);
  CHECK(g[1] >= 7.0 - 1e-6);
  REQUIRE(cli("timeline " + rec.string() + " --width 85mm --out " + (d / "timeline.pdf").string()).code == 0);
  const auto t = pdf_text(d / "timeline.pdf");
  CHECK(std::fabs(t[0] - 85.0) < 0.1);
  CHECK(t[1] >= 7.0 - 1e-6);
  CHECK(t[2] <= 9.0 + 1e-6);
  // frame: the vector picture at a single column, with the colour bar of its colouring.
  REQUIRE(cli("frame " + rec.string() +
              " --at clog:1 --camera outlet --color speed --font-scale 2 --width 85mm " + "--out " +
              (d / "frame.pdf").string())
              .code == 0);
  const auto f = pdf_text(d / "frame.pdf");
  CHECK(std::fabs(f[0] - 85.0) < 0.1);
  CHECK(f[1] >= 7.0 - 1e-6);
  CHECK(f[2] <= 9.0 + 1e-6);
  CHECK_THAT(
      cli("frame " + rec.string() + " --at clog:1 --width 85mm --out " + (d / "x.png").string()).output,
      Catch::Matchers::Contains("--width 85mm: a page width is for a vector figure"));
  CHECK_FALSE(fs::exists(d / "x.png"));
  // Widths refused name the value and what is allowed; nothing is written.
  CHECK_THAT(cli(strip + "--width 85 --out " + (d / "x.pdf").string()).output,
             Catch::Matchers::Contains("--width 85: expected a length with its unit"));
  CHECK_THAT(cli(strip + "--width 500mm --out " + (d / "x.pdf").string()).output,
             Catch::Matchers::Contains("--width 500mm: 500 mm is outside 40 mm to 300 mm"));
  CHECK_THAT(cli("timeline " + rec.string() + " --width wide --out " + (d / "x.pdf").string()).output,
             Catch::Matchers::Contains("--width wide"));
  CHECK_FALSE(fs::exists(d / "x.pdf"));
}

TEST_CASE("a drain's jam is named as the movie names it in the timeline's legend", "[export][app]") {
  fs::path d = temp_dir("timeline_drain");
  const std::string scene = std::string(SILOSCOPE_SOURCE_DIR) + "/assets/scenes/hopper-drain.toml";
  REQUIRE(cli("run " + scene + " --duration 5 --quiet --out " + (d / "r").string()).code == 0);
  REQUIRE(slurp(d / "r" / "metadata.toml").find("drain_outcome = \"jammed\"") != std::string::npos);
  REQUIRE(cli("timeline " + (d / "r").string() + " --out " + (d / "t.svg").string()).code == 0);
  const std::string body = slurp(d / "t.svg");
  CHECK_THAT(body, Catch::Matchers::Contains("jammed (the clog that ended the drain)"));
  CHECK_THAT(body, !Catch::Matchers::Contains("clogged at the run"));
}

TEST_CASE("gallery and timeline refuse a run whose metadata.toml was cut or edited, naming the file",
          "[export][app]") {
  fs::path d = temp_dir("gallery_cut");
  REQUIRE(cli("run " + kScene + " --duration 12 --quiet --out " + (d / "r").string()).code == 0);
  const std::string meta = slurp(d / "r" / "metadata.toml");
  std::ofstream(d / "r" / "metadata.toml") << meta.substr(0, meta.size() / 2);
  for (const std::string& cmd : {std::string("gallery"), std::string("timeline")}) {
    const auto r = cli(cmd + " " + (d / "r").string() + " --out " + (d / (cmd + ".svg")).string());
    CHECK(r.code == 2);
    CHECK_THAT(r.output, Catch::Matchers::Contains("metadata.toml") && Catch::Matchers::Contains("manifest"));
    CHECK_FALSE(fs::exists(d / (cmd + ".svg")));
  }
}

TEST_CASE(
    "record --annotate: a note with an arrow to its point while its time lasts, malformed notes refused",
    "[app][record]") {
  const fs::path d = temp_dir("annotate");
  auto yellow_pixels = [](const fs::path& png) {
    int w = 0, h = 0, c = 0;
    unsigned char* px = stbi_load(png.c_str(), &w, &h, &c, 3);
    REQUIRE(px);
    long n = 0;
    for (long i = 0; i < static_cast<long>(w) * h; ++i)
      n += px[3 * i] > 230 && px[3 * i + 1] > 170 && px[3 * i + 1] < 230 && px[3 * i + 2] < 60;
    stbi_image_free(px);
    return n;
  };
  REQUIRE(cli("record " + kScene +
              " --duration 1 --size 320x180 --camera outlet --overlay none --arch-halo off --png-every 10 "
              "--annotate 0.5:1:0,0.3:here --quiet --out " +
              (d / "a").string())
              .code == 0);
  // Frame 0 (t = 0) is before the note; frame 20 (t = 0.66 s) shows its arrow in the note's yellow.
  CHECK(yellow_pixels(d / "a" / "frames" / "frame_000000.png") == 0);
  CHECK(yellow_pixels(d / "a" / "frames" / "frame_000020.png") > 10);
  CHECK(slurp(d / "a" / "metadata.toml").find("annotate = [\"0.5:1:0,0.3:here\"]") != std::string::npos);
  for (const std::string bad : {"1:0.5:0,0:x", "0:1:0:x", "0:1:0,0:", "a:1:0,0:x"}) {
    const auto r = cli("record " + kScene + " --duration 1 --size 320x180 --quiet --annotate " + bad +
                       " --out " + (d / "b").string());
    INFO(bad << "\n" << r.output);
    CHECK(r.code == 2);
    CHECK(r.output.find("--annotate '" + bad + "'") != std::string::npos);
    CHECK(!fs::exists(d / "b"));
  }
}

TEST_CASE("record --species-color: any species' colour, the paper's two included, in grains and legend",
          "[app][record]") {
  const fs::path d = temp_dir("species_color");
  REQUIRE(cli("record " + kScene +
              " --duration 0.2 --size 320x180 --camera outlet --png-every 1 --species-color original=#00ff00 "
              "--quiet --out " +
              (d / "a").string())
              .code == 0);
  int w = 0, h = 0, c = 0;
  unsigned char* px = stbi_load((d / "a" / "frames" / "frame_000000.png").c_str(), &w, &h, &c, 3);
  REQUIRE(px);
  long green = 0;
  for (long i = 0; i < static_cast<long>(w) * h; ++i)
    green += px[3 * i] < 40 && px[3 * i + 1] > 215 && px[3 * i + 2] < 40;
  stbi_image_free(px);
  CHECK(green > 500);  // the original disks, now green
  CHECK(slurp(d / "a" / "metadata.toml").find("species_colors = [\"original=#00ff00\"]") !=
        std::string::npos);
  const auto bad = cli("record " + kScene + " --duration 0.2 --quiet --species-color big=#00ff00 --out " +
                       (d / "b").string());
  CHECK(bad.code == 2);
  CHECK(bad.output.find("no species named 'big' (this scene has original, added)") != std::string::npos);
  const auto hex = cli("record " + kScene + " --duration 0.2 --quiet --species-color added=green --out " +
                       (d / "b").string());
  CHECK(hex.code == 2);
  CHECK(hex.output.find("the colour is not #rrggbb") != std::string::npos);
}

TEST_CASE("record --panel-title names each panel of a comparison, one each, in order", "[app][record]") {
  const fs::path d = temp_dir("panel_title");
  const auto ok =
      cli("record " + kScene + " --duration 0.5 --size 320x180 --quiet --compare mu=1 --panel-title " +
          "'no magnets' --panel-title 'magnets on' --out " + (d / "a").string());
  INFO(ok.output);
  REQUIRE(ok.code == 0);
  CHECK(slurp(d / "a" / "metadata.toml").find("panel_labels = [\"no magnets\", \"magnets on\"]") !=
        std::string::npos);
  const auto one = cli("record " + kScene + " --duration 0.5 --quiet --compare mu=1 --panel-title x --out " +
                       (d / "b").string());
  CHECK(one.code == 2);
  CHECK(one.output.find("--panel-title: 1 given for 2 panels (one each, in order)") != std::string::npos);
  const auto single =
      cli("record " + kScene + " --duration 0.5 --quiet --panel-title x --out " + (d / "b").string());
  CHECK(single.code == 2);
  CHECK(single.output.find("a single movie has no panels to title") != std::string::npos);
  CHECK(!fs::exists(d / "b"));
}

TEST_CASE(
    "frame re-simulates a run written without a trajectory, as far as --at needs, and leaves nothing behind",
    "[app][heavy]") {
  const fs::path d = temp_dir("frame_resim");
  REQUIRE(cli("run " + kScene + " --seed 3 --duration 8 --quiet --out " + (d / "r").string()).code == 0);
  REQUIRE(!fs::exists(d / "r" / "trajectory.sstraj"));
  const auto r =
      cli("frame " + (d / "r").string() + " --at clog:1 --size 320x180 --out " + (d / "f.png").string());
  INFO(r.output);
  REQUIRE(r.code == 0);
  CHECK(r.output.find("clog:1 at frame") != std::string::npos);
  CHECK(fs::file_size(d / "f.png") > 1000);
  for (const auto& e : fs::directory_iterator(d))
    CHECK(e.path().filename().string().find("resim") == std::string::npos);
  const auto bad = cli("frame " + (d / "r").string() + " --at clog:9 --out " + (d / "g.png").string());
  CHECK(bad.code == 2);
  CHECK(bad.output.find("--at clog:9: the run has 2 clogs (numbered from 1)") != std::string::npos);
}

TEST_CASE("runs of every earlier trajectory version open: inspect, frame and export",
          "[app][history][heavy]") {
  // One file of each earlier version in the test data (version 1 stores a scene with a key since retired),
  // and one of the current version made now.
  const std::string corpus = std::string(SILOSCOPE_SOURCE_DIR) + "/tests/fuzz/corpus/trajectory/";
  const fs::path d = temp_dir("history");
  const std::vector<std::pair<std::string, int>> files = {
      {corpus + "small.sstraj", 1},
      {corpus + "small-v2.sstraj", 2},
      {(recorded("history_v3") / "trajectory.sstraj").string(), 3}};
  for (const auto& [file, version] : files) {
    INFO(file);
    std::ifstream in(file, std::ios::binary);
    char head[12] = {};
    in.read(head, sizeof head);
    CHECK(std::string(head, 8) == "SILOTRAJ");
    CHECK(static_cast<int>(static_cast<unsigned char>(head[8])) == version);
    const std::string tag = "v" + std::to_string(version);
    std::ofstream(d / (tag + ".txt")) << "snapshot " << (d / (tag + ".png")).string() << " 320x180\n";
    const auto insp = cli("inspect " + file + " --script " + (d / (tag + ".txt")).string());
    INFO(insp.output);
    CHECK(insp.code == 0);
    CHECK(fs::file_size(d / (tag + ".png")) > 1000);
    CHECK(cli("frame " + file + " --at t:0 --out " + (d / (tag + "-frame.png")).string()).code == 0);
    CHECK(cli("export " + file + " --format csv --out " + (d / (tag + ".csv")).string()).code == 0);
    // A retired key is said once, by name, and the run opens all the same.
    if (version == 1)
      CHECK_THAT(insp.output, Catch::Contains("arrest_speed") && Catch::Contains("earlier siloscope"));
    else
      CHECK_THAT(insp.output, !Catch::Contains("earlier siloscope"));
  }
}
