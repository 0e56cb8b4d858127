// A recording's shape (samples, duration, columns and their units) as JSON.
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

}  // namespace sysid
