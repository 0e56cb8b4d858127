// The one CSV table writer (sysid/io_csv_table.hpp): RFC 4180 quoting, rows as wide as the
// header, numbers as printf writes them. Python's csv module reads tricky tables back in
// python/tests/test_csv_table.py (the independent reader).
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>

#include "sysid/error.hpp"
#include "sysid/io_csv_table.hpp"

using sysid::CsvField;
using sysid::CsvTable;

TEST_CASE("a field is quoted when it holds a comma, a quote, CR or LF, quotes doubled",
          "[io][csv]") {
  CHECK(CsvField("plain.csv") == "plain.csv");
  CHECK(CsvField("") == "");
  CHECK(CsvField("a b;c'd") == "a b;c'd");  // blanks, semicolons and apostrophes need nothing
  CHECK(CsvField("a,b") == "\"a,b\"");
  CHECK(CsvField("say \"hi\"") == "\"say \"\"hi\"\"\"");
  CHECK(CsvField("\"") == "\"\"\"\"");
  CHECK(CsvField("two\nlines") == "\"two\nlines\"");
  CHECK(CsvField("cr\r") == "\"cr\r\"");
}

TEST_CASE("a table is its header and rows, LF-terminated, with the fields as written",
          "[io][csv]") {
  CsvTable t({"source", "n", "x", "note"}, "# generator: test\n");
  t.Text("a,b.csv").Integer(-3).Number(0.1).Empty().EndRow();
  t.Text("c").Integer(7).Number(1.0 / 3, 17).Quoted("x\"y").EndRow();
  CHECK(t.rows() == 2);
  CHECK(t.str() ==
        "# generator: test\n"
        "source,n,x,note\n"
        "\"a,b.csv\",-3,0.1,\n"
        "c,7,0.33333333333333331,\"x\"\"y\"\n");
}

TEST_CASE("numbers are printf's %.Ng, and 17 digits or Shortest read back exactly", "[io][csv]") {
  const double values[] = {0.1,
                           1.0 / 3,
                           -2.5e-310,
                           6.02214076e23,
                           123456789.0,
                           0.0,
                           -0.0,
                           std::numeric_limits<double>::max(),
                           std::numeric_limits<double>::quiet_NaN(),
                           std::numeric_limits<double>::infinity()};
  for (const double v : values) {
    for (const int digits : {6, 9, 17}) {
      CsvTable t({"v"});
      t.Number(v, digits).EndRow();
      char expected[64];
      std::snprintf(expected, sizeof expected, "v\n%.*g\n", digits, v);  // the reference
      CHECK(t.str() == expected);
    }
    if (!std::isfinite(v)) continue;
    CsvTable t({"a", "b"});
    t.Number(v, 17).Shortest(v).EndRow();
    const std::string row = t.str().substr(4);  // after "a,b\n"
    const size_t comma = row.find(',');
    CHECK(std::strtod(row.substr(0, comma).c_str(), nullptr) == v);
    CHECK(std::strtod(row.substr(comma + 1).c_str(), nullptr) == v);
  }
}

TEST_CASE("a row narrower or wider than the header is a programming error", "[io][csv]") {
  CsvTable narrow({"a", "b"});
  narrow.Text("1");
  CHECK_THROWS_AS(narrow.EndRow(), sysid::InternalError);
  CsvTable unended({"a"});
  unended.Text("1");
  CHECK_THROWS_AS(unended.str(), sysid::InternalError);
  CsvTable wide({"a"});
  wide.Text("1");
  CHECK_THROWS_AS(wide.Text("2"), sysid::InternalError);
}
