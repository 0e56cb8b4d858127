#include "io/units.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "sysid/error.hpp"
#include "sysid/io_containers.hpp"

namespace sysid {
namespace {

using internal::Trim;

/// The SI unit of each column the model reads, and the factors of the scaled units accepted.
struct ColumnUnits {
  const char* si;
  std::map<std::string, double, std::less<>> factor;  // unit -> multiply by this for SI
};

const std::map<std::string, ColumnUnits, std::less<>>& KnownColumns() {
  const std::map<std::string, double, std::less<>> length{
      {"m", 1.0}, {"mm", 1e-3}, {"um", 1e-6}, {"µm", 1e-6}, {"nm", 1e-9}};
  auto per = [&length](const std::string& suffix) {
    std::map<std::string, double, std::less<>> out;
    for (const auto& [unit, f] : length) out[unit + suffix] = f;
    return out;
  };
  std::map<std::string, double, std::less<>> acceleration = per("/s^2");
  for (const auto& [unit, f] : per("/s²")) acceleration[unit] = f;
  static const std::map<std::string, ColumnUnits, std::less<>> known{
      {"t", {"s", {{"s", 1.0}, {"ms", 1e-3}, {"us", 1e-6}, {"µs", 1e-6}}}},
      {"u", {"V", {{"V", 1.0}, {"mV", 1e-3}}}},
      {"x", {"m", length}},
      {"x_ref", {"m", length}},
      {"v", {"m/s", per("/s")}},
      {"a", {"m/s^2", acceleration}}};
  return known;
}

}  // namespace

namespace internal {

void ApplyUnitsMetadata(Recording& recording, long line_no) {
  auto line = std::find_if(recording.metadata.begin(), recording.metadata.end(),
                           [](const auto& kv) { return kv.first == "units"; });
  if (line == recording.metadata.end()) return;
  std::vector<std::string> entries;
  bool converted = false;
  std::string_view rest = line->second;
  while (!rest.empty()) {
    const size_t comma = rest.find_first_of(",;");
    const std::string_view entry = Trim(rest.substr(0, comma));
    rest = comma == std::string_view::npos ? std::string_view{} : rest.substr(comma + 1);
    if (entry.empty()) continue;
    // "x=mm", "x [mm]" or "x = a description [mm]"; anything else is a remark, kept as it is.
    std::string_view name, unit;
    const size_t eq = entry.find('='), open = entry.rfind('[');
    const bool bracket = open != std::string_view::npos && entry.back() == ']';
    name = Trim(entry.substr(0, std::min(eq, bracket ? open : std::string_view::npos)));
    if (bracket)
      unit = Trim(entry.substr(open + 1, entry.size() - open - 2));
    else if (eq != std::string_view::npos)
      unit = Trim(entry.substr(eq + 1));
    const auto known = KnownColumns().find(name);
    if (known == KnownColumns().end() || !recording.has(name)) {
      entries.emplace_back(entry);
      continue;
    }
    const auto factor = known->second.factor.find(unit);
    if (factor == known->second.factor.end()) {
      std::string accepted;
      for (const auto& [u, f] : known->second.factor) accepted += (accepted.empty() ? "" : ", ") + u;
      const std::string where =
          line_no > 0 ? fmt::format("{}:{}:1", recording.source, line_no) : recording.source;
      throw InputError(
          fmt::format("{}: '# units:' metadata: column '{}' in '{}': expected one of {}", where,
                      name, unit, accepted));
    }
    if (factor->second != 1.0) {
      recording.data.col(recording.index_of(name)) *= factor->second;
      converted = true;
    }
    entries.push_back(fmt::format("{} [{}]", name, known->second.si));
  }
  if (!converted) return;
  std::string text;
  for (const auto& e : entries) text += (text.empty() ? "" : ", ") + e;
  line->second = text + " (converted to SI on reading)";
}

}  // namespace internal

std::vector<std::string> UnitSanityWarnings(const Recording& r) {
  std::vector<std::string> warnings;
  if (!r.has("t") || r.rows() < 2) return warnings;
  // The unit whose factor brings `value` [SI] within `limit`, as a hint.
  auto likely = [](double value, double limit) -> std::string {
    for (const auto& [unit, factor] : {std::pair<const char*, double>{"mm", 1e-3},
                                       {"um", 1e-6}, {"nm", 1e-9}})
      if (value * factor <= limit) return unit;
    return "";
  };
  // A MAT or HDF5 file holds no '# units:' line: its fix is the reader's --scale.
  std::error_code ec;
  const bool container = std::filesystem::is_regular_file(r.source, ec) &&
                         DetectFileFormat(r.source) != FileFormat::kText;
  // `unit` a length unit ("mm"), `per` "" for x and "/s" for v.
  auto advice = [&](const std::string& column, const std::string& unit, const char* per) {
    if (unit.empty()) return std::string("check the column's unit");
    if (container)
      return fmt::format("if {} is in {}{}, scale it to m{} with --scale {}={} (a {} file holds "
                         "no '# units:' line)",
                         column, unit, per, per, column,
                         unit == "mm" ? "1e-3" : unit == "um" ? "1e-6" : "1e-9",
                         DescribeFileFormat(r.source));
    return fmt::format(
        "if {} is in {}{}, declare it with a '# units: {}={}{}' line (the reader then converts "
        "it) or scale it to m{}",
        column, unit, per, column, unit, per, per);
  };
  const auto t = r.column("t");
  if (r.has("x")) {
    const auto x = r.column("x");
    const double range = x.maxCoeff() - x.minCoeff();
    if (range > kMaxPlausibleTravel_m)
      warnings.push_back(fmt::format(
          "{}: x spans {:.4g} m, more than the {} m a stage travels: {}", r.source, range,
          kMaxPlausibleTravel_m, advice("x", likely(range, kMaxPlausibleTravel_m), "")));
    double speed = 0;
    for (Eigen::Index k = 0; k + 1 < r.rows(); ++k)
      if (t[k + 1] > t[k]) speed = std::max(speed, std::abs(x[k + 1] - x[k]) / (t[k + 1] - t[k]));
    if (speed > kMaxPlausibleSpeed_mps)
      warnings.push_back(fmt::format(
          "{}: x moves at up to {:.4g} m/s, more than the {} m/s a stage reaches: {}", r.source,
          speed, kMaxPlausibleSpeed_mps,
          advice("x", likely(speed, kMaxPlausibleSpeed_mps), "")));
  }
  if (r.has("v")) {
    const double speed = r.column("v").cwiseAbs().maxCoeff();
    if (speed > kMaxPlausibleSpeed_mps)
      warnings.push_back(fmt::format(
          "{}: |v| reaches {:.4g} m/s, more than the {} m/s a stage reaches: {}", r.source,
          speed, kMaxPlausibleSpeed_mps,
          advice("v", likely(speed, kMaxPlausibleSpeed_mps), "/s")));
  }
  return warnings;
}

}  // namespace sysid
