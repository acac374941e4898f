// TrackMate's XML file (Fiji: File > Save, or "Export tracks to XML"): its spots with the track each belongs
// to, read as the rows of TrackMate's spots table (TRACK_ID, POSITION_X, POSITION_Y, FRAME, RADIUS, and
// POSITION_T when its time unit is seconds), a slice at a time as lab::read_tracks reads a CSV. A spot's
// track is the track whose edges link it; a spot in no track, or in a track the file's filter left out
// (FilteredTracks), is a row with an empty TRACK_ID (skipped and counted, as in a CSV). Each row's line is
// its <Spot>'s line in the file.
//
// Read as a stream (expat, Debian's libexpat1-dev), twice: first the tracks' edges (after the spots in the
// file), then the spots. Memory holds each spot's track (8 bytes a spot) and one slice of rows, not the file:
// a DOM of a 10-minute film's XML (3.6 million spots, about a gigabyte) took several times the file's size.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "io/csv_table.h"

namespace lab {

class TrackMateXml {
 public:
  // Reads the tracks. Throws core::InputError naming the file and what is wrong (not XML, not TrackMate's, an
  // id that is not a whole number).
  explicit TrackMateXml(const std::string& path);
  ~TrackMateXml();
  TrackMateXml(const TrackMateXml&) = delete;
  TrackMateXml& operator=(const TrackMateXml&) = delete;
  // The next spots, about `max_rows` (a few more: the file is parsed a block at a time), into `slice`; false
  // when none were left. Throws core::InputError for a spot without a position, frame or radius.
  bool next(io::CsvTable& slice, std::size_t max_rows);

  struct Parse;  // the parser's state (trackmate_xml.cpp)

 private:
  std::string path_;
  std::vector<std::string> header_;
  std::vector<std::pair<std::int32_t, std::int32_t>> track_of_;  // (spot, track), by spot
  std::unique_ptr<Parse> spots_;                                 // the second pass
};

}  // namespace lab
