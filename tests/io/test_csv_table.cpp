// io::CsvTable: the reader of analysis tables (claims): numbers, or an error naming file, line and column.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "helpers.h"
#include "io/csv_table.h"

namespace fs = std::filesystem;

TEST_CASE("CsvTable reads numbers and names what is wrong", "[io]") {
  const fs::path d = test::temp_dir("csv_table");
  std::ofstream(d / "ok.csv") << "a,b,name\n1,2.5e-3,x\n,nan,y\r\n";
  const auto t = io::CsvTable::read((d / "ok.csv").string(), "a test table");
  REQUIRE(t.rows() == 2);
  CHECK(t.has("b"));
  CHECK_FALSE(t.has("c"));
  CHECK(t.num(0, "b") == 2.5e-3);
  CHECK(std::isnan(t.num(1, "a")));
  CHECK(std::isnan(t.num(1, "b")));
  CHECK(t.text(1, "name") == "y");
  CHECK_THROWS_WITH(t.num(0, "name"), Catch::Contains("ok.csv:2: column name is 'x', not a number"));
  CHECK_THROWS_WITH(t.num(0, "c"), Catch::Contains("no column 'c' (a test table"));

  std::ofstream(d / "short.csv") << "a,b\n1,2\n3\n";
  CHECK_THROWS_WITH(io::CsvTable::read((d / "short.csv").string(), "a test table"),
                    Catch::Contains("short.csv:3: 1 fields where the header has 2"));
  std::ofstream(d / "empty.csv") << "";
  CHECK_THROWS_AS(io::CsvTable::read((d / "empty.csv").string(), "a test table"), core::InputError);
  CHECK_THROWS_WITH(io::CsvTable::read((d / "missing.csv").string(), "a test table"),
                    Catch::Contains("no such file (expected a test table)"));
  CHECK_THROWS_AS(io::CsvTable::read(d.string(), "a test table"), core::InputError);  // a directory
}

TEST_CASE("CsvTable reads the dialects labs write: a byte-order mark, quotes, semicolons, tabs",
          "[io][lab]") {
  const fs::path d = test::temp_dir("csv_dialects");
  // A spreadsheet's export: byte-order mark, quoted header, ';' between fields, a decimal comma.
  std::ofstream(d / "excel.csv")
      << "\xEF\xBB\xBF\"x\";\"y\";\"label\"\r\n0,5;2;\"a; \"\"quoted\"\" one\"\r\n\r\n3;-1,25e-1;b\r\n";
  const auto e = io::CsvTable::read((d / "excel.csv").string(), "tracks");
  REQUIRE(e.rows() == 2);
  CHECK(e.separator() == ';');
  CHECK(e.has("x"));
  CHECK(e.num(0, "x") == 0.5);
  CHECK(e.num(1, "y") == -0.125);
  CHECK(e.text(0, "label") == "a; \"quoted\" one");
  CHECK(e.line(1) == 4);  // the blank line counted
  CHECK_THROWS_WITH(e.num(1, "label"), Catch::Contains("excel.csv:4: column label is 'b', not a number"));
  std::ofstream(d / "tabs.tsv") << "frame\tparticle\tx\n0\t7\t1.5\n";
  const auto t = io::CsvTable::read((d / "tabs.tsv").string(), "tracks");
  CHECK(t.separator() == '\t');
  CHECK(t.num(0, "x") == 1.5);
  // A decimal comma is read only where ';' separates fields; a quote left open is named.
  std::ofstream(d / "comma.csv") << "a,b\n\"1,5\",2\n";
  CHECK_THROWS_WITH(io::CsvTable::read((d / "comma.csv").string(), "t").num(0, "a"),
                    Catch::Contains("column a is '1,5', not a number"));
  std::ofstream(d / "open.csv") << "a,b\n\"1,2\n";
  CHECK_THROWS_WITH(io::CsvTable::read((d / "open.csv").string(), "t"),
                    Catch::Contains("open.csv:2: a quoted field is not closed on its line"));
}
