#include "io/vtu.h"

#include <cmath>
#include <cstdio>

#include "core/format.h"

namespace io {

namespace {
std::string num(double v) {
  return core::format_g(v, 8);
}

// An ASCII data array: `values` already formatted, separated by blanks. Field data (tuples > 0) must say how
// many tuples it holds.
std::string array(const char* type, const char* name, int components, const std::string& values,
                  int tuples = 0) {
  std::string s = "        <DataArray type=\"" + std::string(type) + "\"";
  if (name) s += " Name=\"" + std::string(name) + "\"";
  if (components > 1) s += " NumberOfComponents=\"" + std::to_string(components) + "\"";
  if (tuples > 0) s += " NumberOfTuples=\"" + std::to_string(tuples) + "\"";
  return s + " format=\"ascii\">\n" + values + "\n        </DataArray>\n";
}

std::string grid(size_t points, size_t cells, const std::string& body) {
  return "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" "
         "byte_order=\"LittleEndian\">\n"
         "  <UnstructuredGrid>\n" +
         body.substr(0, body.find("<!--piece-->")) + "    <Piece NumberOfPoints=\"" + std::to_string(points) +
         "\" NumberOfCells=\"" + std::to_string(cells) + "\">\n" +
         body.substr(body.find("<!--piece-->") + 12) + "    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";
}
}  // namespace

std::string vtu_grains(const core::Frame& f) {
  const size_t n = f.particles.size();
  std::vector<char> in_arch(n, 0);
  for (int id : f.arch)
    if (id >= 0 && static_cast<size_t>(id) < n) in_arch[static_cast<size_t>(id)] = 1;
  std::string pts, radius, extent, vel, force, species, arch, id, angle, sides, conn, offsets, types;
  for (size_t i = 0; i < n; ++i) {
    const core::Particle& p = f.particles[i];
    pts += num(p.x) + " " + num(p.y) + " 0 ";
    radius += num(p.radius) + " ";
    extent += num(p.radius * core::polygon_extent(p.sides)) + " ";
    vel += num(p.vx) + " " + num(p.vy) + " 0 ";
    force += num(p.force) + " ";
    species += std::to_string(core::species_index(p.species)) + " ";
    arch += in_arch[i] ? "1 " : "0 ";
    id += std::to_string(i) + " ";
    angle += num(p.angle) + " ";
    sides += std::to_string(p.sides) + " ";
    conn += std::to_string(i) + " ";
    offsets += std::to_string(i + 1) + " ";
    types += "1 ";  // VTK_VERTEX
  }
  std::string body =
      "    <FieldData>\n" + array("Float64", "TimeValue", 1, num(f.t), 1) +
      array("Float64", "ContainerOffset", 2, num(f.container_x) + " " + num(f.container_y), 1) +
      "    </FieldData>\n<!--piece-->";
  body += "      <PointData Scalars=\"radius\" Vectors=\"velocity\">\n" +
          array("Float32", "radius", 1, radius) + array("Float32", "extent", 1, extent) +
          array("Float32", "velocity", 3, vel) + array("Float32", "force", 1, force) +
          array("Int32", "species", 1, species) + array("Int32", "arch", 1, arch) +
          array("Int32", "id", 1, id) + array("Float32", "angle", 1, angle) +
          array("Int32", "sides", 1, sides) + "      </PointData>\n";
  body += "      <Points>\n" + array("Float32", nullptr, 3, pts) + "      </Points>\n";
  body += "      <Cells>\n" + array("Int64", "connectivity", 1, conn) +
          array("Int64", "offsets", 1, offsets) + array("UInt8", "types", 1, types) + "      </Cells>\n";
  return grid(n, n, body);
}

std::string vtu_walls(const core::Geometry& geo, double dx, double dy) {
  std::vector<core::Vec2> points;
  std::vector<std::vector<size_t>> cells;
  std::vector<int> kinds;
  auto line = [&](const std::vector<core::Vec2>& ps, int kind) {
    std::vector<size_t> c;
    for (const auto& p : ps) c.push_back(points.size()), points.push_back({p.x + dx, p.y + dy});
    cells.push_back(c);
    kinds.push_back(kind);
  };
  for (core::Wall w : {core::Wall::HopperLeft, core::Wall::HopperRight, core::Wall::SiloLeft,
                       core::Wall::SiloRight, core::Wall::Top}) {
    const core::Segment& s = geo.walls[static_cast<int>(w)];
    line({s.a, s.b}, static_cast<int>(w));
  }
  if (geo.obstacle.present()) {
    const core::Obstacle& ob = geo.obstacle;
    std::vector<core::Vec2> outline;
    if (ob.kind == core::Obstacle::Kind::Disk) {
      for (int k = 0; k <= 64; ++k) {
        const double a = 2 * 3.14159265358979323846 * k / 64;
        outline.push_back(
            {ob.centre.x + 0.5 * ob.width * std::cos(a), ob.centre.y + 0.5 * ob.width * std::sin(a)});
      }
    } else {
      const double hw = 0.5 * ob.width, hh = 0.5 * ob.height;
      outline = {{ob.centre.x - hw, ob.centre.y - hh},
                 {ob.centre.x + hw, ob.centre.y - hh},
                 {ob.centre.x + hw, ob.centre.y + hh},
                 {ob.centre.x - hw, ob.centre.y + hh},
                 {ob.centre.x - hw, ob.centre.y - hh}};
    }
    line(outline, static_cast<int>(core::Wall::Obstacle));
  }
  std::string pts, conn, offsets, types, wall;
  size_t end = 0;
  for (const auto& p : points) pts += num(p.x) + " " + num(p.y) + " 0 ";
  for (size_t c = 0; c < cells.size(); ++c) {
    for (size_t i : cells[c]) conn += std::to_string(i) + " ";
    end += cells[c].size();
    offsets += std::to_string(end) + " ";
    types += cells[c].size() == 2 ? "3 " : "4 ";  // VTK_LINE, VTK_POLY_LINE
    wall += std::to_string(kinds[c]) + " ";
  }
  std::string body = "<!--piece-->      <CellData Scalars=\"wall\">\n" + array("Int32", "wall", 1, wall) +
                     "      </CellData>\n      <Points>\n" + array("Float32", nullptr, 3, pts) +
                     "      </Points>\n      <Cells>\n" + array("Int64", "connectivity", 1, conn) +
                     array("Int64", "offsets", 1, offsets) + array("UInt8", "types", 1, types) +
                     "      </Cells>\n";
  return grid(points.size(), cells.size(), body);
}

std::string pvd(const std::vector<PvdEntry>& entries) {
  std::string s =
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      "  <Collection>\n";
  for (const auto& e : entries)
    s += "    <DataSet timestep=\"" + num(e.t) + "\" group=\"\" part=\"" + std::to_string(e.part) +
         "\" file=\"" + e.file + "\"/>\n";
  return s + "  </Collection>\n</VTKFile>\n";
}

}  // namespace io
