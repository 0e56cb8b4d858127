// ImportRecording (`sysid import`): one CSV recording from columns of MAT, HDF5 and text files.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/json_text.hpp"
#include "io/containers.hpp"
#include "sysid/error.hpp"

namespace sysid {
namespace {

// Without :VARIABLE, the variable named like the column, else the file's only numeric vector.
std::string DefaultVariable(const ImportColumn& c) {
  if (DetectFileFormat(c.file) == FileFormat::kText) return c.column;
  const std::vector<VariableInfo> vars = ListVariables(c.file);
  std::vector<std::string> vectors;
  for (const auto& v : vars) {
    const std::string bare = !v.name.empty() && v.name[0] == '/' ? v.name.substr(1) : v.name;
    if (bare == c.column) return v.name;
    if (v.numeric_vector && v.length > 1) vectors.push_back(v.name);
  }
  if (vectors.size() == 1) return vectors.front();
  std::vector<std::string> names;
  for (const auto& v : vars) names.push_back(v.name);
  throw InputError(
      fmt::format("{}: --column {}: no variable '{}' and not exactly one numeric "
                  "vector: name it, --column {}={}:VARIABLE (variables: {})",
                  c.file, c.column, c.column, c.column, c.file, internal::JoinList(names)));
}

}  // namespace

Recording ImportRecording(const ImportOptions& options) {
  if (options.columns.empty())
    throw OptionsError("import: no columns: give at least one --column NAME=FILE[:VARIABLE]",
                       "columns");
  if (options.columns.size() > 256) throw OptionsError("import: more than 256 columns", "columns");
  for (const auto& [c, u] : options.units)
    if (u.empty() || u.size() > 32 || internal::Printable(u, 32) != u)
      throw OptionsError(fmt::format("--unit {}={}: expected a unit of 1 to 32 printable "
                                     "characters",
                                     internal::Printable(c, 64), internal::Printable(u, 32)),
                         "units");
  Recording rec;
  rec.source = "import";
  std::vector<std::pair<std::string, std::string>> origins;
  for (const auto& c : options.columns) {
    const bool ok = !c.column.empty() && c.column.size() <= 64 &&
                    std::all_of(c.column.begin(), c.column.end(),
                                [](char ch) {
                                  return std::isalnum(static_cast<unsigned char>(ch)) || ch == '_';
                                }) &&
                    !std::isdigit(static_cast<unsigned char>(c.column[0]));
    if (!ok)
      throw OptionsError(fmt::format("--column {}: a column name is a letter or '_', then "
                                     "letters, digits or '_'",
                                     c.column),
                         "columns");
    if (rec.has(c.column))
      throw OptionsError(fmt::format("--column {}: given twice", c.column), "columns");
    const std::string spec = c.variable.empty() ? DefaultVariable(c) : c.variable;
    const Eigen::VectorXd v = ReadSignal(c.file, spec);
    const std::string where = c.file + ":" + spec;
    if (!rec.names.empty() && v.size() != rec.rows())
      throw InputError(fmt::format("{}: {} samples, but {} has {} (lengths differ)", where,
                                   v.size(), origins.front().second, rec.rows()));
    rec.SetColumn(c.column, v);
    origins.emplace_back(c.column, where);
  }
  // A ControlDesk export's time vector (X.Data) is the recording's t unless one is given.
  if (!rec.has("t") && options.rate_hz == 0) {
    for (const auto& c : options.columns) {
      if (DetectFileFormat(c.file) == FileFormat::kText) continue;
      Eigen::VectorXd t;
      if (!internal::OpenContainer(c.file)->ImpliedTime(&t)) continue;
      const std::string where = c.file + ":X.Data";
      if (t.size() != rec.rows())
        throw InputError(fmt::format("{}: {} samples, but {} has {} (lengths differ)", where,
                                     t.size(), origins.front().second, rec.rows()));
      rec = internal::WithTimeFirst(rec, t);
      origins.insert(origins.begin(), {"t", where});
      break;
    }
  }
  ReadOptions ro;
  ro.required_columns = {"t"};
  ro.any_of_columns.clear();
  ro.mapping.rate_hz = options.rate_hz;
  ro.mapping.scales = options.scales;
  internal::FinishMappedRecording(rec, ro, origins);

  // FinishMappedRecording wrote the provenance (source.*, sample_rate_hz, scale.*); the units
  // follow.
  for (const auto& name : rec.names) {
    std::string unit = ColumnUnit(name);
    for (const auto& [c, u] : options.units)
      if (c == name) unit = u;
    rec.metadata.emplace_back("unit." + name, unit);
  }
  for (const auto& [c, u] : options.units)
    if (!rec.has(c))
      throw OptionsError(fmt::format("--unit {}={}: no column '{}'", c, u, c), "units");
  return rec;
}

}  // namespace sysid
