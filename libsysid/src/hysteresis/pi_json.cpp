// The Prandtl–Ishlinskii model file: {"kind": "pi"|"gpi"|"rdpi", "thresholds": [V], ...}, the
// keys named as PiParameters' fields so that a rule's error points at its key.
#include <fmt/format.h>

#include <cmath>

#include "core/json_text.hpp"
#include "pi_terms.hpp"
#include "sysid/error.hpp"
#include "sysid/hysteresis.hpp"

namespace sysid {

std::string PrandtlIshlinskiiModel::ToJson(int indent) const { return ToJson(indent, ""); }

std::string PrandtlIshlinskiiModel::ToJson(int indent, const std::string& fit_json) const {
  using internal::NumberOrNull;
  nlohmann::ordered_json j;
  j["kind"] = kind();
  j["units"] = {{"u", "V"}, {"y", "m"}, {"thresholds", "V"}, {"weights", "m/V"},
                {"polynomial", "m/V^j"}, {"rate_weights", "m*s/V^2"}, {"offset_m", "m"}};
  j["thresholds"] = p_.thresholds;
  j["weights"] = p_.weights;
  j["polynomial"] = p_.polynomial;
  if (p_.form == PiForm::kRateDependent) j["rate_weights"] = p_.rate_weights;
  j["offset_m"] = p_.offset_m;
  j["initial_input_v"] = p_.initial_input_v;
  j["initial_state"] = internal::InitialState(p_);
  j["input_min_v"] = p_.input_min_v;
  j["input_max_v"] = p_.input_max_v;
  j["range_margin"] = range_margin_;
  nlohmann::ordered_json table = nlohmann::ordered_json::array();
  for (const auto& q : parameters())
    table.push_back({{"name", q.name}, {"unit", q.unit}, {"value", NumberOrNull(q.value)},
                     {"std_error", NumberOrNull(q.std_error)}});
  j["parameters"] = table;
  if (!fit_json.empty()) j["fit"] = nlohmann::ordered_json::parse(fit_json);
  return internal::DumpJson(j, indent);
}

std::unique_ptr<PrandtlIshlinskiiModel> PrandtlIshlinskiiFromJson(std::string_view text,
                                                                  const std::string& source) {
  const internal::JsonDocument doc(text, source);
  const internal::JsonNode root = doc.Root();
  root.ExpectObject({"kind", "units", "thresholds", "weights", "polynomial", "rate_weights",
                     "offset_m", "initial_input_v", "initial_state", "input_min_v", "input_max_v",
                     "range_margin", "parameters"},
                    {"fit"});
  PiParameters p;
  const internal::JsonNode kind = root.Get("kind");
  const std::string name = kind.String(true);
  if (name != "pi" && name != "gpi" && name != "rdpi") kind.Expected("\"pi\", \"gpi\" or \"rdpi\"");
  p.form = PiFormFromString(name);
  // Sizes are bounded before the arrays are read.
  const internal::JsonNode thresholds = root.Get("thresholds");
  thresholds.ExpectArray();
  if (thresholds.Size() > static_cast<size_t>(kMaxPlayOperators))
    thresholds.Fail(fmt::format("{} operators, more than the bound {} (kMaxPlayOperators)",
                                thresholds.Size(), kMaxPlayOperators));
  p.thresholds = thresholds.Numbers();
  p.weights = root.Get("weights").Numbers(p.thresholds.size());
  p.polynomial = root.Get("polynomial").Numbers();
  if (root.Has("rate_weights")) p.rate_weights = root.Get("rate_weights").Numbers(p.thresholds.size() + 1);
  p.offset_m = root.Get("offset_m").Number();
  if (root.Has("initial_input_v")) p.initial_input_v = root.Get("initial_input_v").Number();
  if (root.Has("initial_state")) p.initial_state = root.Get("initial_state").Numbers(p.thresholds.size());
  p.input_min_v = root.Get("input_min_v").Number();
  p.input_max_v = root.Get("input_max_v").Number();
  double margin = 0.05;
  if (root.Has("range_margin")) margin = root.Get("range_margin").Number(internal::NumberRule::Closed(0, 1));
  std::vector<double> se;
  if (root.Has("parameters")) {
    const internal::JsonNode table = root.Get("parameters");
    table.ExpectArray();
    if (table.Size() > static_cast<size_t>(4 * kMaxPlayOperators))
      table.Fail("more entries than any model has parameters");
    for (size_t i = 0; i < table.Size(); ++i) {
      const internal::JsonNode e = table.Element(i);
      e.ExpectObject({"name", "unit", "value", "std_error"});
      se.push_back(e.Has("std_error") ? e.Get("std_error").NumberOrNaN() : NAN);
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
