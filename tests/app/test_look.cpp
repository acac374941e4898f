// One look for every picture (issue 50, point 2): a recording keeps its look (species colours, background,
// text size) in its metadata, and every picture made from it afterwards (frame, filmstrip, gallery, timeline)
// is drawn in that look unless told otherwise.
#include <catch2/catch.hpp>

#include <stb_image.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <regex>
#include <string>

#include "helpers.h"

namespace fs = std::filesystem;

namespace {

struct Rgb {
  int r, g, b;
};

// The colours the recording is made with, and the paper palette's defaults that must not appear.
constexpr Rgb kGreen{0x00, 0xc0, 0x00}, kMagenta{0xc0, 0x00, 0xc0};
constexpr Rgb kPaperRed{0xd9, 0x29, 0x24}, kPaperBlue{0x29, 0x61, 0xd9};

struct Picture {
  int w = 0, h = 0;
  std::vector<unsigned char> rgb;
  explicit Picture(const fs::path& p) {
    int c = 0;
    unsigned char* px = stbi_load(p.c_str(), &w, &h, &c, 3);
    REQUIRE(px);
    rgb.assign(px, px + static_cast<size_t>(w) * h * 3);
    stbi_image_free(px);
  }
  long count(Rgb c, int tol = 12) const {
    long n = 0;
    for (size_t i = 0; i + 2 < rgb.size(); i += 3)
      n += std::abs(rgb[i] - c.r) <= tol && std::abs(rgb[i + 1] - c.g) <= tol &&
           std::abs(rgb[i + 2] - c.b) <= tol;
    return n;
  }
  // The share of pixels darker than a quarter of full brightness: the background dominates a picture.
  double dark_share() const {
    long n = 0;
    for (size_t i = 0; i + 2 < rgb.size(); i += 3) n += (rgb[i] + rgb[i + 1] + rgb[i + 2]) < 3 * 64;
    return static_cast<double>(n) / (static_cast<double>(w) * h);
  }
};

// The largest font size, px, an SVG's text is set in (matplotlib writes "font: ... 18px ...").
double largest_font(const std::string& svg) {
  static const std::regex font(R"(font:[^;"]*?([0-9.]+)px)");
  double most = 0;
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), font); it != std::sregex_iterator(); ++it)
    most = std::max(most, std::stod((*it)[1]));
  return most;
}

}  // namespace

TEST_CASE("pictures made from a recording use its look: species colours, dark background, text size",
          "[app][look][heavy]") {
  using test::cli;
  const fs::path d = test::temp_dir("look");
  const std::string rec = (d / "rec").string();
  // 18 s of seed 4 hold three clogs and three long-lasting arches (the gallery's tiles).
  const auto made = cli("record " + test::kScene +
                        " --duration 18 --seed 4 --size 320x180 --species-color original=#00c000 "
                        "--species-color added=#c000c0 --background dark --font-scale 2 --quiet --out " +
                        rec);
  INFO(made.output);
  REQUIRE(made.code == 0);
  struct Made {
    std::string what, args, out;
  };
  const std::vector<Made> pictures = {
      {"frame", "frame " + rec + " --at clog:2 --size 640x360", "frame.png"},
      {"filmstrip", "filmstrip " + rec + " --clog 2", "strip.png"},
      {"gallery", "gallery " + rec + " --tile 160", "gallery.png"},
      {"timeline", "timeline " + rec, "timeline.png"},
  };
  for (const auto& p : pictures) {
    const auto r = cli(p.args + " --out " + (d / p.out).string());
    INFO(p.what << ": " << r.output);
    REQUIRE(r.code == 0);
    const Picture pic(d / p.out);
    // A timeline draws the species as lines, the others as disks: fewer pixels, the same colours.
    const long least = p.what == "timeline" ? 30 : 300;
    CHECK(pic.count(kGreen) > least);
    CHECK(pic.count(kMagenta) > least);
    CHECK(pic.count(kPaperRed) == 0);
    CHECK(pic.count(kPaperBlue) == 0);
    CHECK(pic.dark_share() > 0.5);
  }
  // The text size comes from the recording too; an option given says otherwise for itself alone.
  REQUIRE(cli("timeline " + rec + " --out " + (d / "big.svg").string()).code == 0);
  REQUIRE(cli("timeline " + rec + " --font-scale 1 --out " + (d / "small.svg").string()).code == 0);
  const double big = largest_font(test::slurp(d / "big.svg")),
               small = largest_font(test::slurp(d / "small.svg"));
  INFO("largest font: the recording's look " << big << " px, --font-scale 1 " << small << " px");
  CHECK(big > 1.6 * small);
  REQUIRE(cli("frame " + rec + " --at clog:2 --size 640x360 --background white --out " +
              (d / "white.png").string())
              .code == 0);
  const Picture white(d / "white.png");
  CHECK(white.dark_share() < 0.2);
  CHECK(white.count(kGreen) > 300);
}
