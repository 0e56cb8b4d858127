// A recording's shape (samples, duration, columns and their units) and its summary (sampling,
// per-column ranges, metadata) as JSON.
#include <fmt/format.h>

#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "core/json_text.hpp"
#include "sysid/io.hpp"

namespace sysid {

std::string ColumnUnit(const std::string& column) {
  static const std::map<std::string, std::string> kUnits = {
      {"t", "s"},       {"u", "V"},     {"u_ff", "V"},        {"x", "m"},
      {"x_ref", "m"},   {"e", "m"},     {"v", "m/s"},         {"v_ref", "m/s"},
      {"a", "m/s^2"},   {"a_ref", "m/s^2"}};
  const auto unit = kUnits.find(column);
  return unit == kUnits.end() ? "1" : unit->second;
}

std::string RecordingShapeToJson(const Recording& r, int indent) {
  nlohmann::ordered_json j;
  j["samples"] = r.rows();
  const Eigen::Index t = r.index_of("t");
  j["duration_s"] = r.rows() > 0 && t >= 0 ? r.data(r.rows() - 1, t) - r.data(0, t) : 0.0;
  j["columns"] = r.names;
  nlohmann::ordered_json units = nlohmann::ordered_json::object();
  for (const auto& n : r.names) units[n] = ColumnUnit(n);
  j["units"] = units;
  return internal::DumpJson(j, indent);
}

std::string RecordingSummaryToJson(const Recording& r, double jitter_tolerance, int indent) {
  nlohmann::ordered_json j;
  j["file"] = r.source;
  j["rows"] = r.rows();
  j["columns"] = r.names;
  const Eigen::Index tc = r.index_of("t");
  const bool timed = tc >= 0 && r.rows() > 0;
  j["duration_s"] = timed ? r.data(r.rows() - 1, tc) - r.data(0, tc) : 0.0;
  j["t_start_s"] = timed ? nlohmann::ordered_json(r.data(0, tc)) : nullptr;
  if (timed && r.rows() >= 2) {
    const SamplingReport s = AnalyzeSampling(r.column("t"), jitter_tolerance);
    j["sample_rate_hz"] = s.sample_rate_hz;
    j["sampling"] = {
        {"nominal_dt_s", s.nominal_dt_s},       {"max_jitter_s", s.max_jitter_s},
        {"rms_jitter_s", s.rms_jitter_s},       {"max_relative_jitter", s.max_relative_jitter},
        {"jitter_tolerance", jitter_tolerance}, {"irregular", s.irregular}};
    if (s.irregular)
      j["sampling"]["warning"] = fmt::format(
          "irregular sampling: interval ending at {} deviates {:.3g} % from the nominal "
          "{:.6g} s; resample with 'sysid derive --resample HZ' or sysid::Resample",
          r.where(s.worst_index + 1), 100 * s.max_relative_jitter, s.nominal_dt_s);
  } else {
    j["sample_rate_hz"] = nullptr;
  }
  nlohmann::ordered_json stats = nlohmann::ordered_json::object();
  for (size_t c = 0; c < r.names.size() && r.rows() > 0; ++c) {
    const auto col = r.data.col(static_cast<Eigen::Index>(c));
    double mean = col.mean();
    // Values near the largest double overflow the sum; each divided by n first cannot.
    if (!std::isfinite(mean)) mean = (col / static_cast<double>(col.size())).sum();
    stats[r.names[c]] = {{"min", col.minCoeff()}, {"max", col.maxCoeff()}, {"mean", mean}};
  }
  j["column_stats"] = stats;
  nlohmann::ordered_json meta = nlohmann::ordered_json::object();
  for (const auto& [k, v] : r.metadata) meta[k] = v;
  j["metadata"] = meta;
  return internal::DumpJson(j, indent);
}

}  // namespace sysid
