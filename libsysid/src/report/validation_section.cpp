// The report's validation table: the final rough model simulated free-run on every held-out
// recording (report_sections.hpp).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "report/report_sections.hpp"
#include "sysid/validate.hpp"

namespace sysid::internal {
namespace {

std::string Verdict(const CorrelationTest& t) {
  if (!t.tested) return "not tested";
  return fmt::format("{} ({}/{} out)", t.pass ? "pass" : "**fail**", t.outside, t.lags.size());
}

}  // namespace

ReportSection ValidationSection(const PipelineResult& result) {
  ReportSection s;
  if (result.validations.empty()) return s;
  namespace fs = std::filesystem;
  s.markdown =
      "\n### The rough model simulated on held-out recordings (validation)\n\n"
      "The final model simulated free-run from each recording's u (none was used to fit it), "
      "scored as MATLAB's compare and resid do (`sysid validate`, docs/validation.md): fit % = "
      "100 (1 - |y - ŷ| / |y - mean y|), `nrmse_std` = RMSE / std y, `nrmse_range` = RMSE / "
      "(max y - min y); the residual's autocorrelation (lags 1..L) and cross-correlation with u "
      "(lags 0..L) against the 99 % band ±2.58/√N. The numbers are in validation.json.\n\n";
  std::vector<std::vector<std::string>> rows;
  nlohmann::ordered_json j;
  j["model"] = "model.json";
  j["recordings"] = nlohmann::ordered_json::array();
  for (const Validation& v : result.validations) {
    const std::string name = fs::path(v.source).stem().string();
    // Pulses alone: a pulse recording's row is its held-out end (the fit took the rest).
    const bool pulse_part = result.inputs.PulsesOnly() &&
                            std::find(result.inputs.pulses.begin(), result.inputs.pulses.end(),
                                      v.source) != result.inputs.pulses.end();
    const std::string label = pulse_part ? name + " (held-out end)" : name;
    j["recordings"].push_back(nlohmann::ordered_json::parse(ToJson(v)));
    for (const OutputValidation& o : v.outputs)
      rows.push_back({label, o.output, fmt::format("{:.4g}", o.scores.fit_percent),
                      fmt::format("{:.4g} {}", o.scores.rmse, o.unit),
                      fmt::format("{:.4g}", o.scores.nrmse_std),
                      fmt::format("{:.4g}", o.scores.nrmse_range), Verdict(o.autocorrelation),
                      Verdict(o.cross_correlation)});
    // The velocity, which the delay and the refinement were fitted on: its trace and its tests.
    for (auto& [file, spec] : ValidationPlots(v, "validate_" + name))
      if (file.find("_v.png") != std::string::npos ||
          file.find("_v_residual_tests.png") != std::string::npos)
        s.plots.push_back({file, spec, label + ": " + spec.title});
  }
  s.markdown += MarkdownTable({"recording", "output", "fit [%]", "RMSE", "nrmse_std", "nrmse_range",
                               "autocorrelation", "cross-correlation u"},
                              rows);
  s.files.push_back({"validation.json", j.dump(2) + "\n"});
  return s;
}

}  // namespace sysid::internal
