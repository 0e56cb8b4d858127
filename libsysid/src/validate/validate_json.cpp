// JSON of a validation (docs/cli.md: validate --json "recordings" entries).
#include <nlohmann/json.hpp>
#include <string>

#include "core/json_text.hpp"
#include "sysid/validate.hpp"

namespace sysid {
namespace {
using Json = nlohmann::ordered_json;

Json TestJson(const CorrelationTest& t) {
  Json r = Json::array();
  for (Eigen::Index i = 0; i < t.r.size(); ++i) r.push_back(internal::NumberOrNull(t.r[i]));
  return {{"name", t.name},
          {"lags", t.lags},
          {"r", r},
          {"bound", internal::NumberOrNull(t.bound)},
          {"strong_bound", internal::NumberOrNull(t.strong_bound)},
          {"outside", t.outside},
          {"allowed_outside", t.allowed_outside},
          {"max_abs_r", internal::NumberOrNull(t.max_abs_r)},
          {"tested", t.tested},
          {"pass", t.pass},
          {"verdict", t.verdict}};
}
}  // namespace

std::string ToJson(const Validation& v, int indent) {
  Json j;
  j["source"] = v.source;
  j["model"] = v.model_kind;
  j["samples"] = v.t_s.size();
  j["outputs"] = Json::array();
  for (const auto& o : v.outputs)
    j["outputs"].push_back({{"output", o.output},
                            {"unit", o.unit},
                            {"fit_percent", internal::NumberOrNull(o.scores.fit_percent)},
                            {"rmse", internal::NumberOrNull(o.scores.rmse)},
                            {"nrmse_std", internal::NumberOrNull(o.scores.nrmse_std)},
                            {"nrmse_range", internal::NumberOrNull(o.scores.nrmse_range)},
                            {"autocorrelation", TestJson(o.autocorrelation)},
                            {"cross_correlation", TestJson(o.cross_correlation)}});
  return internal::DumpJson(j, indent);
}

}  // namespace sysid
