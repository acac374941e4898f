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
