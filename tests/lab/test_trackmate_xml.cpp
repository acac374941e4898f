// TrackMate's XML read as a stream (lab/trackmate_xml.h): slices of its spots with each spot's track and
// line, the tracks the filter left out and spots in no track as rows without a track, and clear refusals.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <string>

#include "core/error.h"
#include "helpers.h"
#include "lab/trackmate_xml.h"

namespace fs = std::filesystem;

namespace {

// 40 tracks of 60 frames (2400 spots, about 250 kB: several of the reader's blocks), track 7 left out by the
// filter, and one spot (ID 99999, after frame 30's) in no track.
fs::path write_file(const fs::path& dir, long& lines_before_first_spot) {
  const fs::path p = dir / "tm.xml";
  std::ofstream x(p);
  x << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<TrackMate version=\"7.11.1\">\n"
       "<Model spatialunits=\"pixel\" timeunits=\"sec\">\n<AllSpots nspots=\"2401\">\n";
  lines_before_first_spot = 5;  // the four lines above and the first <SpotsInFrame>
  for (int k = 0; k < 60; ++k) {
    x << "<SpotsInFrame frame=\"" << k << "\">\n";
    for (int t = 0; t < 40; ++t)
      x << "<Spot ID=\"" << 1000 * t + k << "\" name=\"ID" << 1000 * t + k << "\" POSITION_X=\""
        << 10 * t + 0.5 << "\" POSITION_Y=\"" << 2 * k << "\" POSITION_Z=\"0.0\" POSITION_T=\"" << 0.04 * k
        << "\" FRAME=\"" << k << "\" RADIUS=\"4.5\" QUALITY=\"20.0\" MEAN_INTENSITY_CH1=\"120.25\"/>\n";
    if (k == 30) x << "<Spot ID=\"99999\" POSITION_X=\"1\" POSITION_Y=\"1\" FRAME=\"30\" RADIUS=\"4.5\"/>\n";
    x << "</SpotsInFrame>\n";
  }
  x << "</AllSpots>\n<AllTracks>\n";
  for (int t = 0; t < 40; ++t) {
    x << "<Track name=\"Track_" << t << "\" TRACK_ID=\"" << t << "\">\n";
    for (int k = 1; k < 60; ++k)
      x << "<Edge SPOT_SOURCE_ID=\"" << 1000 * t + k - 1 << "\" SPOT_TARGET_ID=\"" << 1000 * t + k
        << "\"/>\n";
    x << "</Track>\n";
  }
  x << "</AllTracks>\n<FilteredTracks>\n";
  for (int t = 0; t < 40; ++t)
    if (t != 7) x << "<TrackID TRACK_ID=\"" << t << "\"/>\n";
  x << "</FilteredTracks>\n</Model>\n</TrackMate>\n";
  return p;
}

}  // namespace

TEST_CASE("TrackMate XML: spots come in slices, each with its track and its line", "[lab]") {
  const fs::path d = test::temp_dir("trackmate_xml");
  long before = 0;
  const fs::path p = write_file(d, before);
  REQUIRE(fs::file_size(p) > 3 * 65536);  // several blocks
  lab::TrackMateXml xml(p.string());
  io::CsvTable slice;
  long rows = 0, slices = 0, untracked = 0, filtered = 0;
  while (xml.next(slice, 500)) {
    ++slices;
    REQUIRE(slice.rows() >= 1);
    for (size_t r = 0; r < slice.rows(); ++r, ++rows) {
      const std::string track = slice.text(r, "TRACK_ID");
      const double x = slice.num(r, "POSITION_X");
      if (x == 1) {  // spot 99999
        CHECK(track.empty());
        ++untracked;
        continue;
      }
      const int t = static_cast<int>((x - 0.5) / 10);
      if (t == 7) {
        CHECK(track.empty());
        ++filtered;
      } else {
        CHECK(track == std::to_string(t));
      }
      // Its line: after the lines before the first spot, one per spot and two per frame before it.
      const long frame = static_cast<long>(slice.num(r, "FRAME"));
      const long index = frame * 40 + t + (frame > 30 ? 1 : 0);
      CHECK(slice.line(r) == before + 1 + index + 2 * frame);
      CHECK(slice.num(r, "POSITION_T") == Approx(0.04 * static_cast<double>(frame)));
    }
  }
  CHECK(rows == 2401);
  CHECK(untracked == 1);
  CHECK(filtered == 60);
  CHECK(slices >= 3);
}

TEST_CASE(
    "TrackMate XML: a spot without a position and an id that is not a number are refused with their line",
    "[lab]") {
  const fs::path d = test::temp_dir("trackmate_xml_bad");
  const std::string head =
      "<?xml version=\"1.0\"?>\n<TrackMate>\n<Model timeunits=\"frame\">\n<AllSpots>\n<SpotsInFrame "
      "frame=\"0\">\n";
  const std::string tracks =
      "</SpotsInFrame>\n</AllSpots>\n<AllTracks>\n<Track TRACK_ID=\"3\">\n<Edge SPOT_SOURCE_ID=\"1\" "
      "SPOT_TARGET_ID=\"2\"/>\n</Track>\n</AllTracks>\n</Model>\n</TrackMate>\n";
  std::ofstream(d / "nox.xml")
      << head
      << "<Spot ID=\"1\" POSITION_X=\"3\" POSITION_Y=\"4\" FRAME=\"0\" RADIUS=\"2\"/>\n"
         "<Spot ID=\"2\" POSITION_Y=\"4\" FRAME=\"1\" RADIUS=\"2\"/>\n"
      << tracks;
  io::CsvTable slice;
  lab::TrackMateXml nox((d / "nox.xml").string());
  CHECK_THROWS_WITH(nox.next(slice, 100),
                    Catch::Matchers::Contains("nox.xml:7: spot 2 has no POSITION_X attribute"));
  std::ofstream(d / "id.xml") << head << "<Spot ID=\"one\" POSITION_X=\"3\" POSITION_Y=\"4\" FRAME=\"0\"/>\n"
                              << tracks;
  lab::TrackMateXml id((d / "id.xml").string());
  CHECK_THROWS_WITH(id.next(slice, 100), Catch::Matchers::Contains("id.xml:6: <Spot> ID = 'one'") &&
                                             Catch::Matchers::Contains("whole numbers"));
  std::ofstream(d / "cut.xml") << head;
  CHECK_THROWS_WITH(lab::TrackMateXml((d / "cut.xml").string()),
                    Catch::Matchers::Contains("cut.xml: not readable as XML (no element found, at line 6)"));
}
