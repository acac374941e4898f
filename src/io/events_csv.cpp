#include "io/events_csv.h"
#include "core/format.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <vector>

#include "core/error.h"
#include "core/scene.h"
#include "io/output.h"
#include "io/run.h"

namespace io {

namespace {
const char* kExitsHeader = "t_s,id,species";
const char* kClogsHeader = "start_s,end_s,duration_s,ended_by,arrested";
const char* kArchesHeader =
    "t_s,clog_duration_s,method,n_members,n_added,ids,species,span_m,height_m,max_angle_deg";

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::string cur;
  std::stringstream ss(s);
  while (std::getline(ss, cur, sep)) out.push_back(cur);
  if (!s.empty() && s.back() == sep) out.emplace_back();
  return out;
}

// Reads a CSV file line by line, checking the header and the number of columns.
class CsvReader {
 public:
  CsvReader(const std::filesystem::path& path, const char* header, const SpeciesNames& names)
      : path_(path.string()), names_(names) {
    if (std::filesystem::exists(path))
      core::check_input_file(path_, "events file", std::uintmax_t{1} << 30);  // no device, no link to one
    in_.open(path);
    if (!in_) throw core::InputError(path_ + ": missing events file (is this a siloscope run directory?)");
    std::string h;
    if (!std::getline(in_, h) || h != header)
      throw core::InputError(path_ + ":1: header is '" + h + "', expected '" + header + "'");
    columns_ = split(header, ',').size();
  }
  // Next row's cells, or false at the end. A last line without its newline is a truncated file.
  bool next(std::vector<std::string>& cells) {
    std::string line;
    if (!std::getline(in_, line)) return false;
    ++line_;
    if (in_.eof()) fail("truncated (the last line has no newline)");
    cells = split(line, ',');
    if (cells.size() != columns_)
      fail("has " + std::to_string(cells.size()) + " columns, expected " + std::to_string(columns_));
    return true;
  }
  double real(const std::string& s, const char* what) {
    char* end = nullptr;
    double v = std::strtod(s.c_str(), &end);
    if (s.empty() || *end || !std::isfinite(v))
      fail(std::string(what) + " = '" + s + "' is not a finite number");
    return v;
  }
  long integer(const std::string& s, const char* what) {
    char* end = nullptr;
    long v = std::strtol(s.c_str(), &end, 10);
    if (s.empty() || *end || v < 0) fail(std::string(what) + " = '" + s + "' is not a whole number >= 0");
    return v;
  }
  core::Species species(const std::string& s) {
    for (size_t k = 0; k < names_.size(); ++k)
      if (s == names_[k]) return static_cast<core::Species>(k);
    std::string all;
    for (const auto& n : names_) all += (all.empty() ? "" : ", ") + n;
    fail("species = '" + s + "' is not one of the scene's species (" + all + ")");
  }
  [[noreturn]] void fail(const std::string& msg) {
    throw core::InputError(path_ + ":" + std::to_string(line_ + 1) + ": " + msg);
  }

 private:
  std::string path_;
  std::ifstream in_;
  size_t columns_ = 0;
  long line_ = 0;
  const SpeciesNames& names_;
};

const std::string& name_of(const SpeciesNames& names, core::Species s) {
  static const std::string unknown = "unknown";
  const size_t k = static_cast<size_t>(core::species_index(s));
  return k < names.size() ? names[k] : unknown;
}
}  // namespace

const SpeciesNames& shorthand_names() {
  static const SpeciesNames names = {"original", "added"};
  return names;
}

std::string exits_csv(const core::Events& ev, const SpeciesNames& names) {
  std::string s = std::string(kExitsHeader) + "\n";
  for (const auto& e : ev.exits)
    s += core::format_g(e.t) + "," + std::to_string(e.id) + "," + name_of(names, e.species) + "\n";
  return s;
}

std::string clogs_csv(const core::Events& ev) {
  std::string s = std::string(kClogsHeader) + "\n";
  for (const auto& c : ev.clogs)
    s += core::format_g(c.start) + "," + core::format_g(c.end) + "," + core::format_g(c.end - c.start) + "," +
         core::clog_end_name(c.ended_by) + "," + (c.arrested ? "1" : "0") + "\n";
  return s;
}

std::string arches_csv(const core::Events& ev, const SpeciesNames& names) {
  std::string s = std::string(kArchesHeader) + "\n";
  for (const auto& a : ev.arches) {
    std::string ids, sp;
    long added = 0;
    for (size_t k = 0; k < a.ids.size(); ++k) {
      ids += (k ? ";" : "") + std::to_string(a.ids[k]);
      sp += (k ? ";" : "") + name_of(names, a.species[k]);
      added += a.species[k] != core::Species::Original;
    }
    s += core::format_g(a.t) + "," + core::format_g(a.clog_duration) + "," +
         core::arch_method_name(a.method) + "," + std::to_string(a.ids.size()) + "," + std::to_string(added) +
         "," + ids + "," + sp + "," + core::format_g(a.geometry.span) + "," +
         core::format_g(a.geometry.height) + "," + core::format_g(a.geometry.max_angle_deg) + "\n";
  }
  return s;
}

void write_events(const std::filesystem::path& dir, const core::Events& ev, const SpeciesNames& names) {
  write_file_atomic(dir / run_file::kExits, exits_csv(ev, names));
  write_file_atomic(dir / run_file::kClogs, clogs_csv(ev));
  write_file_atomic(dir / run_file::kArches, arches_csv(ev, names));
}

core::Events read_events(const std::filesystem::path& dir, const SpeciesNames& names) {
  core::Events ev;
  std::vector<std::string> c;
  {
    CsvReader r(dir / run_file::kExits, kExitsHeader, names);
    double last = -INFINITY;
    while (r.next(c)) {
      core::ExitEvent e{r.real(c[0], "t_s"), static_cast<int>(r.integer(c[1], "id")), r.species(c[2])};
      if (e.t < last) r.fail("exit times go backwards");
      last = e.t;
      ev.exits.push_back(e);
    }
  }
  {
    CsvReader r(dir / run_file::kClogs, kClogsHeader, names);
    while (r.next(c)) {
      core::ClogEvent e{
          r.real(c[0], "start_s"), r.real(c[1], "end_s"), core::ClogEnd::Spontaneous, c[4] == "1", NAN, {}};
      bool known = false;
      for (auto k :
           {core::ClogEnd::Spontaneous, core::ClogEnd::Vibration, core::ClogEnd::Rule, core::ClogEnd::RunEnd})
        if (c[3] == core::clog_end_name(k)) e.ended_by = k, known = true;
      if (!known) r.fail("ended_by = '" + c[3] + "' is not spontaneous, vibration, rule or run_end");
      if (e.end < e.start) r.fail("a clog ends before it starts");
      ev.clogs.push_back(e);
    }
  }
  {
    CsvReader r(dir / run_file::kArches, kArchesHeader, names);
    while (r.next(c)) {
      core::ArchEvent a;
      a.t = r.real(c[0], "t_s");
      a.clog_duration = r.real(c[1], "clog_duration_s");
      if (!core::parse_arch_method(c[2], a.method))
        r.fail("method '" + c[2] + "' is not contact_path or visible");
      long n = r.integer(c[3], "n_members");
      auto ids = c[5].empty() ? std::vector<std::string>{} : split(c[5], ';');
      auto sp = c[6].empty() ? std::vector<std::string>{} : split(c[6], ';');
      if (static_cast<long>(ids.size()) != n || static_cast<long>(sp.size()) != n)
        r.fail("n_members = " + c[3] + " does not match the ids and species lists");
      for (size_t k = 0; k < ids.size(); ++k) {
        a.ids.push_back(static_cast<int>(r.integer(ids[k], "ids")));
        a.species.push_back(r.species(sp[k]));
      }
      a.geometry = {r.real(c[7], "span_m"), r.real(c[8], "height_m"), r.real(c[9], "max_angle_deg")};
      ev.arches.push_back(std::move(a));
    }
  }
  return ev;
}

}  // namespace io
