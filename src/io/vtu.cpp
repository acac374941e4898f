#include "io/vtu.h"

#include <zlib.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <type_traits>

#include "core/error.h"
#include "core/forces.h"
#include "core/format.h"

namespace io {

namespace {
std::string num(double v) {
  return core::format_g(v, 8);
}

// The arrays of one file, written as ASCII (`values` formatted, separated by blanks) or, by default, as VTK's
// appended raw binary, each array zlib-compressed (header UInt64: blocks, block size, last block size, then
// each block's compressed size; one block per array).
class Arrays {
 public:
  explicit Arrays(VtuEncoding enc) : enc_(enc) {}
  // One array; `raw` its little-endian binary values (binary files), `ascii` their text (ASCII files). Field
  // data (tuples > 0) says how many tuples it holds.
  std::string array(const char* type, const char* name, int components, const std::string& ascii,
                    const std::string& raw, int tuples = 0) {
    std::string s = "        <DataArray type=\"" + std::string(type) + "\"";
    if (name) s += " Name=\"" + std::string(name) + "\"";
    if (components > 1) s += " NumberOfComponents=\"" + std::to_string(components) + "\"";
    if (tuples > 0) s += " NumberOfTuples=\"" + std::to_string(tuples) + "\"";
    if (enc_ == VtuEncoding::Ascii) return s + " format=\"ascii\">\n" + ascii + "\n        </DataArray>\n";
    s += " format=\"appended\" offset=\"" + std::to_string(appended_.size()) + "\"/>\n";
    uLongf bound = compressBound(static_cast<uLong>(raw.size()));
    std::string packed(bound, '\0');
    if (compress2(reinterpret_cast<Bytef*>(&packed[0]), &bound, reinterpret_cast<const Bytef*>(raw.data()),
                  static_cast<uLong>(raw.size()), 6) != Z_OK)
      throw core::RuntimeFault("VTU export: zlib could not compress an array");
    packed.resize(bound);
    const std::uint64_t header[4] = {raw.empty() ? 0u : 1u, raw.size(), raw.size(), packed.size()};
    appended_.append(reinterpret_cast<const char*>(header), raw.empty() ? 3 * 8 : 4 * 8);
    if (!raw.empty()) appended_ += packed;
    return s;
  }
  // The file around `body` (which holds "<!--piece-->" where the piece begins).
  std::string file(size_t points, size_t cells, const std::string& body) const {
    std::string head =
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" "
        "byte_order=\"LittleEndian\" header_type=\"UInt64\"";
    if (enc_ == VtuEncoding::Binary) head += " compressor=\"vtkZLibDataCompressor\"";
    std::string s = head + ">\n  <UnstructuredGrid>\n" + body.substr(0, body.find("<!--piece-->")) +
                    "    <Piece NumberOfPoints=\"" + std::to_string(points) + "\" NumberOfCells=\"" +
                    std::to_string(cells) + "\">\n" + body.substr(body.find("<!--piece-->") + 12) +
                    "    </Piece>\n  </UnstructuredGrid>\n";
    if (enc_ == VtuEncoding::Binary)
      s += "  <AppendedData encoding=\"raw\">\n   _" + appended_ + "\n  </AppendedData>\n";
    return s + "</VTKFile>\n";
  }
  bool ascii() const { return enc_ == VtuEncoding::Ascii; }

 private:
  VtuEncoding enc_;
  std::string appended_;
};

// Values collected both ways (the text only for ASCII files, the bytes only for binary ones).
template <typename T>
struct Column {
  explicit Column(bool as_text) : ascii(as_text) {}
  bool ascii;
  std::string text, raw;
  void add(T v) {
    if (ascii) {
      if constexpr (std::is_floating_point_v<T>)
        text += num(v) + " ";
      else
        text += std::to_string(v) + " ";
    } else {
      raw.append(reinterpret_cast<const char*>(&v), sizeof v);
    }
  }
};
}  // namespace

std::string vtu_grains(const core::Frame& f, const std::vector<std::string>& species_names, VtuEncoding enc) {
  const size_t n = f.particles.size();
  Arrays out(enc);
  const bool a = out.ascii();
  std::vector<char> in_arch(n, 0);
  for (int id : f.arch)
    if (id >= 0 && static_cast<size_t>(id) < n) in_arch[static_cast<size_t>(id)] = 1;
  Column<float> pts{a}, radius{a}, extent{a}, vel{a}, force{a}, angle{a};
  Column<std::int32_t> species{a}, arch{a}, id{a}, sides{a};
  Column<std::int64_t> conn{a}, offsets{a};
  Column<std::uint8_t> types{a};
  for (size_t i = 0; i < n; ++i) {
    const core::Particle& p = f.particles[i];
    pts.add(p.x), pts.add(p.y), pts.add(0.0f);
    radius.add(p.radius);
    extent.add(static_cast<float>(p.radius * core::polygon_extent(p.sides)));
    vel.add(p.vx), vel.add(p.vy), vel.add(0.0f);
    force.add(p.force);
    species.add(static_cast<std::int32_t>(core::species_index(p.species)));
    arch.add(in_arch[i] ? 1 : 0);
    id.add(static_cast<std::int32_t>(i));
    angle.add(p.angle);
    sides.add(p.sides);
    conn.add(static_cast<std::int64_t>(i));
    offsets.add(static_cast<std::int64_t>(i + 1));
    types.add(1);  // VTK_VERTEX
  }
  // Field data: the time, the container's displacement, and the species' names (index = the species array).
  Column<double> t{a}, offset{a};
  t.add(f.t), offset.add(f.container_x), offset.add(f.container_y);
  std::string names_raw;
  for (const auto& nm : species_names) names_raw += nm + std::string(1, '\0');
  std::string names_ascii;
  for (const auto& nm : species_names)
    for (char c : nm + std::string(1, '\0')) names_ascii += std::to_string(static_cast<int>(c)) + " ";
  std::string body = "    <FieldData>\n" + out.array("Float64", "TimeValue", 1, t.text, t.raw, 1) +
                     out.array("Float64", "ContainerOffset", 2, offset.text, offset.raw, 1);
  if (!species_names.empty())
    body += out.array("String", "SpeciesNames", 1, names_ascii, names_raw,
                      static_cast<int>(species_names.size()));
  body += "    </FieldData>\n<!--piece-->";
  // Each grain's pressure from its Love-Weber stress, when the frame's contacts carry their geometry.
  const std::vector<double> pressure = core::pressures(f);
  Column<float> pres{a};
  for (double v : pressure) pres.add(static_cast<float>(v));
  body += "      <PointData Scalars=\"radius\" Vectors=\"velocity\">\n" +
          out.array("Float32", "radius", 1, radius.text, radius.raw) +
          out.array("Float32", "extent", 1, extent.text, extent.raw) +
          out.array("Float32", "velocity", 3, vel.text, vel.raw) +
          out.array("Float32", "force", 1, force.text, force.raw) +
          out.array("Int32", "species", 1, species.text, species.raw) +
          out.array("Int32", "arch", 1, arch.text, arch.raw) + out.array("Int32", "id", 1, id.text, id.raw) +
          out.array("Float32", "angle", 1, angle.text, angle.raw) +
          out.array("Int32", "sides", 1, sides.text, sides.raw) +
          (pressure.empty() ? std::string() : out.array("Float32", "pressure", 1, pres.text, pres.raw)) +
          "      </PointData>\n";
  body += "      <Points>\n" + out.array("Float32", nullptr, 3, pts.text, pts.raw) + "      </Points>\n";
  body += "      <Cells>\n" + out.array("Int64", "connectivity", 1, conn.text, conn.raw) +
          out.array("Int64", "offsets", 1, offsets.text, offsets.raw) +
          out.array("UInt8", "types", 1, types.text, types.raw) + "      </Cells>\n";
  return out.file(n, n, body);
}

std::string vtu_walls(const core::Geometry& geo, double dx, double dy, VtuEncoding enc) {
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
  Arrays out(enc);
  const bool a = out.ascii();
  Column<float> pts{a};
  Column<std::int64_t> conn{a}, offsets{a};
  Column<std::uint8_t> types{a};
  Column<std::int32_t> wall{a};
  std::int64_t end = 0;
  for (const auto& p : points)
    pts.add(static_cast<float>(p.x)), pts.add(static_cast<float>(p.y)), pts.add(0.0f);
  for (size_t c = 0; c < cells.size(); ++c) {
    for (size_t i : cells[c]) conn.add(static_cast<std::int64_t>(i));
    end += static_cast<std::int64_t>(cells[c].size());
    offsets.add(end);
    types.add(cells[c].size() == 2 ? 3 : 4);  // VTK_LINE, VTK_POLY_LINE
    wall.add(kinds[c]);
  }
  std::string body =
      "<!--piece-->      <CellData Scalars=\"wall\">\n" + out.array("Int32", "wall", 1, wall.text, wall.raw) +
      "      </CellData>\n      <Points>\n" + out.array("Float32", nullptr, 3, pts.text, pts.raw) +
      "      </Points>\n      <Cells>\n" + out.array("Int64", "connectivity", 1, conn.text, conn.raw) +
      out.array("Int64", "offsets", 1, offsets.text, offsets.raw) +
      out.array("UInt8", "types", 1, types.text, types.raw) + "      </Cells>\n";
  return out.file(points.size(), cells.size(), body);
}

std::string vtu_cells(const std::vector<core::Vec2>& points,
                      const std::vector<std::vector<std::int64_t>>& cells,
                      const std::vector<std::uint8_t>& types, const std::vector<CellFloats>& floats,
                      const std::vector<CellInts>& ints, VtuEncoding enc) {
  Arrays out(enc);
  const bool a = out.ascii();
  Column<float> pts{a};
  Column<std::int64_t> conn{a}, offsets{a};
  Column<std::uint8_t> type{a};
  for (const auto& p : points)
    pts.add(static_cast<float>(p.x)), pts.add(static_cast<float>(p.y)), pts.add(0.0f);
  std::int64_t end = 0;
  for (size_t c = 0; c < cells.size(); ++c) {
    for (std::int64_t i : cells[c]) conn.add(i);
    end += static_cast<std::int64_t>(cells[c].size());
    offsets.add(end);
    type.add(types[c]);
  }
  std::string body = "<!--piece-->      <CellData>\n";
  for (const auto& [name, values] : floats) {
    Column<float> col{a};
    for (float v : values) col.add(v);
    body += out.array("Float32", name.c_str(), 1, col.text, col.raw);
  }
  for (const auto& [name, values] : ints) {
    Column<std::int32_t> col{a};
    for (std::int32_t v : values) col.add(v);
    body += out.array("Int32", name.c_str(), 1, col.text, col.raw);
  }
  body += "      </CellData>\n      <Points>\n" + out.array("Float32", nullptr, 3, pts.text, pts.raw) +
          "      </Points>\n      <Cells>\n" + out.array("Int64", "connectivity", 1, conn.text, conn.raw) +
          out.array("Int64", "offsets", 1, offsets.text, offsets.raw) +
          out.array("UInt8", "types", 1, type.text, type.raw) + "      </Cells>\n";
  return out.file(points.size(), cells.size(), body);
}

std::string vtu_obstacle(const core::Geometry& geo, double dx, double dy, VtuEncoding enc) {
  std::vector<core::Vec2> points;
  std::vector<std::vector<std::int64_t>> cells;
  std::vector<std::uint8_t> types;
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
    outline.pop_back();  // closed by the polygon cell itself
    std::vector<std::int64_t> cell;
    for (const auto& p : outline)
      cell.push_back(static_cast<std::int64_t>(points.size())), points.push_back({p.x + dx, p.y + dy});
    cells.push_back(cell);
    types.push_back(7);  // VTK_POLYGON: the obstacle filled
  }
  return vtu_cells(
      points, cells, types, {},
      {{"wall", std::vector<std::int32_t>(cells.size(), static_cast<std::int32_t>(core::Wall::Obstacle))}},
      enc);
}

std::string vtu_shapes(const core::Frame& f, VtuEncoding enc) {
  std::vector<core::Vec2> points;
  std::vector<std::vector<std::int64_t>> cells;
  std::vector<std::uint8_t> types;
  CellFloats force{"force", {}}, angle{"angle", {}}, radius{"radius", {}};
  CellInts species{"species", {}}, id{"id", {}}, arch{"arch", {}}, sides{"sides", {}};
  std::vector<char> in_arch(f.particles.size(), 0);
  for (int i : f.arch)
    if (i >= 0 && static_cast<size_t>(i) < in_arch.size()) in_arch[static_cast<size_t>(i)] = 1;
  for (size_t i = 0; i < f.particles.size(); ++i) {
    const core::Particle& p = f.particles[i];
    if (p.sides < 3) continue;
    const double R = p.radius * core::polygon_extent(p.sides);
    std::vector<std::int64_t> cell;
    for (int k = 0; k < p.sides; ++k) {
      const double a = p.angle + 2.0 * 3.14159265358979323846 * k / p.sides;
      cell.push_back(static_cast<std::int64_t>(points.size()));
      points.push_back({p.x + R * std::cos(a), p.y + R * std::sin(a)});
    }
    cells.push_back(cell);
    types.push_back(7);  // VTK_POLYGON
    force.second.push_back(p.force), angle.second.push_back(p.angle), radius.second.push_back(p.radius);
    species.second.push_back(static_cast<std::int32_t>(core::species_index(p.species)));
    id.second.push_back(static_cast<std::int32_t>(i)), arch.second.push_back(in_arch[i]);
    sides.second.push_back(p.sides);
  }
  return vtu_cells(points, cells, types, {force, angle, radius}, {species, id, arch, sides}, enc);
}

std::string vtu_arch(const core::Frame& f, VtuEncoding enc) {
  std::vector<core::Vec2> points;
  std::vector<std::vector<std::int64_t>> cells;
  std::vector<std::uint8_t> types;
  CellInts members{"members", {}};
  if (f.arch.size() >= 2) {
    std::vector<std::int64_t> cell;
    for (int i : f.arch) {
      if (i < 0 || static_cast<size_t>(i) >= f.particles.size()) continue;
      cell.push_back(static_cast<std::int64_t>(points.size()));
      points.push_back({f.particles[static_cast<size_t>(i)].x, f.particles[static_cast<size_t>(i)].y});
    }
    cells.push_back(cell);
    types.push_back(4);  // VTK_POLY_LINE
    members.second.push_back(static_cast<std::int32_t>(cell.size()));
  }
  return vtu_cells(points, cells, types, {}, {members}, enc);
}

std::string vtu_chains(const core::Frame& f, VtuEncoding enc) {
  std::vector<core::Vec2> points;
  std::vector<std::vector<std::int64_t>> cells;
  std::vector<std::uint8_t> types;
  CellFloats force{"force", {}}, tangential{"tangential_force", {}};
  CellInts a_id{"a", {}}, b_id{"b", {}};
  const size_t n = f.particles.size();
  for (const auto* list : {&f.contacts, &f.wall_contacts})
    for (const auto& c : *list) {
      const bool wall = c.a < 0;
      if (c.b < 0 || static_cast<size_t>(c.b) >= n || (!wall && static_cast<size_t>(c.a) >= n) ||
          (wall && !c.has_geometry()))
        continue;
      const auto& q = f.particles[static_cast<size_t>(c.b)];
      const auto k = static_cast<std::int64_t>(points.size());
      if (wall)
        points.push_back({c.px, c.py});
      else
        points.push_back({f.particles[static_cast<size_t>(c.a)].x, f.particles[static_cast<size_t>(c.a)].y});
      points.push_back({q.x, q.y});
      cells.push_back({k, k + 1});
      types.push_back(3);  // VTK_LINE
      force.second.push_back(c.force), tangential.second.push_back(c.ft);
      a_id.second.push_back(c.a), b_id.second.push_back(c.b);
    }
  return vtu_cells(points, cells, types, {force, tangential}, {a_id, b_id}, enc);
}

std::string pvd(const std::vector<PvdEntry>& entries) {
  static const char* const kPartNames[] = {"grains", "walls", "shapes", "arch", "force chains", "obstacle"};
  std::string s =
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      "  <Collection>\n";
  for (const auto& e : entries)
    s += "    <DataSet timestep=\"" + num(e.t) + "\" group=\"\" part=\"" + std::to_string(e.part) +
         "\" name=\"" + (e.part >= 0 && e.part < 6 ? kPartNames[e.part] : "part") + "\" file=\"" + e.file +
         "\"/>\n";
  return s + "  </Collection>\n</VTKFile>\n";
}

}  // namespace io
