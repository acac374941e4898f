// VTK XML files for ParaView (and any VTK reader): one UnstructuredGrid per frame with the grains as vertices
// and their data, the container's walls as lines, and a .pvd collection that makes them a time series.
#pragma once

#include <string>
#include <vector>

#include "core/frame.h"
#include "core/geometry.h"

namespace io {

// ASCII (readable, about 8 times larger) or VTK's appended raw binary with each array zlib-compressed.
enum class VtuEncoding { Binary, Ascii };

// The grains of a frame: points at their centres (z = 0), one vertex cell each, point data radius (m, of the
// disk of equal area), extent (m, circumradius: a polygon's reach), velocity (m/s, 3 components), force (N),
// species (index), arch (1 for members of the blocking arch), id, angle (rad), sides (0 disk, 3-8 polygon);
// field data TimeValue (s), ContainerOffset (m) and SpeciesNames (the names of the species indices).
std::string vtu_grains(const core::Frame& f, const std::vector<std::string>& species_names = {},
                       VtuEncoding enc = VtuEncoding::Binary);

// The container at displacement (dx, dy) (m): its bottom, side and top walls as line cells, and the obstacle
// (a disk as a 64-sided polygon, a bar as a rectangle) as a closed polyline; cell data wall (the core::Wall
// index).
std::string vtu_walls(const core::Geometry& geo, double dx = 0, double dy = 0,
                      VtuEncoding enc = VtuEncoding::Binary);

struct PvdEntry {
  double t;          // s
  int part;          // 0 grains, 1 walls
  std::string file;  // relative to the .pvd
};
// A ParaView collection of the entries, a time series with one part per kind of file.
std::string pvd(const std::vector<PvdEntry>& entries);

}  // namespace io
