// A CSV table: one header line of column names, then rows of fields, as siloscope's analysis writes them
// (points.csv, realizations.csv) and as labs' tools and spreadsheets write them: a UTF-8 byte-order mark is
// skipped, the separator is the header's (',', ';' or a tab), fields may be quoted ("a ""b""", within a
// line), and with ';' a decimal comma reads as a point. Read whole, checked as it is read, so a reader gets
// numbers or an error that names the file, the line and the column.
#pragma once

#include <cstddef>
#include <fstream>
#include <string>
#include <vector>

namespace io {

class CsvTable {
 public:
  // Reads `path`; `what` names the file in errors ("points.csv of a campaign analysis"). Throws
  // core::InputError when the file is missing, unreadable, larger than kMaxBytes, has no header, or a row
  // has another number of fields than the header.
  static CsvTable read(const std::string& path, const std::string& what);
  static constexpr std::size_t kMaxBytes = std::size_t{1} << 28;  // 256 MiB: no campaign table comes near
  // A table made in memory (a file of another format read into rows): `lines` numbers the rows in messages.
  static CsvTable from_rows(const std::string& path, const std::string& what, std::vector<std::string> header,
                            std::vector<std::vector<std::string>> rows, std::vector<long> lines);

  const std::string& path() const { return path_; }
  std::size_t rows() const { return cells_.size(); }
  long line(std::size_t row) const { return lines_.at(row); }  // the file's line of a row (1: the header)
  char separator() const { return separator_; }
  bool has(const std::string& column) const;
  // The field as written. Throws core::InputError for a column the table lacks.
  const std::string& text(std::size_t row, const std::string& column) const;
  // The field as a number: NaN for an empty field or nan. Throws core::InputError (path:line, column, value)
  // for a field that is not a number.
  double num(std::size_t row, const std::string& column) const;

 private:
  friend class CsvStream;
  std::size_t column(const std::string& name) const;
  std::string path_, what_;
  std::vector<std::string> header_;
  std::vector<std::vector<std::string>> cells_;
  std::vector<long> lines_;
  char separator_ = ',';
};

// The same file read a slice of rows at a time, for files of any size (a long film's tracks): each slice is a
// CsvTable with the file's header, its lines numbered as in the file. Checked as CsvTable::read checks, no
// size limit.
class CsvStream {
 public:
  // Opens `path` and reads its header. Throws core::InputError as CsvTable::read does.
  CsvStream(const std::string& path, const std::string& what);
  // The next rows, at most `max_rows`, into `slice` (its rows replaced); false when none were left.
  bool next(CsvTable& slice, std::size_t max_rows);

 private:
  std::ifstream in_;
  CsvTable head_;  // the header, the separator, the names
  long line_ = 1;  // the file's last line read
};

}  // namespace io
