// TrackMate's XML file read as its spots table, a slice at a time (lab/trackmate_xml.h).
#include "lab/trackmate_xml.h"

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cstdlib>
#include <cstring>

#include <expat.h>

#include "core/error.h"

namespace lab {

namespace {

constexpr size_t kBlock = 1 << 16;  // bytes parsed at a time

const char* attribute(const XML_Char** attrs, const char* name) {
  for (size_t i = 0; attrs[i]; i += 2)
    if (std::strcmp(attrs[i], name) == 0) return attrs[i + 1];
  return nullptr;
}

bool path_is(const std::vector<std::string>& stack, std::initializer_list<const char*> names) {
  if (stack.size() != names.size()) return false;
  size_t i = 0;
  for (const char* n : names)
    if (stack[i++] != n) return false;
  return true;
}

}  // namespace

struct TrackMateXml::Parse {
  std::string path;
  std::FILE* file = nullptr;
  XML_Parser parser = nullptr;
  bool at_end = false;
  std::vector<std::string> stack;  // the open elements
  std::string error;               // a handler's: the parse stopped
  // The first pass: the tracks.
  bool spots_seen = false, filtered = false;
  std::string time_unit;
  std::int32_t track = 0;
  bool in_track = false;
  std::vector<std::pair<std::int32_t, std::int32_t>> edges;  // (spot, track)
  std::vector<std::int32_t> kept;                            // the tracks the filter kept
  // The second pass: the spots.
  const TrackMateXml* owner = nullptr;
  std::vector<std::vector<std::string>> rows;
  std::vector<long> lines;

  Parse(const std::string& p, bool spots) : path(p) {
    file = std::fopen(p.c_str(), "rb");
    if (!file) throw core::InputError(p + ": cannot open the TrackMate file (" + std::strerror(errno) + ")");
    parser = XML_ParserCreate(nullptr);
    XML_SetUserData(parser, this);
    if (spots)
      XML_SetElementHandler(parser, spot_start, pop);
    else
      XML_SetElementHandler(parser, track_start, pop);
  }
  ~Parse() {
    if (parser) XML_ParserFree(parser);
    if (file) std::fclose(file);
  }
  Parse(const Parse&) = delete;
  Parse& operator=(const Parse&) = delete;

  // Parses the next block; false at the end of the file.
  bool step() {
    if (at_end) return false;
    char buffer[kBlock];
    const size_t n = std::fread(buffer, 1, kBlock, file);
    if (std::ferror(file)) throw core::InputError(path + ": cannot read the TrackMate file");
    at_end = n < kBlock;
    if (XML_Parse(parser, buffer, static_cast<int>(n), at_end) != XML_STATUS_OK) {
      if (!error.empty()) throw core::InputError(error);
      throw core::InputError(path + ": not readable as XML (" + XML_ErrorString(XML_GetErrorCode(parser)) +
                             ", at line " + std::to_string(XML_GetCurrentLineNumber(parser)) + ")");
    }
    return !at_end;
  }

  void fail(const std::string& what) {
    if (error.empty()) error = path + ":" + std::to_string(XML_GetCurrentLineNumber(parser)) + ": " + what;
    XML_StopParser(parser, XML_FALSE);
  }

  // An id attribute as a whole number (TrackMate's are Java ints); false after fail() otherwise.
  bool id(const XML_Char** attrs, const char* name, const char* element, std::int32_t& out) {
    const char* v = attribute(attrs, name);
    if (!v) {
      fail(std::string("a <") + element + "> without " + name);
      return false;
    }
    char* end = nullptr;
    errno = 0;
    const long x = std::strtol(v, &end, 10);
    if (end == v || *end || errno || x < INT32_MIN || x > INT32_MAX) {
      fail(std::string("<") + element + "> " + name + " = '" + v +
           "': TrackMate's ids are whole numbers (a file TrackMate saved?)");
      return false;
    }
    out = static_cast<std::int32_t>(x);
    return true;
  }

  static void pop(void* self, const XML_Char*) {
    Parse& p = *static_cast<Parse*>(self);
    if (!p.stack.empty()) p.stack.pop_back();
  }

  static void track_start(void* self, const XML_Char* name, const XML_Char** attrs) {
    Parse& p = *static_cast<Parse*>(self);
    const std::vector<std::string>& s = p.stack;
    if (path_is(s, {"TrackMate"}) && std::strcmp(name, "Model") == 0) {
      const char* unit = attribute(attrs, "timeunits");
      p.time_unit = unit ? unit : "";
    } else if (path_is(s, {"TrackMate", "Model"}) && std::strcmp(name, "AllSpots") == 0) {
      p.spots_seen = true;
    } else if (path_is(s, {"TrackMate", "Model"}) && std::strcmp(name, "FilteredTracks") == 0) {
      p.filtered = true;
    } else if (path_is(s, {"TrackMate", "Model", "AllTracks"}) && std::strcmp(name, "Track") == 0) {
      p.in_track = p.id(attrs, "TRACK_ID", "Track", p.track);
    } else if (p.in_track && path_is(s, {"TrackMate", "Model", "AllTracks", "Track"}) &&
               std::strcmp(name, "Edge") == 0) {
      std::int32_t from = 0, to = 0;
      if (p.id(attrs, "SPOT_SOURCE_ID", "Edge", from) && p.id(attrs, "SPOT_TARGET_ID", "Edge", to)) {
        p.edges.emplace_back(from, p.track);
        p.edges.emplace_back(to, p.track);
      }
    } else if (path_is(s, {"TrackMate", "Model", "FilteredTracks"}) && std::strcmp(name, "TrackID") == 0) {
      std::int32_t t = 0;
      if (p.id(attrs, "TRACK_ID", "TrackID", t)) p.kept.push_back(t);
    }
    p.stack.emplace_back(name);
  }

  static void spot_start(void* self, const XML_Char* name, const XML_Char** attrs) {
    Parse& p = *static_cast<Parse*>(self);
    if (std::strcmp(name, "Spot") == 0 &&
        path_is(p.stack, {"TrackMate", "Model", "AllSpots", "SpotsInFrame"})) {
      std::int32_t spot = 0;
      if (p.id(attrs, "ID", "Spot", spot)) p.add(spot, attrs);
    }
    p.stack.emplace_back(name);
  }

  // A spot's row: its track's id (empty: none), then its attributes in the header's order.
  void add(std::int32_t spot, const XML_Char** attrs) {
    const auto& of = owner->track_of_;
    const auto it = std::lower_bound(of.begin(), of.end(), std::make_pair(spot, INT32_MIN));
    const bool tracked = it != of.end() && it->first == spot;
    std::vector<std::string> row{tracked ? std::to_string(it->second) : std::string()};
    const std::vector<std::string>& header = owner->header_;
    for (size_t c = 1; c < header.size(); ++c) {
      const char* v = attribute(attrs, header[c].c_str());
      if (!v && tracked) {
        fail("spot " + std::to_string(spot) + " has no " + header[c] +
             " attribute (TrackMate writes it for every spot)");
        return;
      }
      row.emplace_back(v ? v : "");
    }
    rows.push_back(std::move(row));
    lines.push_back(static_cast<long>(XML_GetCurrentLineNumber(parser)));
  }
};

TrackMateXml::TrackMateXml(const std::string& path) : path_(path) {
  Parse tracks(path, false);
  while (tracks.step()) {
  }
  if (!tracks.spots_seen)
    throw core::InputError(path +
                           ": not a TrackMate file (expected <TrackMate><Model><AllSpots>: save it from "
                           "TrackMate, or export its spots as CSV)");
  const std::string& u = tracks.time_unit;
  const bool seconds = u == "sec" || u == "s" || u == "second" || u == "seconds";
  header_ = {"TRACK_ID", "POSITION_X", "POSITION_Y", "FRAME", "RADIUS"};
  if (seconds) header_.push_back("POSITION_T");
  // Each spot's track, from the edges of the tracks the file's filter kept.
  std::vector<std::int32_t>& kept = tracks.kept;
  std::sort(kept.begin(), kept.end());
  track_of_ = std::move(tracks.edges);
  if (tracks.filtered)
    track_of_.erase(std::remove_if(track_of_.begin(), track_of_.end(),
                                   [&](const auto& e) {
                                     return !std::binary_search(kept.begin(), kept.end(), e.second);
                                   }),
                    track_of_.end());
  std::sort(track_of_.begin(), track_of_.end());
  track_of_.erase(std::unique(track_of_.begin(), track_of_.end(),
                              [](const auto& a, const auto& b) { return a.first == b.first; }),
                  track_of_.end());
  track_of_.shrink_to_fit();
  spots_ = std::make_unique<Parse>(path, true);
  spots_->owner = this;
}

TrackMateXml::~TrackMateXml() = default;

bool TrackMateXml::next(io::CsvTable& slice, std::size_t max_rows) {
  Parse& p = *spots_;
  p.rows.clear();
  p.lines.clear();
  while (p.rows.size() < max_rows && p.step()) {
  }
  if (p.rows.empty()) return false;
  slice = io::CsvTable::from_rows(path_, "TrackMate spots", header_, std::move(p.rows), std::move(p.lines));
  p.rows = {};
  p.lines = {};
  return true;
}

}  // namespace lab
