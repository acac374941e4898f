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

// The separator the header uses: the most frequent of ',', ';' and tab outside quotes (',' when none).
char separator_of(const std::string& header) {
  long comma = 0, semicolon = 0, tab = 0;
  bool quoted = false;
  for (char c : header) {
    if (c == '"') quoted = !quoted;
    if (quoted) continue;
    comma += c == ',';
    semicolon += c == ';';
    tab += c == '\t';
  }
  if (semicolon > comma && semicolon >= tab) return ';';
  if (tab > comma && tab > semicolon) return '\t';
  return ',';
}

// One line's fields; a quoted field may hold the separator and doubled quotes. Throws core::InputError
// (`where`) for a quote left open.
std::vector<std::string> split(const std::string& line, char sep, const std::string& where) {
  std::vector<std::string> out;
  std::string field;
  size_t k = 0;
  while (true) {
    field.clear();
    if (k < line.size() && line[k] == '"') {
      for (++k;; ++k) {
        if (k >= line.size()) throw core::InputError(where + ": a quoted field is not closed on its line");
        if (line[k] == '"' && k + 1 < line.size() && line[k + 1] == '"') {
          field += '"';
          ++k;
        } else if (line[k] == '"') {
          ++k;
          break;
        } else {
          field += line[k];
        }
      }
      while (k < line.size() && line[k] != sep) field += line[k++];  // text after the closing quote
    } else {
      while (k < line.size() && line[k] != sep) field += line[k++];
    }
    out.push_back(field);
    if (k >= line.size()) break;
    ++k;  // the separator
  }
  return out;
}

}  // namespace

CsvTable CsvTable::read(const std::string& path, const std::string& what) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::is_regular_file(path, ec) && fs::file_size(path, ec) > kMaxBytes)
    throw core::InputError(path + ": larger than " + std::to_string(kMaxBytes >> 20) + " MiB; " + what +
                           " never is");
  CsvStream stream(path, what);
  CsvTable t;
  stream.next(t, static_cast<std::size_t>(-1));
  return t;
}

CsvTable CsvTable::from_rows(const std::string& path, const std::string& what,
                             std::vector<std::string> header, std::vector<std::vector<std::string>> rows,
                             std::vector<long> lines) {
  CsvTable t;
  t.path_ = path;
  t.what_ = what;
  t.header_ = std::move(header);
  t.cells_ = std::move(rows);
  t.lines_ = std::move(lines);
  return t;
}

CsvStream::CsvStream(const std::string& path, const std::string& what) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throw core::InputError(path + ": no such file (expected " + what + ")");
  in_.open(path);
  if (!in_) throw core::InputError(path + ": cannot be read (" + what + ")");
  head_.path_ = path;
  head_.what_ = what;
  std::string line;
  if (!std::getline(in_, line) || line.empty())
    throw core::InputError(path + ": empty; expected " + what + " with a header line");
  if (line.rfind("\xEF\xBB\xBF", 0) == 0) line.erase(0, 3);  // a UTF-8 byte-order mark
  if (!line.empty() && line.back() == '\r') line.pop_back();
  head_.separator_ = separator_of(line);
  head_.header_ = split(line, head_.separator_, path + ":1");
}

bool CsvStream::next(CsvTable& t, std::size_t max_rows) {
  t.path_ = head_.path_;
  t.what_ = head_.what_;
  t.header_ = head_.header_;
  t.separator_ = head_.separator_;
  t.cells_.clear();
  t.lines_.clear();
  const std::string& path = head_.path_;
  std::string line;
  while (t.cells_.size() < max_rows && std::getline(in_, line)) {
    const long n = ++line_;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    auto row = split(line, t.separator_, path + ":" + std::to_string(n));
    if (row.size() != t.header_.size())
      throw core::InputError(path + ":" + std::to_string(n) + ": " + std::to_string(row.size()) +
                             " fields where the header has " + std::to_string(t.header_.size()) +
                             " (a truncated or hand-edited " + head_.what_ + "?)");
    t.cells_.push_back(std::move(row));
    t.lines_.push_back(n);
  }
  return !t.cells_.empty();
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
  std::string s = text(row, name);
  if (s.empty() || s == "nan" || s == "-nan") return NAN;
  // With ';' between fields, a spreadsheet of a comma-decimal locale writes 0,5 for 0.5.
  if (separator_ == ';' && s.find(',') != std::string::npos && s.find('.') == std::string::npos &&
      s.find(',') == s.rfind(','))
    s[s.find(',')] = '.';
  errno = 0;
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  if (end == s.c_str() || *end != '\0' || errno == ERANGE)
    throw core::InputError(path_ + ":" + std::to_string(line(row)) + ": column " + name + " is '" +
                           text(row, name) + "', not a number");
  return v;
}

}  // namespace io
