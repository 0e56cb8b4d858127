// Strict, fast recording parser. The file is read in one piece and parsed in place; every cell
// goes through std::from_chars (libstdc++ 12 uses a correctly rounded fast path), so a 100 MB
// file parses in a fraction of a second.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <string>
#include <string_view>
#include <vector>

#include "core/json_text.hpp"
#include "io/units.hpp"
#include "io/containers.hpp"
#include "sysid/error.hpp"
#include "sysid/io.hpp"
#include "sysid/io_containers.hpp"
#include "sysid/io_output.hpp"

namespace sysid {
namespace {

using internal::Trim;

// Shows a cell in an error message: quoted, shortened if long, control bytes as \xHH.
std::string Quote(std::string_view s) { return "\"" + internal::Printable(s, 40) + "\""; }


class Parser {
 public:
  Parser(std::string_view text, const std::string& source, const ReadOptions& options)
      : text_(text), source_(source), options_(options) {}

  // Parses into `rec` (its previous content replaced, its matrix storage reused when the size
  // matches) with `values` as the row-major scratch. A fresh `values` is reserved from a count
  // of the lines first; a reused one (RecordingReader) keeps its capacity and skips the count.
  void Run(Recording& rec, std::vector<double>& values) {
    if (text_.size() >= 3 && std::memcmp(text_.data(), "\xEF\xBB\xBF", 3) == 0) {
      text_.remove_prefix(3);
      bom_ = true;
    }
    rec.source = source_;
    rec.names.clear();
    rec.metadata.clear();
    rec.row_lines.clear();
    ReadHeader(rec);
    ReadRows(rec, values);
    CheckColumns(rec);
    internal::ApplyUnitsMetadata(rec, units_line_);
  }

 private:
  // Next physical line without its terminator; false at the end of the text.
  bool NextLine(std::string_view& line) {
    if (pos_ >= text_.size()) return false;
    const char* begin = text_.data() + pos_;
    const void* nl = std::memchr(begin, '\n', text_.size() - pos_);
    size_t len = nl ? static_cast<size_t>(static_cast<const char*>(nl) - begin)
                    : text_.size() - pos_;
    pos_ += len + (nl ? 1 : 0);
    line = std::string_view(begin, len);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    ++line_no_;
    return true;
  }

  [[noreturn]] void Fail(long line, long column, const std::string& what) const {
    std::string msg = source_ + ":" + std::to_string(line) + ":";
    if (column > 0) msg += std::to_string(column) + ":";
    throw InputError(msg + " " + what);
  }

  // Column (1-based, in characters of the physical line) of `p` inside `line`.
  long ColumnOf(std::string_view line, const char* p) const {
    return static_cast<long>(p - line.data()) + 1;
  }

  static void KeepMetadata(std::string_view comment, Recording& rec) {
    comment.remove_prefix(1);  // '#'
    const size_t colon = comment.find(':');
    if (colon == std::string_view::npos) return;
    const std::string_view key = Trim(comment.substr(0, colon));
    if (key.empty() || key.size() > 64) return;
    const bool keyish = std::all_of(key.begin(), key.end(), [](char c) {
      return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.' ||
             c == ' ';
    });
    if (!keyish) return;
    // The file's mark of who wrote it (sysid/io_output.hpp), not a fact about the data: a
    // recording written again gets its writer's own.
    const std::string_view value = Trim(comment.substr(colon + 1));
    if (key == "generator" && value.substr(0, 6) == "sysid ") return;
    // A comment is the user's free text, kept; its control bytes (an escape sequence would
    // reach the terminal through `sysid info` and every file that copies metadata) as \xHH.
    rec.metadata.emplace_back(std::string(key), internal::OneLine(Trim(comment.substr(colon + 1))));
  }

  void ReadHeader(Recording& rec) {
    std::string_view line;
    while (NextLine(line)) {
      const std::string_view t = Trim(line);
      if (t.empty()) continue;
      if (t.front() == '#') {
        const size_t kept = rec.metadata.size();
        KeepMetadata(t, rec);
        if (rec.metadata.size() > kept && rec.metadata.back().first == "units")
          units_line_ = line_no_;  // ApplyUnitsMetadata's errors point at it
        continue;
      }
      header_line_ = line_no_;
      size_t start = 0;
      while (true) {
        const size_t comma = line.find(',', start);
        const std::string_view raw =
            line.substr(start, comma == std::string_view::npos ? std::string_view::npos
                                                               : comma - start);
        const std::string_view name = Trim(raw);
        const long col = static_cast<long>(start) + 1;
        if (name.empty()) Fail(line_no_, col, "header: empty column name");
        if (internal::HasControlByte(name))
          Fail(line_no_, col,
               "header: expected a column name of printable characters, found " + Quote(name));
        if (std::find(rec.names.begin(), rec.names.end(), name) != rec.names.end())
          Fail(line_no_, col, "header: duplicate column name " + Quote(name));
        if (std::isdigit(static_cast<unsigned char>(name.front())) || name.front() == '-' ||
            name.front() == '.')
          Fail(line_no_, col,
               "expected a header line of column names, found the number " + Quote(name));
        rec.names.emplace_back(name);
        if (comma == std::string_view::npos) break;
        start = comma + 1;
      }
      return;
    }
    Fail(std::max(line_no_, 1L), 0,
         line_no_ == 0 ? "empty file: expected a header line of column names (t,u,x,...)"
                       : "no header line: expected a line of column names (t,u,x,...)");
  }

  // The most rows of a recording, as of a generated signal: bounds the memory of the values.
  static constexpr size_t kMaxRows = static_cast<size_t>(kMaxSignalSamples);

  void ReadRows(Recording& rec, std::vector<double>& values) {
    const size_t ncol = rec.names.size();
    values.clear();  // row-major while parsing; transposed once at the end
    if (values.capacity() == 0) {
      // Upper bound of the row count: the remaining newlines (+1 for a missing final one).
      const size_t max_rows =
          static_cast<size_t>(std::count(text_.begin() + static_cast<long>(pos_), text_.end(),
                                         '\n')) + 1;
      // At most kMaxSignalSamples rows are ever kept (checked per row below).
      values.reserve(std::min(max_rows, kMaxRows + 1) * ncol);
    }
    const int t_index = options_.require_increasing_time ? rec.index_of("t") : -1;
    double t_prev = 0, t_first = 0;
    long t_prev_line = 0;
    size_t rows = 0;
    std::string_view line;
    while (NextLine(line)) {
      if (line.empty() || Trim(line).empty()) {
        if (AllRemainingBlank()) break;
        Fail(line_no_, 0, "empty line: expected " + std::to_string(ncol) + " numbers");
      }
      if (line.front() == '#') continue;
      if (rows == kMaxRows)
        Fail(line_no_, 0,
             "more than " + std::to_string(kMaxRows) +
                 " rows, past the most a recording may hold (sysid::kMaxSignalSamples)");
      if (rec.row_lines.empty() || rec.row_lines.back().second +
                                           static_cast<long>(static_cast<Eigen::Index>(rows) -
                                                             rec.row_lines.back().first) !=
                                       line_no_)
        rec.row_lines.emplace_back(static_cast<Eigen::Index>(rows), line_no_);
      const char* p = line.data();
      const char* end = line.data() + line.size();
      for (size_t c = 0; c < ncol; ++c) {
        const char* field_end = static_cast<const char*>(std::memchr(p, ',', end - p));
        if (!field_end) field_end = end;
        if (c + 1 < ncol && field_end == end)
          Fail(line_no_, 0,
               "expected " + std::to_string(ncol) + " fields (" + JoinNames(rec) + "), found " +
                   std::to_string(c + 1));
        if (c + 1 == ncol && field_end != end)
          Fail(line_no_, ColumnOf(line, field_end + 1),
               "expected " + std::to_string(ncol) + " fields (" + JoinNames(rec) +
                   "), found more");
        values.push_back(ParseNumber(line, p, field_end, rec.names[c]));
        p = field_end + 1;
      }
      if (t_index >= 0) {
        const double t = values[rows * ncol + static_cast<size_t>(t_index)];
        if (rows > 0 && !(t > t_prev))
          Fail(line_no_, FieldColumn(line, static_cast<size_t>(t_index)),
               "column 't': time must be strictly increasing, found " + Num(t) + " after " +
                   Num(t_prev) + " (line " + std::to_string(t_prev_line) + ")");
        // Every step must have a finite rate 1/step, and the span a finite duration: a
        // subnormal step or a span past the largest double makes both inf.
        if (rows > 0 && !(t - t_prev >= kMinTimeStep_s))
          Fail(line_no_, FieldColumn(line, static_cast<size_t>(t_index)),
               "column 't': a step of " + Num(t - t_prev) + " s after " + Num(t_prev) +
                   " (line " + std::to_string(t_prev_line) + "): expected a step of at least " +
                   Num(kMinTimeStep_s) + " s, whose sample rate 1/step is a finite number");
        if (rows == 0) t_first = t;
        if (!std::isfinite(t - t_first))
          Fail(line_no_, FieldColumn(line, static_cast<size_t>(t_index)),
               "column 't': " + Num(t) + " is more than the largest double after the first "
               "time, " + Num(t_first) + ": expected a duration that is a finite number");
        t_prev = t;
        t_prev_line = line_no_;
      }
      ++rows;
    }
    if (rows == 0)
      Fail(header_line_, 0, "header without rows: expected numeric rows after the header");
    rec.data.resize(static_cast<Eigen::Index>(rows), static_cast<Eigen::Index>(ncol));
    rec.row_lines_rows = static_cast<Eigen::Index>(rows);
    for (size_t r = 0; r < rows; ++r)
      for (size_t c = 0; c < ncol; ++c)
        rec.data(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c)) =
            values[r * ncol + c];
  }

  bool AllRemainingBlank() const {
    for (size_t i = pos_; i < text_.size(); ++i)
      if (!std::isspace(static_cast<unsigned char>(text_[i]))) return false;
    return true;
  }

  double ParseNumber(std::string_view line, const char* begin, const char* end,
                     const std::string& name) {
    std::string_view cell(begin, static_cast<size_t>(end - begin));
    const std::string_view trimmed = Trim(cell);
    const long col = ColumnOf(line, trimmed.empty() ? begin : trimmed.data());
    if (trimmed.empty())
      Fail(line_no_, col, "column '" + name + "': expected a number, found an empty cell");
    const char* b = trimmed.data();
    const char* e = trimmed.data() + trimmed.size();
    if (*b == '+' && e - b > 1) ++b;  // from_chars rejects a leading '+'
    double value = 0;
    const auto [ptr, ec] = std::from_chars(b, e, value);
    if (ec == std::errc::result_out_of_range)
      Fail(line_no_, col,
           "column '" + name + "': number out of range for a double: " + Quote(trimmed));
    if (ec != std::errc() || ptr != e)
      Fail(line_no_, col, "column '" + name + "': expected a number, found " + Quote(trimmed));
    if (!std::isfinite(value))
      Fail(line_no_, col,
           "column '" + name + "': expected a finite number, found " + Quote(trimmed));
    return value;
  }

  long FieldColumn(std::string_view line, size_t index) const {
    size_t start = 0;
    for (size_t i = 0; i < index; ++i) start = line.find(',', start) + 1;
    return static_cast<long>(start) + 1;
  }

  static std::string JoinNames(const Recording& rec) {
    std::string s;
    for (const auto& n : rec.names) s += (s.empty() ? "" : ",") + n;
    return s;
  }

  static std::string Num(double v) {
    char buf[32];
    const auto r = std::to_chars(buf, buf + sizeof buf, v);
    return std::string(buf, r.ptr);
  }

  void CheckColumns(const Recording& rec) const {
    for (const auto& name : options_.required_columns)
      if (!rec.has(name))
        Fail(header_line_, 0,
             "missing required column '" + name + "' (found: " + JoinNames(rec) + ")");
    if (!options_.any_of_columns.empty() &&
        std::none_of(options_.any_of_columns.begin(), options_.any_of_columns.end(),
                     [&](const std::string& n) { return rec.has(n); })) {
      std::string expected;
      for (const auto& n : options_.any_of_columns)
        expected += (expected.empty() ? "'" : " or '") + n + "'";
      Fail(header_line_, 0,
           "missing column: expected " + expected + " (found: " + JoinNames(rec) + ")");
    }
  }

  std::string_view text_;
  const std::string& source_;
  const ReadOptions& options_;
  size_t pos_ = 0;
  long line_no_ = 0;
  long header_line_ = 0;
  long units_line_ = 0;
  bool bom_ = false;
};

}  // namespace

Recording ParseRecording(std::string_view text, const std::string& source,
                         const ReadOptions& options) {
  if (!options.mapping.empty()) return internal::ParseMappedCsv(text, source, options);
  Recording rec;
  std::vector<double> values;
  Parser(text, source, options).Run(rec, values);
  return rec;
}

Recording ReadRecording(const std::string& path, const ReadOptions& options) {
  if (DetectFileFormat(path) != FileFormat::kText)
    return internal::ReadContainerRecording(path, options);
  return ParseRecording(ReadFile(path), path, options);
}

const Recording& RecordingReader::Read(const std::string& path) {
  if (!options_.mapping.empty() || DetectFileFormat(path) != FileFormat::kText) {
    recording_ = ReadRecording(path, options_);
    return recording_;
  }
  ReadFile(path, &text_);
  Parser(text_, path, options_).Run(recording_, values_);
  return recording_;
}

}  // namespace sysid
