// What the MAT and HDF5 readers share: variable specs, the checks on values, the column mapping's
// last steps, and the public entry points (ListVariables, ReadSignal, the MAT/HDF5 branch of
// ReadRecording).
#include "io/containers.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <functional>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/json_text.hpp"
#include "sysid/error.hpp"
#include "sysid/io_output.hpp"

namespace sysid {
namespace internal {
namespace {

std::string Num(double v) {
  if (std::isnan(v)) return "NaN";
  if (std::isinf(v)) return v > 0 ? "Inf" : "-Inf";
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

}  // namespace

VariableSpec ParseVariableSpec(const std::string& path, const std::string& spec) {
  VariableSpec out;
  out.text = spec;
  const auto fail = [&](const std::string& why) -> VariableSpec {
    throw InputError(fmt::format(
        "{}: variable spec '{}': {} (expected NAME, /group/dataset, NAME[:,k] or NAME[k,:] with "
        "k 1-based, like MATLAB)",
        path, spec, why));
  };
  if (spec.empty()) return fail("empty");
  const size_t open = spec.find('[');
  if (open == std::string::npos) {
    out.name = spec;
    return out;
  }
  if (spec.back() != ']') return fail("an index must end with ']'");
  out.name = spec.substr(0, open);
  if (out.name.empty()) return fail("no variable name before '['");
  const std::string inner = spec.substr(open + 1, spec.size() - open - 2);
  const size_t comma = inner.find(',');
  if (comma == std::string::npos) return fail("the index needs two parts, ':' and k");
  const std::string a = inner.substr(0, comma), b = inner.substr(comma + 1);
  std::string k;
  if (a == ":") {
    out.pick = VariableSpec::Pick::kColumn;
    k = b;
  } else if (b == ":") {
    out.pick = VariableSpec::Pick::kRow;
    k = a;
  } else {
    return fail("one of the two index parts must be ':'");
  }
  std::uint64_t value = 0;
  const auto [ptr, ec] = std::from_chars(k.data(), k.data() + k.size(), value);
  if (k.empty() || ec != std::errc() || ptr != k.data() + k.size())
    return fail("'" + k + "' is not a whole number");
  if (value == 0) return fail("index 0: indices start at 1");
  out.index = value;
  return out;
}

std::uint64_t PickedLength(const VariableSpec& spec, const std::vector<std::uint64_t>& dims,
                           const std::string& shape, const char* kind, const std::string& where) {
  const double count = ElementCount(dims);
  if (count > kMaxVariableElements)  // checked before any cast: count may be past 2^64
    throw InputError(fmt::format("{}: declares {} ({:.3g} elements), more than the {:.0f} a "
                                 "variable may hold",
                                 where, shape, count, kMaxVariableElements));
  if (spec.pick == VariableSpec::Pick::kWhole) {
    if (std::count_if(dims.begin(), dims.end(), [](auto d) { return d != 1; }) > 1)
      throw InputError(fmt::format("{}: is a {} ({}); pick a column with {}[:,k] or a row with "
                                   "{}[k,:] (k 1-based, like MATLAB)",
                                   where, kind, shape, spec.name, spec.name));
    return static_cast<std::uint64_t>(count);
  }
  if (dims.size() != 2)
    throw InputError(fmt::format("{}: is {}-dimensional ({}); [:,k] and [k,:] need a 2-D {}",
                                 where, dims.size(), shape, kind));
  const bool column = spec.pick == VariableSpec::Pick::kColumn;
  if (spec.index > (column ? dims[1] : dims[0]))
    throw InputError(fmt::format("{}: {} {} out of range: the {} is {} (indices are 1-based, "
                                 "like MATLAB)",
                                 where, column ? "column" : "row", spec.index, kind, shape));
  return column ? dims[0] : dims[1];
}

std::string FormatDims(const std::vector<std::uint64_t>& dims) {
  std::string s;
  for (const auto d : dims) s += (s.empty() ? "" : "x") + std::to_string(d);
  return s.empty() ? "0" : s;
}

double ElementCount(const std::vector<std::uint64_t>& dims) {
  double n = 1;
  for (const auto d : dims) {
    n *= static_cast<double>(d);
    if (n > kElementCountCap) return kElementCountCap;
  }
  return n;
}

void CheckFinite(const Eigen::VectorXd& v, const std::string& where) {
  for (Eigen::Index i = 0; i < v.size(); ++i)
    if (!std::isfinite(v[i]))
      throw InputError(
          fmt::format("{}[{}]: expected a finite number, found {}", where, i + 1, Num(v[i])));
}

void RequireFiniteToWrite(const Recording& rec, const std::string& path) {
  for (Eigen::Index c = 0; c < rec.data.cols(); ++c)
    for (Eigen::Index r = 0; r < rec.data.rows(); ++r)
      if (!std::isfinite(rec.data(r, c)))
        throw NumericalError(fmt::format(
            "{}: column '{}', row {} is {}: not written (sysid writes no recording it would "
            "refuse to read; the computation that gave it overflowed or failed)",
            path, rec.names[static_cast<size_t>(c)], r + 1, Num(rec.data(r, c))));
}

void SetRange(VariableInfo& info, const Eigen::VectorXd& values) {
  info.numeric_vector = true;
  info.length = static_cast<std::uint64_t>(values.size());
  if (values.size() == 0) return;
  info.min = values.minCoeff();
  info.max = values.maxCoeff();
  if (!values.allFinite()) info.min = info.max = std::numeric_limits<double>::quiet_NaN();
}

Recording WithTimeFirst(const Recording& rec, const Eigen::VectorXd& t_s) {
  Recording out;
  out.source = rec.source;
  out.metadata = rec.metadata;
  out.names.push_back("t");
  out.names.insert(out.names.end(), rec.names.begin(), rec.names.end());
  out.data.resize(rec.rows(), rec.data.cols() + 1);
  out.data.col(0) = t_s;
  out.data.rightCols(rec.data.cols()) = rec.data;
  return out;
}

std::string JoinList(const std::vector<std::string>& names) {
  std::string s;
  for (size_t i = 0; i < names.size() && i < 20; ++i) s += (i ? ", " : "") + names[i];
  if (names.size() > 20) s += fmt::format(", ... ({} in all)", names.size());
  return s.empty() ? "none" : s;
}

namespace {

// Where a column came from, for messages.
using Origin = std::function<std::string(const std::string& column)>;

// --scale: each mapped column times its factor, every value still finite.
void ApplyScales(Recording& rec, const SourceMapping& m, const Origin& origin) {
  const auto columns = [&] { return JoinList(rec.names); };
  for (const auto& [column, factor] : m.scales) {
    if (!std::isfinite(factor) || factor == 0)
      throw OptionsError(
          fmt::format("--scale {}={}: expected a finite, non-zero factor", column, Num(factor)),
          "scales");
    const int i = rec.index_of(column);
    if (i < 0)
      throw InputError(fmt::format("{}: --scale {}: no column '{}' (columns: {})", rec.source,
                                   column, column, columns()));
    rec.data.col(i) *= factor;
    for (Eigen::Index k = 0; k < rec.data.rows(); ++k)
      if (!std::isfinite(rec.data(k, i)))
        throw OptionsError(fmt::format("--scale {}={}: {}[{}] becomes {}: expected a factor "
                                       "that keeps every value finite",
                                       column, Num(factor), origin(column), k + 1,
                                       Num(rec.data(k, i))),
                           "scales");
  }
}

// --rate: t = k / rate, for a recording without a time column.
void ApplyRate(Recording& rec, const SourceMapping& m, const Origin& origin) {
  if (!std::isfinite(m.rate_hz) || m.rate_hz <= 0)
    throw OptionsError(
        fmt::format("--rate {}: expected a positive sample rate [Hz]", Num(m.rate_hz)),
        "rate_hz");
  if (rec.has("t"))
    throw InputError(fmt::format(
        "{}: has a time column 't' ({}); --rate applies only to recordings without one",
        rec.source, origin("t")));
  const Eigen::Index n = rec.rows();
  // t = k / rate: every step and the span must stay finite numbers (--rate 1e-320 made t inf,
  // --rate 1e308 a subnormal step whose rate is inf).
  const double last_t = static_cast<double>(n > 0 ? n - 1 : 0) / m.rate_hz;
  if (!(1 / m.rate_hz >= kMinTimeStep_s) || !std::isfinite(last_t))
    throw OptionsError(
        fmt::format("--rate {}: t = k / rate over {} samples {}: expected a rate whose step "
                    "1/rate is at least {} s and whose duration is a finite number",
                    Num(m.rate_hz), n,
                    std::isfinite(last_t) ? "steps by a subnormal number" : "reaches inf",
                    Num(kMinTimeStep_s)),
        "rate_hz");
  Eigen::VectorXd t(n);
  for (Eigen::Index k = 0; k < n; ++k) t[k] = static_cast<double>(k) / m.rate_hz;
  rec = WithTimeFirst(rec, t);
}

// The columns the caller requires, and a time that increases by steps a rate can be had from.
void CheckColumnsAndTime(const Recording& rec, const ReadOptions& options, const Origin& origin) {
  const auto columns = [&] { return JoinList(rec.names); };
  for (const auto& name : options.required_columns)
    if (!rec.has(name)) {
      if (name == "t")
        throw InputError(fmt::format(
            "{}: no time column 't' (columns: {}): give the sample rate with --rate HZ or map a "
            "time variable with --var t=NAME",
            rec.source, columns()));
      throw InputError(
          fmt::format("{}: missing required column '{}' (columns: {}); map it with "
                      "--var {}=NAME",
                      rec.source, name, columns(), name));
    }
  if (!options.any_of_columns.empty() &&
      std::none_of(options.any_of_columns.begin(), options.any_of_columns.end(),
                   [&](const std::string& n) { return rec.has(n); })) {
    std::string expected;
    for (const auto& n : options.any_of_columns)
      expected += (expected.empty() ? "'" : " or '") + n + "'";
    throw InputError(fmt::format("{}: missing column: expected {} (columns: {})", rec.source,
                                 expected, columns()));
  }
  if (rec.rows() == 0) throw InputError(rec.source + ": no samples");
  const int ti = options.require_increasing_time ? rec.index_of("t") : -1;
  if (ti >= 0) {
    const auto t = rec.data.col(ti);
    for (Eigen::Index k = 1; k < t.size(); ++k)
      if (!(t[k] > t[k - 1]))
        throw InputError(fmt::format("{}[{}]: time must be strictly increasing, found {} after {}",
                                     origin("t"), k + 1, Num(t[k]), Num(t[k - 1])));
    // A subnormal step has an infinite rate, a span past the largest double an infinite
    // duration (--scale t=1e-320 makes the first).
    for (Eigen::Index k = 1; k < t.size(); ++k)
      if (!(t[k] - t[k - 1] >= kMinTimeStep_s) || !std::isfinite(t[k] - t[0]))
        throw InputError(fmt::format(
            "{}[{}]: t = {} after {}: expected a step of at least {} s (a finite sample rate) "
            "and a duration that is a finite number",
            origin("t"), k + 1, Num(t[k]), Num(t[k - 1]), Num(kMinTimeStep_s)));
  }
}

// Provenance, in the recording's column order: every writer that keeps the metadata (derive,
// import) says where each column came from, at what rate and scale. A file name may hold a
// newline or an escape sequence: written as \xHH, so each line stays one line.
void SetProvenance(Recording& rec, const SourceMapping& m,
                   const std::vector<std::pair<std::string, std::string>>& origins) {
  const auto set = [&](const std::string& key, const std::string& value) {
    for (auto& [k, v] : rec.metadata)
      if (k == key) {
        v = value;
        return;
      }
    rec.metadata.emplace_back(key, value);
  };
  for (const auto& name : rec.names)
    for (const auto& [column, where] : origins)
      if (column == name) set("source." + column, OneLine(where));
  if (m.rate_hz != 0) set("sample_rate_hz", Num(m.rate_hz));
  for (const auto& [column, factor] : m.scales) set("scale." + column, Num(factor));
}

}  // namespace

void FinishMappedRecording(Recording& rec, const ReadOptions& options,
                           const std::vector<std::pair<std::string, std::string>>& origins) {
  const Origin origin = [&](const std::string& column) {
    for (const auto& [c, o] : origins)
      if (c == column) return o;
    return rec.source + ": column '" + column + "'";
  };
  const SourceMapping& m = options.mapping;
  ApplyScales(rec, m, origin);
  if (m.rate_hz != 0) ApplyRate(rec, m, origin);
  CheckColumnsAndTime(rec, options, origin);
  if (m.t_start_s || m.t_end_s) {
    const int ti = rec.index_of("t");  // none: CropRecording says so
    const auto t_at = [&](Eigen::Index row) { return ti < 0 ? 0.0 : rec.data(row, ti); };
    rec = CropRecording(rec, m.t_start_s.value_or(t_at(0)),
                        m.t_end_s.value_or(t_at(rec.rows() - 1)));
  }
  SetProvenance(rec, m, origins);
}

std::unique_ptr<SignalContainer> OpenContainer(const std::string& path) {
  switch (DetectFileFormat(path)) {
    case FileFormat::kMat:
      return OpenMatContainer(path);
    case FileFormat::kHdf5:
      return OpenHdf5Container(path);
    case FileFormat::kText:
      break;
  }
  throw InputError(path + ": not a MAT or HDF5 file (no MAT v5 header, no HDF5 signature)");
}

// The MAT/HDF5 branch of ReadRecording.
Recording ReadContainerRecording(const std::string& path, const ReadOptions& options) {
  auto c = OpenContainer(path);
  Recording rec;
  rec.source = path;
  std::vector<std::pair<std::string, std::string>> origins;
  std::vector<std::pair<std::string, std::string>> vars = options.mapping.variables;
  if (vars.empty()) {
    const std::string reason = c->MappingRequiredReason();
    if (!reason.empty()) throw InputError(path + ": " + reason);
    for (const auto& name : c->DefaultColumns()) vars.emplace_back(name, name);
    if (vars.empty()) {
      const std::vector<VariableInfo> all = c->List();
      if (all.empty()) throw InputError(path + ": holds no variables (an empty or truncated file)");
      std::vector<std::string> names;
      for (const auto& v : all)
        names.push_back(v.name + " (" + v.type + " " + FormatDims(v.dims) + ")");
      throw InputError(fmt::format(
          "{}: no top-level numeric vectors to read as columns; map variables with --var "
          "t=NAME,u=NAME,x=NAME (variables: {})",
          path, JoinList(names)));
    }
  }
  if (vars.size() > 256) throw InputError(path + ": more than 256 columns mapped");
  const bool by_name = options.mapping.variables.empty();
  for (const auto& [column, spec_text] : vars) {
    if (rec.has(column) && by_name)
      throw InputError(fmt::format("{}: two variables named '{}'", path, column));
    if (rec.has(column))
      throw OptionsError(fmt::format("--var: column '{}' mapped twice", column), "mapping");
    const VariableSpec spec = ParseVariableSpec(path, spec_text);
    const Eigen::VectorXd v = c->Read(spec);
    const std::string where = path + ":" + spec_text;
    if (!rec.names.empty() && v.size() != rec.rows())
      throw InputError(fmt::format("{}: {} samples, but {} has {} (lengths differ)", where,
                                   v.size(), origins.front().second, rec.rows()));
    rec.SetColumn(column, v);
    origins.emplace_back(column, where);
  }
  Eigen::VectorXd t;
  if (!rec.has("t") && options.mapping.rate_hz == 0 && c->ImpliedTime(&t)) {
    if (t.size() != rec.rows())
      throw InputError(fmt::format("{}:X.Data: {} samples, but {} has {} (lengths differ)", path,
                                   t.size(), origins.front().second, rec.rows()));
    rec = WithTimeFirst(rec, t);
    origins.emplace_back("t", path + ":X.Data");
  }
  FinishMappedRecording(rec, options, origins);
  return rec;
}

// CSV text through a mapping: rename (or select) columns, then the same last steps.
Recording ParseMappedCsv(std::string_view text, const std::string& source,
                         const ReadOptions& options) {
  ReadOptions raw;
  raw.required_columns.clear();
  raw.any_of_columns.clear();
  raw.require_increasing_time = false;
  Recording in = ParseRecording(text, source, raw);
  std::vector<std::string> names = in.names;
  std::vector<std::pair<std::string, std::string>> origins;
  std::vector<bool> keep(names.size(), true);
  for (const auto& [column, spec] : options.mapping.variables) {
    const int src = in.index_of(spec);
    if (src < 0)
      throw InputError(fmt::format("{}: --var {}={}: no column '{}' (columns: {})", source, column,
                                   spec, spec, JoinList(in.names)));
    const int clash = in.index_of(column);
    if (clash >= 0 && clash != src) keep[static_cast<size_t>(clash)] = false;
    names[static_cast<size_t>(src)] = column;
    origins.emplace_back(column, source + ": column '" + spec + "'");
  }
  Recording rec;
  rec.source = source;
  rec.metadata = in.metadata;
  for (size_t i = 0; i < names.size(); ++i) {
    if (!keep[i]) continue;
    if (rec.has(names[i]))
      throw OptionsError(fmt::format("--var: column '{}' mapped twice", names[i]), "mapping");
    rec.SetColumn(names[i], in.data.col(static_cast<Eigen::Index>(i)));
  }
  FinishMappedRecording(rec, options, origins);
  return rec;
}

}  // namespace internal

std::vector<VariableInfo> ListVariables(const std::string& path) {
  return internal::OpenContainer(path)->List();
}

std::string VariableListToJson(const std::string& path, const std::vector<VariableInfo>& vars,
                               int indent) {
  nlohmann::ordered_json j;
  j["file"] = path;
  j["format"] = DescribeFileFormat(path);
  j["variables"] = nlohmann::ordered_json::array();
  for (const auto& v : vars) {
    nlohmann::ordered_json e;
    e["name"] = v.name;
    e["type"] = v.type;
    e["dims"] = v.dims;
    e["complex"] = v.complex;
    e["sparse"] = v.sparse;
    if (v.numeric_vector) {
      e["length"] = v.length;
      // An empty variable has no range; a NaN one is a range not read or not finite.
      const bool range = v.length > 0;
      e["min"] = range && std::isfinite(v.min) ? nlohmann::ordered_json(v.min) : nullptr;
      e["max"] = range && std::isfinite(v.max) ? nlohmann::ordered_json(v.max) : nullptr;
    }
    j["variables"].push_back(e);
  }
  return internal::DumpJson(j, indent);
}

Eigen::VectorXd ReadSignal(const std::string& path, const std::string& spec) {
  if (DetectFileFormat(path) != FileFormat::kText) {
    auto c = internal::OpenContainer(path);
    return c->Read(internal::ParseVariableSpec(path, spec));
  }
  const internal::TextTable table = internal::ReadTextTable(path);
  size_t index = table.columns.size();
  if (!table.names.empty()) {
    const auto it = std::find(table.names.begin(), table.names.end(), spec);
    if (it != table.names.end()) index = static_cast<size_t>(it - table.names.begin());
  }
  if (index == table.columns.size()) {
    size_t k = 0;
    const auto [ptr, ec] = std::from_chars(spec.data(), spec.data() + spec.size(), k);
    if (ec == std::errc() && ptr == spec.data() + spec.size() && k >= 1 &&
        k <= table.columns.size())
      index = k - 1;
  }
  if (index == table.columns.size())
    throw InputError(fmt::format(
        "{}: no column '{}': expected {}a column number 1..{} (1-based)", path, spec,
        table.names.empty() ? std::string()
                            : "a header name (" + internal::JoinList(table.names) + ") or ",
        table.columns.size()));
  const auto& col = table.columns[index];
  return Eigen::Map<const Eigen::VectorXd>(col.data(), static_cast<Eigen::Index>(col.size()));
}

}  // namespace sysid
