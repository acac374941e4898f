// Event streams as CSV files with a header: exits.csv, clogs.csv, arches.csv. Times in s, lengths in m.
#pragma once

#include <filesystem>
#include <string>

#include "core/frame.h"

namespace io {

#include <vector>

// The species' names of a scene, index = core::Species (the shorthand: "original", "added").
using SpeciesNames = std::vector<std::string>;
const SpeciesNames& shorthand_names();

std::string exits_csv(const core::Events& ev, const SpeciesNames& names = shorthand_names());
std::string clogs_csv(const core::Events& ev);
// n_added counts the members not of the first species (the shorthand: the added disks).
std::string arches_csv(const core::Events& ev, const SpeciesNames& names = shorthand_names());

// Write the three files into `dir` (each atomically).
void write_events(const std::filesystem::path& dir, const core::Events& ev,
                  const SpeciesNames& names = shorthand_names());

// Read them back. Throws core::InputError naming the file, the line and what is wrong (a missing file,
// a wrong header, a truncated or malformed row, a species not in `names`).
core::Events read_events(const std::filesystem::path& dir, const SpeciesNames& names = shorthand_names());

}  // namespace io
