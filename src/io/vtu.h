// VTK XML files for ParaView (and any VTK reader): one UnstructuredGrid per frame with the grains as vertices
// and their data, the container's walls as lines, and a .pvd collection that makes them a time series.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
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

// The container at displacement (dx, dy) (m): its bottom, side and top walls as line cells; cell data wall
// (the core::Wall index). The obstacle is a block of its own (vtu_obstacle).
std::string vtu_walls(const core::Geometry& geo, double dx = 0, double dy = 0,
                      VtuEncoding enc = VtuEncoding::Binary);

// Cell data of vtu_cells: a name and one value per cell.
using CellFloats = std::pair<std::string, std::vector<float>>;
using CellInts = std::pair<std::string, std::vector<std::int32_t>>;
// Any cells in the plane (z = 0): `cells` index `points`, `types` are VTK cell types, cell data as given.
std::string vtu_cells(const std::vector<core::Vec2>& points,
                      const std::vector<std::vector<std::int64_t>>& cells,
                      const std::vector<std::uint8_t>& types, const std::vector<CellFloats>& floats,
                      const std::vector<CellInts>& ints, VtuEncoding enc = VtuEncoding::Binary);
// The polygon grains of a frame as polygon cells at their true shape and orientation (cell data force, angle,
// radius, species, id, arch, sides); disks are left to the grains' points.
std::string vtu_shapes(const core::Frame& f, VtuEncoding enc = VtuEncoding::Binary);
// The frame's blocking arch as a polyline through its members' centres (no cell when none stands).
std::string vtu_arch(const core::Frame& f, VtuEncoding enc = VtuEncoding::Binary);
// Force chains from the frame's contacts: a line cell between the centres of each pair in contact, and from
// each grain's centre to where it touches a wall; cell data force (N, normal), tangential_force (N, signed;
// 0 from a version-1 contacts file), a (a wall: -1 - its index), b.
std::string vtu_chains(const core::Frame& f, VtuEncoding enc = VtuEncoding::Binary);

// The obstacle at displacement (dx, dy), filled: a disk as a 64-sided polygon cell, a bar as a rectangle (no
// cell without an obstacle); cell data wall.
std::string vtu_obstacle(const core::Geometry& geo, double dx = 0, double dy = 0,
                         VtuEncoding enc = VtuEncoding::Binary);

struct PvdEntry {
  double t;          // s
  int part;          // 0 grains, 1 walls, 2 shapes, 3 arch, 4 force chains, 5 obstacle (each its own block)
  std::string file;  // relative to the .pvd
};
// A ParaView collection of the entries, a time series with one part per kind of file.
std::string pvd(const std::vector<PvdEntry>& entries);

}  // namespace io
