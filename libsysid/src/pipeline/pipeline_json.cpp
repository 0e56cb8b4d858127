// JSON summary of a pipeline run (docs/cli.md: pipeline --json): the model, the dominant
// variable, the networks' MSEs, every tracking run and the wall time per step.
#include <nlohmann/json.hpp>
#include <string>

#include "core/json_text.hpp"
#include "sysid/pipeline.hpp"

namespace sysid {

std::string ToJson(const PipelineResult& r, int indent) {
  using Json = nlohmann::ordered_json;
  Json j;
  j["model"] = Json::parse(ModelToJson(r.model, -1));
  j["dominant"] = r.dominance.dominant;
  j["nn_inputs"] = r.nn_inputs;
  j["hidden"] = r.network.hidden_size();
  j["nn_test_mse"] = internal::NumberOrNull(r.network_test_mse);
  if (r.typical) {
    j["typical_train_mse"] = internal::NumberOrNull(r.typical->train_mse);
    j["typical_test_mse"] = internal::NumberOrNull(r.typical_test_mse);
  }
  j["tracking"] = Json::array();
  for (const auto& t : r.tracking)
    j["tracking"].push_back({{"frequency_hz", t.frequency_hz},
                             {"ff", t.scheme},
                             {"max_error_m", t.result.max_error_m},
                             {"rms_error_m", t.result.rms_error_m}});
  if (r.facts) j["facts_required_met"] = r.facts->RequiredMet();
  j["steps"] = Json::object();
  for (const auto& [name, s] : r.step_seconds) j["steps"][name] = s;
  return internal::DumpJson(j, indent);
}

}  // namespace sysid
