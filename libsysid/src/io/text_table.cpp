// ReadTextTable: whitespace- or comma-separated numbers, an optional header line of names,
// '#' comment lines. As strict as the CSV reader: every cell is a whole finite number.
#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <string>
#include <string_view>
#include <vector>

#include "io/containers.hpp"
#include "sysid/error.hpp"

namespace sysid::internal {
namespace {

bool IsSpace(char c) { return c == ' ' || c == '\t' || c == '\r'; }

// Splits a line into fields: on commas when it has any, else on runs of blanks. Each field
// keeps its 1-based character column.
void Split(std::string_view line, std::vector<std::pair<std::string_view, long>>& out) {
  out.clear();
  const bool commas = line.find(',') != std::string_view::npos;
  size_t i = 0;
  if (commas) {
    while (true) {
      const size_t c = line.find(',', i);
      std::string_view f = line.substr(i, c == std::string_view::npos ? line.npos : c - i);
      size_t lead = 0;
      while (lead < f.size() && IsSpace(f[lead])) ++lead;
      f.remove_prefix(lead);
      while (!f.empty() && IsSpace(f.back())) f.remove_suffix(1);
      out.emplace_back(f, static_cast<long>(i + lead) + 1);
      if (c == std::string_view::npos) break;
      i = c + 1;
    }
    return;
  }
  while (i < line.size()) {
    while (i < line.size() && IsSpace(line[i])) ++i;
    if (i >= line.size()) break;
    const size_t b = i;
    while (i < line.size() && !IsSpace(line[i])) ++i;
    out.emplace_back(line.substr(b, i - b), static_cast<long>(b) + 1);
  }
}

bool ParseDouble(std::string_view s, double* v) {
  const char* b = s.data();
  const char* e = s.data() + s.size();
  if (b != e && *b == '+') ++b;
  const auto [ptr, ec] = std::from_chars(b, e, *v);
  return !s.empty() && ec == std::errc() && ptr == e;
}

// Starts like a number: a digit, or a sign or point before a digit or point.
bool LooksNumeric(std::string_view s) {
  const auto digit = [](char c) { return c >= '0' && c <= '9'; };
  if (s.empty()) return false;
  if (digit(s[0])) return true;
  if (s[0] == '+' || s[0] == '-') s.remove_prefix(1);
  if (!s.empty() && s[0] == '.') s.remove_prefix(1);
  return !s.empty() && digit(s[0]);
}

}  // namespace

TextTable ReadTextTable(const std::string& path) {
  const std::string text = ReadFile(path);
  TextTable table;
  std::vector<std::pair<std::string_view, long>> fields;
  size_t pos = 0;
  long line_no = 0;
  bool first = true;
  size_t ncol = 0;
  std::string_view view(text);
  if (view.size() >= 3 && std::memcmp(view.data(), "\xEF\xBB\xBF", 3) == 0) pos = 3;
  while (pos < view.size()) {
    const size_t nl = view.find('\n', pos);
    std::string_view line = view.substr(pos, nl == view.npos ? view.npos : nl - pos);
    pos = nl == view.npos ? view.size() : nl + 1;
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    size_t k = 0;
    while (k < line.size() && IsSpace(line[k])) ++k;
    if (k == line.size() || line[k] == '#') continue;
    Split(line, fields);
    if (first) {
      first = false;
      ncol = fields.size();
      if (ncol > 4096)
        throw InputError(fmt::format("{}:{}: {} columns: at most 4096", path, line_no, ncol));
      table.columns.resize(ncol);
      // A header line is one whose cells are all names: a cell that starts like a number
      // ("1.2.3", "1e400", "0x10") makes the line a row, so a malformed first number is an
      // error with its line and column instead of a header that drops the row.
      if (std::none_of(fields.begin(), fields.end(),
                       [](const auto& f) { return LooksNumeric(f.first); })) {
        for (const auto& f : fields) {
          if (f.first.empty())
            throw InputError(
                fmt::format("{}:{}:{}: header: empty column name", path, line_no, f.second));
          table.names.emplace_back(f.first);
        }
        continue;
      }
    }
    if (fields.size() != ncol)
      throw InputError(
          fmt::format("{}:{}: expected {} fields, found {}", path, line_no, ncol, fields.size()));
    for (size_t c = 0; c < ncol; ++c) {
      double v = 0;
      const auto& [cell, col] = fields[c];
      if (!ParseDouble(cell, &v))
        throw InputError(fmt::format(
            "{}:{}:{}: column {}: expected a number, found \"{}\"", path, line_no, col, c + 1,
            cell.size() > 40 ? std::string(cell.substr(0, 40)) + "..." : std::string(cell)));
      if (!std::isfinite(v))
        throw InputError(fmt::format("{}:{}:{}: column {}: expected a finite number, found \"{}\"",
                                     path, line_no, col, c + 1, std::string(cell)));
      if (static_cast<double>(table.columns[c].size()) >= kMaxSignalSamples)
        throw InputError(
            fmt::format("{}:{}: more than {:.0f} rows", path, line_no, kMaxSignalSamples));
      table.columns[c].push_back(v);
    }
  }
  if (ncol == 0) throw InputError(path + ": empty file: expected rows of numbers");
  if (table.columns[0].empty()) throw InputError(path + ": no rows of numbers");
  return table;
}

}  // namespace sysid::internal
