// The Prandtl–Ishlinskii model file: {"kind": "pi"|"gpi"|"rdpi", "thresholds": [V], ...}, the
// keys named as PiParameters' fields so that a rule's error points at its key.
#include <fmt/format.h>

#include <cmath>

#include "core/json_fields.hpp"
#include "core/json_text.hpp"
#include "hysteresis/hysteresis_json.hpp"
#include "pi_terms.hpp"
#include "sysid/error.hpp"
#include "sysid/hysteresis.hpp"

namespace sysid {

namespace internal {

nlohmann::ordered_json JsonForm<PiForm>::Write(const PiForm& form) { return ToString(form); }
void JsonForm<PiForm>::Read(const JsonNode& node, PiForm& form) {
  const std::string name = node.String(true);
  if (name != "pi" && name != "gpi" && name != "rdpi") node.Expected("\"pi\", \"gpi\" or \"rdpi\"");
  form = PiFormFromString(name);
}

}  // namespace internal

std::string PrandtlIshlinskiiModel::ToJson(int indent) const { return ToJson(indent, ""); }

std::string PrandtlIshlinskiiModel::ToJson(int indent, const std::string& fit_json) const {
  // The described parameters (the initial state written out), the units after the kind, then
  // the model's range margin and its parameters with their standard errors.
  PiParameters p = p_;
  p.initial_state = internal::InitialState(p_);
  const nlohmann::ordered_json fields = internal::WriteFields(p);
  nlohmann::ordered_json j;
  for (auto it = fields.begin(); it != fields.end(); ++it) {
    j[it.key()] = *it;
    if (it.key() == "kind")
      j["units"] = {{"u", "V"}, {"y", "m"}, {"thresholds", "V"}, {"weights", "m/V"},
                    {"polynomial", "m/V^j"}, {"rate_weights", "m*s/V^2"}, {"offset_m", "m"}};
  }
  j["range_margin"] = range_margin_;
  j["parameters"] = internal::JsonForm<std::vector<HysteresisParameter>>::Write(parameters());
  if (!fit_json.empty()) j["fit"] = nlohmann::ordered_json::parse(fit_json);
  return internal::DumpJson(j, indent);
}

std::unique_ptr<PrandtlIshlinskiiModel> PrandtlIshlinskiiFromJson(std::string_view text,
                                                                  const std::string& source) {
  const internal::JsonDocument doc(text, source);
  const internal::JsonNode root = doc.Root();
  // The operators are bounded before any list is read.
  if (root.json().is_object() && root.Has("thresholds")) {
    const internal::JsonNode thresholds = root.Get("thresholds");
    thresholds.ExpectArray();
    if (thresholds.Size() > static_cast<size_t>(kMaxPlayOperators))
      thresholds.Fail(fmt::format("{} operators, more than the bound {} (kMaxPlayOperators)",
                                  thresholds.Size(), kMaxPlayOperators));
  }
  PiParameters p;
  internal::ReadFields(root, p, {"units", "range_margin", "parameters", "fit"});
  const size_t n = p.thresholds.size();
  root.Get("weights").ExpectArray(n);
  if (root.Has("rate_weights")) root.Get("rate_weights").ExpectArray(n + 1);
  if (root.Has("initial_state")) root.Get("initial_state").ExpectArray(n);
  double margin = 0.05;
  if (root.Has("range_margin")) margin = root.Get("range_margin").Number(internal::NumberRule::Closed(0, 1));
  std::vector<double> se;
  if (root.Has("parameters")) {
    const internal::JsonNode table = root.Get("parameters");
    table.ExpectArray();
    if (table.Size() > static_cast<size_t>(4 * kMaxPlayOperators))
      table.Fail("more entries than any model has parameters");
    for (size_t i = 0; i < table.Size(); ++i) {
      HysteresisParameter q;
      q.std_error = NAN;  // an entry without one has none
      internal::ReadFields(table.Element(i), q);
      se.push_back(q.std_error);
    }
  }
  std::unique_ptr<PrandtlIshlinskiiModel> model;
  internal::ValidateOptions(doc, [&] {
    model = std::make_unique<PrandtlIshlinskiiModel>(p, std::vector<double>{}, margin);
  });
  if (!se.empty()) {
    if (se.size() != model->parameters().size())
      root.Get("parameters").Fail(fmt::format("expected {} entries (one per parameter), found {}",
                                              model->parameters().size(), se.size()));
    model = std::make_unique<PrandtlIshlinskiiModel>(p, se, margin);
  }
  return model;
}

}  // namespace sysid
