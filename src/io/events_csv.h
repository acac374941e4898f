// Event streams as CSV files with a header: exits.csv, clogs.csv, arches.csv. Times in s, lengths in m.
#pragma once

#include <filesystem>
#include <string>

#include "core/frame.h"

namespace io {

std::string exits_csv(const core::Events& ev);
std::string clogs_csv(const core::Events& ev);
std::string arches_csv(const core::Events& ev);

// Write the three files into `dir` (each atomically).
void write_events(const std::filesystem::path& dir, const core::Events& ev);

// Read them back. Throws core::InputError naming the file, the line and what is wrong (a missing file,
// a wrong header, a truncated or malformed row).
core::Events read_events(const std::filesystem::path& dir);

}  // namespace io
