#include <nlohmann/json.hpp>
#include <string>

#include "detail/json_text.hpp"
#include "sysid/error.hpp"
#include "sysid/io.hpp"
#include "sysid/model.hpp"

namespace sysid {
FrictionModel ParseModel(std::string_view json_text, const std::string& source) {
  const auto j = detail::ParseJsonText(json_text, source);
  if (!j.is_object())
    throw InputError(source +
                     ":1:1: expected a JSON object with keys a1p, a1n, a2p, a2n, a3, "
                     "tau");
  FrictionModel m;
  struct Field {
    const char* key;
    double* target;
    bool required;
  };
  const Field fields[] = {{"a1p", &m.a1p, true}, {"a1n", &m.a1n, true}, {"a2p", &m.a2p, true},
                          {"a2n", &m.a2n, true}, {"a3", &m.a3, true},   {"tau", &m.tau_s, false}};
  for (const auto& [key, value] : j.items()) {
    // Reports and comments may ride along: "diagnostics", "units", "note", "_anything".
    if (key == "diagnostics" || key == "units" || key == "note" || key == "model" ||
        (!key.empty() && key[0] == '_'))
      continue;
    bool known = false;
    for (const auto& f : fields) known = known || key == f.key;
    if (!known)
      throw InputError(source + ":" + detail::JsonKeyPosition(json_text, key) + ": unknown key '" +
                       key + "' (expected a1p, a1n, a2p, a2n, a3, tau)");
  }
  for (const auto& f : fields) {
    if (!j.contains(f.key)) {
      if (f.required)
        throw InputError(source + ": missing key '" + f.key +
                         "' (a model file needs a1p, "
                         "a1n, a2p, a2n, a3 and optionally tau [s])");
      continue;
    }
    const auto& v = j.at(f.key);
    if (!v.is_number())
      throw InputError(source + ":" + detail::JsonKeyPosition(json_text, f.key) + ": key '" +
                       f.key + "': expected a number, found " + v.type_name());
    *f.target = v.get<double>();
  }
  try {
    m.Validate();
  } catch (const OptionsError& e) {
    throw InputError(source + ": invalid model: " + e.what());
  }
  return m;
}

FrictionModel ReadModel(const std::string& path) { return ParseModel(ReadFile(path), path); }

std::string ModelToJson(const FrictionModel& m, int indent) {
  nlohmann::ordered_json j;
  j["a1p"] = m.a1p;
  j["a1n"] = m.a1n;
  j["a2p"] = m.a2p;
  j["a2n"] = m.a2n;
  j["a3"] = m.a3;
  j["tau"] = m.tau_s;
  j["units"] = {{"a1p", "1/s"},   {"a1n", "1/s"},      {"a2p", "m/s^2"},
                {"a2n", "m/s^2"}, {"a3", "m/(s^2 V)"}, {"tau", "s"}};
  return j.dump(indent) + "\n";
}

void WriteModel(const std::string& path, const FrictionModel& model) {
  WriteFileAtomically(path, ModelToJson(model));
}

}  // namespace sysid
