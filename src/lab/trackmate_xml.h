// TrackMate's XML file (Fiji: File > Save, or "Export tracks to XML"): its spots with the track each belongs
// to, read into the rows of TrackMate's spots table (TRACK_ID, POSITION_X, POSITION_Y, FRAME, RADIUS, and
// POSITION_T when its time unit is seconds), which lab::read_tracks then reads as it reads the CSV. A spot's
// track is the track whose edges link it; spots in no track, or in a track the file's filter left out
// (FilteredTracks), are skipped and counted. Messages number the spots (1 for the first) where a CSV has
// lines.
#pragma once

#include <string>

#include "io/csv_table.h"

namespace lab {

// Throws core::InputError naming the file and what is wrong (not XML, not TrackMate's, an attribute missing).
io::CsvTable trackmate_xml(const std::string& path, long& untracked);

}  // namespace lab
