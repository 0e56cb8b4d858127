// JSON of a validation (docs/cli.md: validate --json "recordings" entries): the described
// fields (Validation::Serialize), with the samples after the model.
#include <nlohmann/json.hpp>
#include <string>

#include "core/json_fields.hpp"
#include "core/json_text.hpp"
#include "sysid/validate.hpp"

namespace sysid {

std::string ToJson(const Validation& v, int indent) {
  nlohmann::ordered_json j;
  const nlohmann::ordered_json fields = internal::WriteFields(v);
  for (auto it = fields.begin(); it != fields.end(); ++it) {
    j[it.key()] = *it;
    if (it.key() == "model") j["samples"] = v.t_s.size();
  }
  return internal::DumpJson(j, indent);
}

}  // namespace sysid
