// CSV tables in one dialect (sysid/io_csv_table.hpp).
#include <fmt/format.h>

#include "sysid/error.hpp"
#include "sysid/io_csv_table.hpp"

namespace sysid {

namespace {

// `s` in double quotes, each inner quote doubled (RFC 4180, 2.7).
std::string InQuotes(std::string_view s) {
  std::string out = "\"";
  for (const char c : s) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
}

}  // namespace

std::string CsvField(std::string_view s) {
  return s.find_first_of(",\"\r\n") == std::string_view::npos ? std::string(s) : InQuotes(s);
}

CsvTable::CsvTable(const std::vector<std::string>& header, std::string_view preamble)
    : text_(preamble), columns_(header.size()) {
  SYSID_CHECK(!header.empty(), "CsvTable: a table needs at least one column");
  for (const auto& name : header) Text(name);
  EndRow();
  rows_ = 0;
}

CsvTable& CsvTable::Append(std::string_view raw) {
  SYSID_CHECK(fields_ < columns_,
              fmt::format("CsvTable: a row of more than the header's {} fields", columns_));
  if (fields_++ > 0) text_ += ',';
  text_ += raw;
  return *this;
}

CsvTable& CsvTable::Text(std::string_view field) { return Append(CsvField(field)); }

CsvTable& CsvTable::Quoted(std::string_view field) { return Append(InQuotes(field)); }

CsvTable& CsvTable::Number(double v, int significant_digits) {
  return Append(fmt::format("{:.{}g}", v, significant_digits));
}

CsvTable& CsvTable::Shortest(double v) { return Append(fmt::format("{}", v)); }

CsvTable& CsvTable::Integer(long long v) { return Append(fmt::format("{}", v)); }

CsvTable& CsvTable::Empty() { return Append(""); }

CsvTable& CsvTable::EndRow() {
  SYSID_CHECK(fields_ == columns_,
              fmt::format("CsvTable: a row of {} fields under a header of {}", fields_, columns_));
  text_ += '\n';
  fields_ = 0;
  ++rows_;
  return *this;
}

const std::string& CsvTable::str() const {
  SYSID_CHECK(fields_ == 0, "CsvTable: the last row is not ended");
  return text_;
}

}  // namespace sysid
