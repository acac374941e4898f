// Tracked particles from a CSV file (lab/tracks.h).
#include "lab/tracks.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "core/error.h"
#include "core/format.h"
#include "io/csv_table.h"

namespace lab {

namespace {

struct Role {
  const char* key;                 // the map's name for it
  std::string ColumnMap::*field;   // where the map keeps it
  std::vector<const char*> names;  // the default names looked for
};

const std::vector<Role>& roles() {
  static const std::vector<Role> r = {
      {"time", &ColumnMap::time, {"t", "time", "t_s"}},
      {"frame", &ColumnMap::frame, {"frame"}},
      {"id", &ColumnMap::id, {"particle", "id", "track", "track_id"}},
      {"x", &ColumnMap::x, {"x"}},
      {"y", &ColumnMap::y, {"y"}},
      {"radius", &ColumnMap::radius, {"r", "radius"}},
      {"diameter", &ColumnMap::diameter, {"diameter", "d"}},
      {"angle", &ColumnMap::angle, {"angle"}},
      {"species", &ColumnMap::species, {"species"}},
  };
  return r;
}

std::string allowed_roles() {
  std::string s;
  for (const Role& r : roles()) s += (s.empty() ? "" : ", ") + std::string(r.key);
  return s;
}

// The column for a role: the mapped one (which must exist), else the first default name present, else "".
std::string find_column(const io::CsvTable& t, const ColumnMap& map, const Role& role) {
  const std::string& mapped = map.*(role.field);
  if (!mapped.empty()) {
    if (!t.has(mapped))
      throw core::InputError(t.path() + ": --columns " + role.key + "=" + mapped +
                             ": the file has no column '" + mapped + "'");
    return mapped;
  }
  for (const char* n : role.names)
    if (t.has(n)) return n;
  return "";
}

std::string looked_for(const Role& role) {
  std::string s;
  for (const char* n : role.names) s += (s.empty() ? "" : ", ") + std::string(n);
  return s;
}

}  // namespace

ColumnMap parse_column_map(const std::string& text, const std::string& option) {
  ColumnMap m;
  size_t start = 0;
  while (start <= text.size() && !text.empty()) {
    size_t comma = text.find(',', start);
    const std::string entry =
        text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    const size_t eq = entry.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == entry.size())
      throw core::InputError(option + " '" + text + "': entry '" + entry +
                             "' is not ROLE=COLUMN (roles: " + allowed_roles() + ")");
    const std::string key = entry.substr(0, eq), column = entry.substr(eq + 1);
    bool known = false;
    for (const Role& r : roles())
      if (key == r.key) m.*(r.field) = column, known = true;
    if (!known)
      throw core::InputError(option + " '" + text + "': '" + key +
                             "' is not a role (roles: " + allowed_roles() + ")");
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return m;
}

void parse_origin(const std::string& text, double& x, double& y) {
  const size_t comma = text.find(',');
  char* end = nullptr;
  bool ok = comma != std::string::npos;
  if (ok) {
    const std::string a = text.substr(0, comma), b = text.substr(comma + 1);
    x = std::strtod(a.c_str(), &end);
    ok = !a.empty() && *end == '\0' && std::isfinite(x);
    y = std::strtod(b.c_str(), &end);
    ok = ok && !b.empty() && *end == '\0' && std::isfinite(y);
  }
  if (!ok)
    throw core::InputError("--origin '" + text + "': expected X,Y (the outlet centre's pixel, e.g. 640,700)");
}

namespace {

// The columns of a track file, checked and named once; then each row read into a Detection.
class RowReader {
 public:
  RowReader(const io::CsvTable& t, const std::string& path, const ColumnMap& map, const Units& units,
            const core::Setup& setup, const core::Geometry& geo, Tracks& out)
      : t_(t), path_(path), units_(units), setup_(setup), geo_(geo), names_(setup.species_names()) {
    for (const Role& r : roles()) {
      col_[r.key] = find_column(t, map, r);
      if (!col_[r.key].empty()) out.columns_used.push_back(std::string(r.key) + "=" + col_[r.key]);
    }
    need("id");
    need("x");
    need("y");
    if (col_["time"].empty() && col_["frame"].empty())
      throw core::InputError(path +
                             ": no column for the time (looked for t, time, t_s, or frame numbers in frame; "
                             "name one with --columns time=COLUMN or frame=COLUMN)");
    by_frame_ = col_["time"].empty();
    if (by_frame_ && !(units.fps > 0))
      throw core::InputError(path + ": the file numbers frames (column " + col_["frame"] +
                             ") and has no times: give the frame rate with --fps (frames per second, > 0)");
    out.has_radius = has_radius_ = !col_["radius"].empty() || !col_["diameter"].empty();
    out.has_angle = has_angle_ = !col_["angle"].empty();
    out.has_species = has_species_ = !col_["species"].empty();
    scale_ = units.scale > 0 ? units.scale : 1.0;
    ysign_ = units.scale > 0 && !units.y_up ? -1.0 : 1.0;
  }

  // Row `row`: the detection, its time and its frame number (-1 without one).
  Detection read(size_t row, double& time, long& number) {
    Detection d{};
    d.line = static_cast<long>(row + 2);
    const double idv = finite(row, col_["id"]);
    if (idv != std::floor(idv) || std::fabs(idv) > 9e15)
      throw core::InputError(line_of(row) + ": column " + col_["id"] + " is '" + t_.text(row, col_["id"]) +
                             "', not a whole number (particle ids are integers)");
    d.id = static_cast<long>(idv);
    number = -1;
    if (!col_["frame"].empty()) {
      const double f = finite(row, col_["frame"]);
      if (f != std::floor(f) || f < 0)
        throw core::InputError(line_of(row) + ": column " + col_["frame"] + " is '" +
                               t_.text(row, col_["frame"]) + "', not a frame number (a whole number >= 0)");
      number = static_cast<long>(f);
    }
    time = by_frame_ ? static_cast<double>(number) / units_.fps : finite(row, col_["time"]);
    d.x = (finite(row, col_["x"]) - units_.origin_x) * scale_;
    d.y = ysign_ * (finite(row, col_["y"]) - units_.origin_y) * scale_;
    d.species = has_species_ ? species(row) : 0;
    size(row, d);
    d.angle = has_angle_ ? finite(row, col_["angle"]) : 0.0;
    check_inside(row, d);
    return d;
  }

 private:
  const io::CsvTable& t_;
  const std::string& path_;
  const Units& units_;
  const core::Setup& setup_;
  const core::Geometry& geo_;
  const std::vector<std::string> names_;
  std::map<std::string, std::string> col_;
  bool by_frame_ = false, has_radius_ = false, has_angle_ = false, has_species_ = false;
  double scale_ = 1, ysign_ = 1;

  void need(const char* key) {
    if (!col_[key].empty()) return;
    for (const Role& r : roles())
      if (r.key == std::string(key))
        throw core::InputError(path_ + ": no column for " + key + " (looked for " + looked_for(r) +
                               "; name it with --columns " + key + "=COLUMN)");
  }
  std::string line_of(size_t row) const { return path_ + ":" + std::to_string(row + 2); }
  double finite(size_t row, const std::string& c) const {
    const double v = t_.num(row, c);
    if (!std::isfinite(v))
      throw core::InputError(line_of(row) + ": column " + c + " is '" + t_.text(row, c) +
                             "', not a finite number");
    return v;
  }

  // Species: a name of the scene's or its index.
  int species(size_t row) {
    const int n_species = static_cast<int>(setup_.species.size());
    const std::string& s = t_.text(row, col_["species"]);
    auto it = std::find(names_.begin(), names_.end(), s);
    if (it != names_.end()) return static_cast<int>(it - names_.begin());
    char* end = nullptr;
    const long k = std::strtol(s.c_str(), &end, 10);
    if (s.empty() || *end != '\0' || k < 0 || k >= n_species) {
      std::string list;
      for (const auto& n : names_) list += (list.empty() ? "" : ", ") + n;
      throw core::InputError(line_of(row) + ": column " + col_["species"] + " is '" + s +
                             "': not a species of the geometry scene (" + list + ", or 0 to " +
                             std::to_string(n_species - 1) + ")");
    }
    return static_cast<int>(k);
  }

  // The grain's radius from a radius or diameter column (without a species column, the species whose mean
  // radius is nearest); the species' radius without one.
  void size(size_t row, Detection& d) {
    const int n_species = static_cast<int>(setup_.species.size());
    if (!has_radius_) {
      d.r = setup_.species[static_cast<size_t>(d.species)].radius;
      return;
    }
    const bool diameter = col_["radius"].empty();
    const std::string& c = diameter ? col_["diameter"] : col_["radius"];
    const double v = finite(row, c) * scale_ * (diameter ? 0.5 : 1.0);
    if (!(v > 0))
      throw core::InputError(line_of(row) + ": column " + c + " is '" + t_.text(row, c) +
                             "': a grain's size must be > 0");
    d.r = v;
    if (has_species_ || n_species <= 1) return;
    double best = INFINITY;
    for (int k = 0; k < n_species; ++k) {
      const double e = std::fabs(std::log(v / setup_.species[static_cast<size_t>(k)].radius));
      if (e < best) best = e, d.species = k;
    }
  }

  // Inside the container, or below the outlet where grains fall: a centre beyond a wall or above the top by
  // more than a diameter is a calibration error, not a grain.
  void check_inside(size_t row, const Detection& d) const {
    const core::Vec2 p{d.x, d.y};
    const double slack = 2 * d.r;
    const bool outside = d.y > geo_.total_height + slack || d.x < geo_.x_left - slack ||
                         d.x > geo_.x_right + slack || (d.y >= slack && geo_.side_clearance(p, 0) < -slack);
    if (outside)
      throw core::InputError(line_of(row) + ": particle " + std::to_string(d.id) + " at (" +
                             core::format_g(d.x, 4) + ", " + core::format_g(d.y, 4) +
                             ") m lies outside the container (x from " + core::format_g(geo_.x_left, 4) +
                             " to " + core::format_g(geo_.x_right, 4) + " m, y up to " +
                             core::format_g(geo_.total_height, 4) +
                             " m, the outlet's centre at 0, 0): check --scale, --origin and --y-up");
  }
};

}  // namespace

Tracks read_tracks(const std::string& path, const ColumnMap& map, const Units& units,
                   const core::Setup& setup, const core::Geometry& geo) {
  const io::CsvTable t = io::CsvTable::read(path, "tracked particles");
  Tracks out;
  out.source = path;
  out.rows = static_cast<long>(t.rows());
  RowReader reader(t, path, map, units, setup, geo, out);
  std::map<double, TrackFrame> frames;  // by time
  for (size_t row = 0; row < t.rows(); ++row) {
    double time = 0;
    long number = -1;
    const Detection d = reader.read(row, time, number);
    TrackFrame& f = frames[time];
    f.t = time;
    f.number = number;
    f.found.push_back(d);
  }
  if (frames.empty()) throw core::InputError(path + ": no rows (a header and no particle)");
  for (auto& [time, f] : frames) {
    std::sort(f.found.begin(), f.found.end(),
              [](const Detection& a, const Detection& b) { return a.id < b.id; });
    for (size_t k = 1; k < f.found.size(); ++k)
      if (f.found[k].id == f.found[k - 1].id)
        throw core::InputError(path + ":" + std::to_string(f.found[k].line) + ": particle " +
                               std::to_string(f.found[k].id) +
                               " appears twice at t = " + core::format_g(time, 6) + " s (also line " +
                               std::to_string(f.found[k - 1].line) + "): ids must be unique within a frame");
    out.frames.push_back(std::move(f));
  }
  return out;
}

}  // namespace lab
