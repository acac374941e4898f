// Tracked particles from a CSV file (lab/tracks.h). Over 400 lines because it is one reader: the columns'
// roles and their default names, TrackMate's and trackpy's layouts, the species from sizes and every row's
// checks all decide together what one row means, and read best beside each other.
#include "lab/tracks.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <set>

#include "core/error.h"
#include "core/format.h"
#include "core/interrupt.h"
#include "io/csv_table.h"
#include "lab/size_species.h"
#include "lab/trackmate_xml.h"

namespace lab {

namespace {

struct Role {
  const char* key;                 // the map's name for it
  std::string ColumnMap::*field;   // where the map keeps it
  std::vector<const char*> names;  // the default names looked for
};

const std::vector<Role>& roles() {
  static const std::vector<Role> r = {
      {"time", &ColumnMap::time, {"t", "time", "t_s", "POSITION_T"}},
      {"frame", &ColumnMap::frame, {"frame", "FRAME"}},
      {"id", &ColumnMap::id, {"particle", "id", "track", "track_id", "TRACK_ID"}},
      {"x", &ColumnMap::x, {"x", "x_m", "POSITION_X"}},
      {"y", &ColumnMap::y, {"y", "y_m", "POSITION_Y"}},
      {"radius", &ColumnMap::radius, {"r", "radius", "radius_m", "RADIUS"}},
      {"diameter", &ColumnMap::diameter, {"diameter", "d"}},
      {"angle", &ColumnMap::angle, {"angle"}},
      {"species", &ColumnMap::species, {"species"}},
      {"size", &ColumnMap::size, {"size"}},
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
            const core::Setup& setup, const core::Geometry& geo, size_t first_row, Tracks& out)
      : t_(&t), path_(path), units_(units), setup_(setup), geo_(geo), names_(setup.species_names()) {
    for (const Role& r : roles()) col_[r.key] = find_column(t, map, r);
    // TrackMate's time is in the image's unit: seconds, or frames when the image has no frame interval.
    if (col_["time"] == "POSITION_T" && map.time.empty() && first_row > 0) {
      const std::string unit = t.text(first_row - 1, "POSITION_T");
      if (unit != "(sec)" && unit != "(s)") col_["time"].clear();
    }
    for (const Role& r : roles())
      if (!col_[r.key].empty()) out.columns_used.push_back(std::string(r.key) + "=" + col_[r.key]);
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
    if (has_radius_ && !has_species_ && setup.species.size() > 1) {  // species from radii: the likeliest
      likeliest_.emplace(setup.species, 0, kAssumedSizeSpread);
      out.size_spread = kAssumedSizeSpread;
      out.size_error_rate = likeliest_->error_rate();
    }
    scale_ = units.scale > 0 ? units.scale : 1.0;
    ysign_ = units.scale > 0 && !units.y_up ? -1.0 : 1.0;
  }

  // The slice of the file the rows are read from next.
  void use(const io::CsvTable& t) { t_ = &t; }

  // Row `row`: the detection, its time and its frame number (-1 without one); false for a spot without a
  // track id (a tracker's spot it linked to no track), which is skipped.
  bool read(size_t row, Detection& d, double& time, long& number) {
    d = Detection{};
    d.line = static_cast<std::int32_t>(t_->line(row));
    const std::string& id_text = t_->text(row, col_["id"]);
    if (id_text.empty() || id_text == "None" || id_text == "NaN" || id_text == "nan") return false;
    const double idv = finite(row, col_["id"]);
    if (idv != std::floor(idv) || std::fabs(idv) > 9e15)
      throw core::InputError(line_of(row) + ": column " + col_["id"] + " is '" + t_->text(row, col_["id"]) +
                             "', not a whole number (particle ids are integers)");
    d.id = static_cast<long>(idv);
    number = -1;
    if (!col_["frame"].empty()) {
      const double f = finite(row, col_["frame"]);
      if (f != std::floor(f) || f < 0)
        throw core::InputError(line_of(row) + ": column " + col_["frame"] + " is '" +
                               t_->text(row, col_["frame"]) + "', not a frame number (a whole number >= 0)");
      number = static_cast<long>(f);
    }
    time = by_frame_ ? static_cast<double>(number) / units_.fps : finite(row, col_["time"]);
    d.x = (finite(row, col_["x"]) - units_.origin_x) * scale_;
    d.y = ysign_ * (finite(row, col_["y"]) - units_.origin_y) * scale_;
    if (units_.rotation != 0) {
      const double c = std::cos(units_.rotation), s = std::sin(units_.rotation), x = d.x, y = d.y;
      d.x = c * x + s * y;
      d.y = -s * x + c * y;
    }
    d.species = has_species_ ? species(row) : 0;
    size(row, d);
    d.angle = has_angle_ ? finite(row, col_["angle"]) : 0.0;
    check_inside(row, d);
    return true;
  }

  // The size column (trackpy's radius of gyration, px) when it is what tells species apart: no radius,
  // diameter or species column, and a scene of several species. Empty otherwise.
  std::string size_column() const {
    return has_radius_ || has_species_ || setup_.species.size() <= 1 ? "" : col_.at("size");
  }
  double size_of(size_t row) const {
    const double v = finite(row, col_.at("size"));
    if (!(v > 0))
      throw core::InputError(line_of(row) + ": column " + col_.at("size") + " is '" +
                             t_->text(row, col_.at("size")) + "': a grain's size must be > 0");
    return v;
  }

 private:
  const io::CsvTable* t_;
  const std::string& path_;
  const Units& units_;
  const core::Setup& setup_;
  const core::Geometry& geo_;
  const std::vector<std::string> names_;
  std::map<std::string, std::string> col_;
  bool by_frame_ = false, has_radius_ = false, has_angle_ = false, has_species_ = false;
  std::optional<SizeSpecies> likeliest_;  // a grain's species from its radius
  double scale_ = 1, ysign_ = 1;

  void need(const char* key) {
    if (!col_[key].empty()) return;
    for (const Role& r : roles())
      if (r.key == std::string(key))
        throw core::InputError(path_ + ": no column for " + key + " (looked for " + looked_for(r) +
                               "; name it with --columns " + key + "=COLUMN)");
  }
  std::string line_of(size_t row) const { return path_ + ":" + std::to_string(t_->line(row)); }
  double finite(size_t row, const std::string& c) const {
    const double v = t_->num(row, c);
    if (!std::isfinite(v))
      throw core::InputError(line_of(row) + ": column " + c + " is '" + t_->text(row, c) +
                             "', not a finite number");
    return v;
  }

  // Species: a name of the scene's or its index.
  int species(size_t row) {
    const int n_species = static_cast<int>(setup_.species.size());
    const std::string& s = t_->text(row, col_["species"]);
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

  // The grain's radius from a radius or diameter column (without a species column, the species likeliest to
  // have it: lab/size_species.h); the species' radius without one.
  void size(size_t row, Detection& d) {
    if (!has_radius_) {
      d.r = setup_.species[static_cast<size_t>(d.species)].radius;
      return;
    }
    const bool diameter = col_["radius"].empty();
    const std::string& c = diameter ? col_["diameter"] : col_["radius"];
    const double v = finite(row, c) * scale_ * (diameter ? 0.5 : 1.0);
    if (!(v > 0))
      throw core::InputError(line_of(row) + ": column " + c + " is '" + t_->text(row, c) +
                             "': a grain's size must be > 0");
    d.r = v;
    if (likeliest_) d.species = likeliest_->species(v);
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

namespace {

// TrackMate writes three lines under its header (the features' names, short names and units): the rows at the
// top whose x is not a number, when the header is TrackMate's.
size_t description_rows(const io::CsvTable& t) {
  if (!t.has("POSITION_X") || !t.has("TRACK_ID")) return 0;
  size_t k = 0;
  while (k < 3 && k < t.rows()) {
    const std::string& x = t.text(k, "POSITION_X");
    char* end = nullptr;
    std::strtod(x.c_str(), &end);
    if (!x.empty() && *end == '\0') break;
    ++k;
  }
  return k;
}

// Species from sizes alone (trackpy's `size` is a radius of gyration in pixels, not a radius): the sizes
// (each detection's r until then) fall into as many groups as the scene has species (k-means on log size),
// matched to the species in the order of their radii, which gives the sizes' scale and spread; each
// detection then takes the species likeliest to have its size (lab/size_species.h: a lognormal's tail that
// reaches past a uniform interval's end is not cut at the midpoint between the groups) and that species'
// radius. The sizes are read in passes, not held. Throws core::InputError when the groups are not apart as
// the species' radii are.
void species_by_size(io::Spill<Detection>& dets, const core::Setup& setup, const std::string& path,
                     const std::string& column, const std::string& spill_dir, double& out_spread,
                     double& out_error_rate) {
  const size_t k = setup.species.size(), n = dets.size();
  std::vector<size_t> by_radius(k);
  for (size_t i = 0; i < k; ++i) by_radius[i] = i;
  std::sort(by_radius.begin(), by_radius.end(),
            [&](size_t a, size_t b) { return setup.species[a].radius < setup.species[b].radius; });
  std::vector<double> centre(k);
  {
    io::Spill<double> sizes(spill_dir);  // the log is monotonic: the sizes' quantiles give the logs'
    for (size_t i = 0; i < n; ++i) {
      sizes.push_back(dets[i].r);
      dets.release_after(i), sizes.release_after(i);
    }
    for (size_t c = 0; c < k; ++c)
      centre[c] = std::log(io::kth_smallest(sizes, (2 * c + 1) * (n - 1) / (2 * k)));
  }
  auto nearest = [&](double log_size, const std::vector<double>& at) {
    size_t best = 0;
    for (size_t c = 1; c < k; ++c)
      if (std::fabs(log_size - at[c]) < std::fabs(log_size - at[best])) best = c;
    return best;
  };
  std::vector<double> used = centre;  // the centres the groups were last taken by
  for (int pass = 0; pass < 100; ++pass) {
    used = centre;
    std::vector<double> sum(k, 0.0);
    std::vector<long> count(k, 0);
    for (size_t i = 0; i < n; ++i) {
      const double l = std::log(dets[i].r);
      const size_t best = nearest(l, used);
      sum[best] += l;
      ++count[best];
      dets.release_after(i);
    }
    bool moved = false;
    for (size_t c = 0; c < k; ++c)
      if (count[c] > 0 && std::fabs(sum[c] / count[c] - centre[c]) > 1e-12)
        centre[c] = sum[c] / count[c], moved = true;
    if (!moved) break;
  }
  // Groups apart as the radii are: each pair of neighbouring groups at least half as far apart (in log size)
  // as their species' radii.
  for (size_t c = 1; c < k; ++c) {
    const double want = std::log(setup.species[by_radius[c]].radius / setup.species[by_radius[c - 1]].radius);
    if (!(centre[c] - centre[c - 1] >= 0.5 * want) || want <= 0)
      throw core::InputError(
          path + ": the sizes in column " + column + " do not fall into the scene's " + std::to_string(k) +
          " species (their groups differ by a factor " +
          core::format_g(std::exp(centre[c] - centre[c - 1]), 3) + " where the radii of " +
          setup.species[by_radius[c - 1]].name + " and " + setup.species[by_radius[c]].name + " differ by " +
          core::format_g(std::exp(want), 3) +
          "): give each grain's species or radius (--columns species=COLUMN or radius=COLUMN)");
  }
  // The groups give the size's scale (trackpy's size is a radius of gyration, in pixels) and the sizes'
  // spread: from the species of one fixed size (the spread by the median deviation, which a neighbour's tail
  // in the group hardly moves); from every group's mean otherwise (a group of a species whose law reaches
  // into its neighbour's misses its tail: a slightly biased scale).
  auto is_fixed = [&](size_t c) { return setup.species[by_radius[c]].law == core::SizeLaw::Fixed; };
  std::vector<long> count(k, 0);
  io::Spill<double> deviation(spill_dir);
  for (size_t i = 0; i < n; ++i) {
    const double l = std::log(dets[i].r);
    const size_t c = nearest(l, used);
    ++count[c];
    if (is_fixed(c)) {
      deviation.push_back(std::fabs(l - centre[c]));
      deviation.release_after(deviation.size() - 1);
    }
    dets.release_after(i);
  }
  const SizeSpecies exact(setup.species, 0, kAssumedSizeSpread);
  double scale = 0, weight = 0;
  for (size_t c = 0; c < k; ++c)
    if (is_fixed(c)) {
      scale += static_cast<double>(count[c]) * (centre[c] - std::log(setup.species[by_radius[c]].radius));
      weight += static_cast<double>(count[c]);
    }
  if (weight == 0)
    for (size_t c = 0; c < k; ++c) {
      scale +=
          static_cast<double>(count[c]) * (centre[c] - exact.mean_log_radius(static_cast<int>(by_radius[c])));
      weight += static_cast<double>(count[c]);
    }
  out_spread =
      deviation.size() == 0
          ? kAssumedSizeSpread
          : std::max(kLeastSizeSpread, 1.4826 * io::kth_smallest(deviation, (deviation.size() - 1) / 2));
  const SizeSpecies likeliest(setup.species, scale / weight, out_spread);
  out_error_rate = likeliest.error_rate();
  for (size_t i = 0; i < n; ++i) {
    Detection& d = dets[i];
    d.species = likeliest.species(d.r);
    d.r = setup.species[static_cast<size_t>(d.species)].radius;
    dets.release_after(i);
  }
  dets.release();
}

}  // namespace

namespace {

constexpr size_t kSliceRows = 1 << 16;  // rows read at a time

struct RowRead {
  double time;
  Detection d;
};
struct FrameTally {
  long number = -1;
  size_t count = 0, next = 0;
};

// Each frame's detections by id, no id twice in a frame; then the frames in time order over them.
void frames_by_id(Tracks& out, const std::map<double, FrameTally>& frames, const std::string& path) {
  size_t first = 0;
  for (const auto& [time, f] : frames) {
    TrackFrame tf;
    tf.t = time;
    tf.number = f.number;
    tf.first = first;
    tf.found = std::span<Detection>(out.detections.data() + first, f.count);
    std::sort(tf.found.begin(), tf.found.end(),
              [](const Detection& a, const Detection& b) { return a.id < b.id; });
    for (size_t k = 1; k < tf.found.size(); ++k)
      if (tf.found[k].id == tf.found[k - 1].id)
        throw core::InputError(path + ":" + std::to_string(tf.found[k].line) + ": particle " +
                               std::to_string(tf.found[k].id) +
                               " appears twice at t = " + core::format_g(time, 6) + " s (also line " +
                               std::to_string(tf.found[k - 1].line) + "): ids must be unique within a frame");
    out.frames.push_back(tf);
    first += f.count;
    if (out.frames.size() % 1024 == 0) out.detections.release();
  }
  out.detections.release();
}

}  // namespace

Tracks read_tracks(const std::string& path, const ColumnMap& map, const Units& units,
                   const core::Setup& setup, const core::Geometry& geo, const std::string& spill_dir) {
  // Read a slice of rows at a time, each row kept on disk (io/spill.h), in frame order: memory does not grow
  // with the film. TrackMate's XML too (its spots as the rows of its spots table).
  Tracks out;
  out.source = path;
  out.detections = io::Spill<Detection>(spill_dir);
  std::optional<io::CsvStream> stream;
  std::optional<TrackMateXml> xml;
  io::CsvTable slice;
  if (core::lower_extension(path) == ".xml") {
    xml.emplace(path);
    if (!xml->next(slice, kSliceRows))
      throw core::InputError(path + ": a TrackMate file without spots (<AllSpots> is empty)");
  } else {
    stream.emplace(path, "tracked particles");
    stream->next(slice, kSliceRows);
  }
  auto next_slice = [&] { return xml ? xml->next(slice, kSliceRows) : stream->next(slice, kSliceRows); };
  const size_t first = description_rows(slice);
  RowReader reader(slice, path, map, units, setup, geo, first, out);
  const std::string size_column = reader.size_column();
  std::map<double, FrameTally> frames;  // by time
  // Rows in frame order (detect's, trackpy's, siloscope's export) go straight into the detections; from the
  // first row out of order on (TrackMate's spots, by track), each is kept with its time and put in place
  // once all are read.
  bool in_order = true;
  io::Spill<RowRead> rows(spill_dir);
  for (size_t row = first;; ++row) {
    if (row >= slice.rows()) {
      core::throw_if_interrupted();
      rows.release();
      out.detections.release();
      if (!next_slice()) break;
      row = 0;
    }
    ++out.rows;
    double time = 0;
    long number = -1;
    Detection d;
    if (!reader.read(row, d, time, number)) {
      ++out.untracked;
      continue;
    }
    if (!size_column.empty()) d.r = reader.size_of(row);  // the size, until the species are known
    if (in_order && !frames.empty() && time < frames.rbegin()->first) {
      in_order = false;
      size_t i = 0;
      for (const auto& [t, f] : frames)
        for (size_t c = 0; c < f.count; ++c) rows.push_back({t, out.detections[i++]});
      out.detections.resize(0);
    }
    FrameTally& f = frames[time];
    f.number = number;
    ++f.count;
    if (in_order)
      out.detections.push_back(d);
    else
      rows.push_back({time, d});
  }
  if (frames.empty()) throw core::InputError(path + ": no rows (a header and no particle)");
  size_t at = 0;
  for (auto& [time, f] : frames) f.next = at, at += f.count;
  out.detections.resize(at);  // in order: as read
  auto it = frames.end();
  for (size_t i = 0; i < rows.size(); ++i) {  // each row into its frame's place
    if (it == frames.end() || it->first != rows[i].time) it = frames.find(rows[i].time);
    out.detections[it->second.next++] = rows[i].d;
    if ((i + 1) % kSliceRows == 0) {
      core::throw_if_interrupted();
      rows.release();
      out.detections.release();
    }
  }
  rows = io::Spill<RowRead>();
  if (!size_column.empty()) {
    species_by_size(out.detections, setup, path, size_column, spill_dir, out.size_spread,
                    out.size_error_rate);
    out.species_by_size = true;
  }
  frames_by_id(out, frames, path);
  return out;
}

}  // namespace lab
