// The report's reference numbers (sysid/pipeline.hpp, PipelineReference), read before the run so
// that a bad file fails before the long steps and the report reads nothing.
#include <fmt/format.h>

#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/json_text.hpp"
#include "sysid/error.hpp"
#include "sysid/io.hpp"
#include "sysid/pipeline.hpp"

namespace sysid {
namespace {

// `f` reads one top-level key; a value of the wrong type throws InputError at that key.
template <typename Read>
void ReadKey(const nlohmann::json& j, std::string_view text, const std::string& path,
             const std::string& key, const char* expected, Read&& f) {
  if (!j.contains(key)) return;
  try {
    f(j.at(key));
  } catch (const nlohmann::json::exception&) {
    throw InputError(fmt::format("{}:{}: {}: expected {}", path,
                                 internal::JsonKeyPosition(text, key), key, expected));
  } catch (const std::logic_error&) {  // std::stod of a frequency key
    throw InputError(fmt::format("{}:{}: {}: expected {}", path,
                                 internal::JsonKeyPosition(text, key), key, expected));
  }
}

}  // namespace

std::optional<double> PipelineReference::ModelValue(const std::string& name) const {
  if (model)
    for (const auto& [key, value] : *model)
      if (key == name) return value;
  return std::nullopt;
}

PipelineReference ReadPipelineReference(const std::string& path) {
  const std::string text = ReadFile(path);
  const nlohmann::json j = internal::ParseJsonText(text, path);  // positioned, duplicate keys
  if (!j.is_object()) throw InputError(path + ":1:1: expected a JSON object of reference numbers");
  PipelineReference ref;
  ReadKey(j, text, path, "label", "a string",
          [&](const nlohmann::json& v) { ref.label = v.get<std::string>(); });
  ReadKey(j, text, path, "model", "an object of numbers", [&](const nlohmann::json& v) {
    ref.model.emplace();
    for (const auto& [name, value] : v.items()) ref.model->emplace_back(name, value.get<double>());
  });
  ReadKey(j, text, path, "dominance_ratio_bound", "a number",
          [&](const nlohmann::json& v) { ref.dominance_ratio_bound = v.get<double>(); });
  ReadKey(j, text, path, "sweep", "an array of {hidden, epochs, train_mse, test_mse}",
          [&](const nlohmann::json& v) {
            ref.sweep.emplace();
            for (const auto& row : v.get<std::vector<nlohmann::json>>())
              ref.sweep->push_back({row.value("hidden", -1), row.value("epochs", 0),
                                    row.value("train_mse", 0.0), row.value("test_mse", 0.0)});
          });
  ReadKey(j, text, path, "tracking_max_error_mm",
          "an object {\"FREQUENCY\": {\"SCHEME\": max error [mm]}}", [&](const nlohmann::json& v) {
            ref.tracking_max_error_mm.emplace();
            for (const auto& [frequency, schemes] : v.items())
              for (const auto& [scheme, error] : schemes.items())
                ref.tracking_max_error_mm->push_back(
                    {std::stod(frequency), scheme, error.get<double>()});
          });
  return ref;
}

}  // namespace sysid
