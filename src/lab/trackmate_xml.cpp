// TrackMate's XML file read as its spots table (lab/trackmate_xml.h).
#include "lab/trackmate_xml.h"

#include <set>
#include <unordered_map>

#include <pugixml.hpp>

#include "core/error.h"

namespace lab {

io::CsvTable trackmate_xml(const std::string& path, long& untracked) {
  pugi::xml_document doc;
  const pugi::xml_parse_result ok = doc.load_file(path.c_str());
  if (!ok)
    throw core::InputError(path + ": not readable as XML (" + ok.description() + ", at byte " +
                           std::to_string(ok.offset) + ")");
  const pugi::xml_node model = doc.child("TrackMate").child("Model");
  if (!model || !model.child("AllSpots"))
    throw core::InputError(path +
                           ": not a TrackMate file (expected <TrackMate><Model><AllSpots>: save it from "
                           "TrackMate, or export its spots as CSV)");
  const std::string time_unit = model.attribute("timeunits").as_string();
  const bool seconds =
      time_unit == "sec" || time_unit == "s" || time_unit == "second" || time_unit == "seconds";
  // Each spot's track, from the edges of the tracks the file's filter kept.
  std::set<std::string> kept;
  const pugi::xml_node filtered = model.child("FilteredTracks");
  for (pugi::xml_node t : filtered.children("TrackID")) kept.insert(t.attribute("TRACK_ID").as_string());
  std::unordered_map<std::string, std::string> track_of;
  for (pugi::xml_node track : model.child("AllTracks").children("Track")) {
    const std::string id = track.attribute("TRACK_ID").as_string();
    if (id.empty()) throw core::InputError(path + ": a <Track> without TRACK_ID");
    if (filtered && !kept.count(id)) continue;
    for (pugi::xml_node e : track.children("Edge"))
      for (const char* end : {"SPOT_SOURCE_ID", "SPOT_TARGET_ID"})
        track_of[e.attribute(end).as_string()] = id;
  }
  std::vector<std::string> header{"TRACK_ID", "POSITION_X", "POSITION_Y", "FRAME", "RADIUS"};
  if (seconds) header.push_back("POSITION_T");
  std::vector<std::vector<std::string>> rows;
  std::vector<long> lines;
  long n = 0;
  for (pugi::xml_node frame : model.child("AllSpots").children("SpotsInFrame"))
    for (pugi::xml_node spot : frame.children("Spot")) {
      ++n;
      auto it = track_of.find(spot.attribute("ID").as_string());
      if (it == track_of.end()) {
        ++untracked;
        continue;
      }
      std::vector<std::string> row{it->second};
      for (size_t c = 1; c < header.size(); ++c) {
        const pugi::xml_attribute a = spot.attribute(header[c].c_str());
        if (!a)
          throw core::InputError(path + ": spot " + spot.attribute("ID").as_string() + " has no " +
                                 header[c] + " attribute (TrackMate writes it for every spot)");
        row.push_back(a.as_string());
      }
      rows.push_back(std::move(row));
      lines.push_back(n);
    }
  return io::CsvTable::from_rows(path, "TrackMate spots", std::move(header), std::move(rows),
                                 std::move(lines));
}

}  // namespace lab
