#include "io/csv_table.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.h"

namespace io {

namespace {
std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::string field;
  std::istringstream in(line);
  while (std::getline(in, field, ',')) out.push_back(field);
  if (!line.empty() && line.back() == ',') out.emplace_back();
  return out;
}
}  // namespace

CsvTable CsvTable::read(const std::string& path, const std::string& what) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throw core::InputError(path + ": no such file (expected " + what + ")");
  if (fs::file_size(path, ec) > kMaxBytes)
    throw core::InputError(path + ": larger than " + std::to_string(kMaxBytes >> 20) + " MiB; " + what +
                           " never is");
  std::ifstream in(path);
  if (!in) throw core::InputError(path + ": cannot be read (" + what + ")");
  CsvTable t;
  t.path_ = path;
  t.what_ = what;
  std::string line;
  if (!std::getline(in, line) || line.empty())
    throw core::InputError(path + ": empty; expected " + what + " with a header line");
  if (!line.empty() && line.back() == '\r') line.pop_back();
  t.header_ = split(line);
  for (long n = 2; std::getline(in, line); ++n) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    auto row = split(line);
    if (row.size() != t.header_.size())
      throw core::InputError(path + ":" + std::to_string(n) + ": " + std::to_string(row.size()) +
                             " fields where the header has " + std::to_string(t.header_.size()) +
                             " (a truncated or hand-edited " + what + "?)");
    t.cells_.push_back(std::move(row));
  }
  return t;
}

bool CsvTable::has(const std::string& name) const {
  for (const auto& h : header_)
    if (h == name) return true;
  return false;
}

std::size_t CsvTable::column(const std::string& name) const {
  for (std::size_t k = 0; k < header_.size(); ++k)
    if (header_[k] == name) return k;
  throw core::InputError(path_ + ": no column '" + name + "' (" + what_ + "; rerun `siloscope analyze`?)");
}

const std::string& CsvTable::text(std::size_t row, const std::string& name) const {
  return cells_.at(row)[column(name)];
}

double CsvTable::num(std::size_t row, const std::string& name) const {
  const std::string& s = text(row, name);
  if (s.empty() || s == "nan" || s == "-nan") return NAN;
  errno = 0;
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  if (end == s.c_str() || *end != '\0' || errno == ERANGE)
    throw core::InputError(path_ + ":" + std::to_string(row + 2) + ": column " + name + " is '" + s +
                           "', not a number");
  return v;
}

}  // namespace io
