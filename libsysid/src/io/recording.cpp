#include <algorithm>
#include <charconv>
#include <string>

#include "core/json_text.hpp"
#include "io/containers.hpp"
#include "sysid/error.hpp"
#include "sysid/io_output.hpp"
#include "sysid/io.hpp"

namespace sysid {

int Recording::index_of(std::string_view name) const {
  for (size_t i = 0; i < names.size(); ++i)
    if (names[i] == name) return static_cast<int>(i);
  return -1;
}

Eigen::MatrixXd::ConstColXpr Recording::column(std::string_view name) const {
  const int i = index_of(name);
  if (i < 0) {
    std::string found;
    for (const auto& n : names) found += (found.empty() ? "" : ",") + n;
    throw InputError(source + ": missing column '" + std::string(name) + "' (found: " + found +
                     ")");
  }
  return data.col(i);
}

long Recording::line_of(Eigen::Index row) const {
  if (row_lines.empty() || row_lines_rows != data.rows() || row < 0 || row >= data.rows())
    return 0;
  // The last run starting at or before `row`.
  auto it = std::upper_bound(row_lines.begin(), row_lines.end(), row,
                             [](Eigen::Index r, const auto& run) { return r < run.first; });
  if (it == row_lines.begin()) return 0;
  --it;
  return it->second + static_cast<long>(row - it->first);
}

std::string Recording::where(Eigen::Index row) const {
  const long line = line_of(row);
  return line > 0 ? source + ":" + std::to_string(line)
                  : source + ": row " + std::to_string(row + 1);
}

std::string Recording::meta(std::string_view key, std::string fallback) const {
  for (const auto& [k, v] : metadata)
    if (k == key) return v;
  return fallback;
}

void Recording::SetColumn(const std::string& name, const Eigen::VectorXd& values) {
  if (data.cols() > 0 && values.size() != data.rows())
    throw InternalError("Recording::SetColumn: column '" + name + "' has " +
                        std::to_string(values.size()) + " rows, the recording " +
                        std::to_string(data.rows()));
  const int i = index_of(name);
  if (i >= 0) {
    data.col(i) = values;
    return;
  }
  names.push_back(name);
  if (data.cols() == 0) data.resize(values.size(), 0);
  data.conservativeResize(data.rows(), data.cols() + 1);
  data.col(data.cols() - 1) = values;
}

namespace {

// The CSV text of `recording`; `where` names the destination in the error for an inf or NaN.
std::string FormatChecked(const Recording& recording, const std::string& where) {
  internal::RequireFiniteToWrite(recording, where);
  std::string out;
  const auto rows = recording.data.rows(), cols = recording.data.cols();
  out.reserve(static_cast<size_t>(rows * cols) * 16 + 256);
  // Metadata values may come from users (file names, comments): one line each, whatever they
  // hold, so the file reads back and prints safely.
  // The first line says sysid wrote the file (a later -o replaces only such files); a
  // recording read from one of sysid's files keeps no generator of its own.
  out += GeneratorLine();
  for (const auto& [k, v] : recording.metadata)
    if (k != "generator" || v.rfind("sysid ", 0) != 0)
      out += "# " + internal::OneLine(k) + ": " + internal::OneLine(v) + "\n";
  for (Eigen::Index c = 0; c < cols; ++c) {
    out += recording.names[static_cast<size_t>(c)];
    out += c + 1 < cols ? ',' : '\n';
  }
  char buf[32];
  for (Eigen::Index r = 0; r < rows; ++r) {
    for (Eigen::Index c = 0; c < cols; ++c) {
      // Shortest text that reads back to the same double: exact round trip, compact files.
      const auto res = std::to_chars(buf, buf + sizeof buf, recording.data(r, c));
      out.append(buf, res.ptr);
      out += c + 1 < cols ? ',' : '\n';
    }
  }
  return out;
}

}  // namespace

std::string FormatRecording(const Recording& recording) {
  return FormatChecked(recording, "CSV output");
}

void WriteRecording(const std::string& path, const Recording& recording) {
  WriteFileAtomically(path, FormatChecked(recording, path));
}

}  // namespace sysid
